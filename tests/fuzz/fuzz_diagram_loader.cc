// Fuzz target: a diagram's XML text through the whole loader -- reading,
// identifiers and expressions, mechanism compilation, block parameters,
// connections, schedule and loops -- without running it.

#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

void LoadDiagramText(const std::string& text) {
  mechflow::diagrams::LoadDiagramDescription(mechflow::diagrams::ReadDiagramText(text, "fuzz.xml"));
}

}  // namespace

MECHFLOW_FUZZ_TARGET(LoadDiagramText)
