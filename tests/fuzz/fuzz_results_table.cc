// Fuzz target: a results CSV's text as `mechflow psd` reads it (quoted
// fields, a byte-order mark, strictly rising times), asking for the columns
// "x" and "y".

#include "run/results_table.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

void ReadColumns(const std::string& text) { mechflow::run::ReadResultsColumns(text, "fuzz.csv", {"x", "y"}); }

}  // namespace

MECHFLOW_FUZZ_TARGET(ReadColumns)
