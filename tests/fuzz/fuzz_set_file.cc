// Fuzz target: a --set-file's text (NAME=VALUE lines, '#' comments, a
// byte-order mark) as the command line reads it. A bad line is a usage
// error, which a user can cause, so it is no finding.

#include "cli/arguments.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

void ReadSets(const std::string& text) {
  mechflow::cli::Arguments arguments;
  try {
    mechflow::cli::ReadSetFile(text, "fuzz.set", &arguments);
  } catch (const mechflow::cli::UsageError&) {
  }
}

}  // namespace

MECHFLOW_FUZZ_TARGET(ReadSets)
