#pragma once
// The variables an exported FMU shows, taken from a loaded diagram: the
// exporter writes them into modelDescription.xml and the FMU's instance
// finds them again from the same diagram, so both number them alike.
//
//   outputs     every logged column (<log>), in its column's unit
//   inputs      every top-level <input>, in its unit
//   parameters  every identifier defined by a number (fixed: applied when
//               the run starts), in the unit of its definition; not those a
//               mechanism's <input> overwrites at every evaluation
// Value references are 1, 2, ... in that order.

#include <string>
#include <vector>

#include "diagrams/loader.h"

namespace mechflow::fmi {

enum class Causality { kOutput, kInput, kParameter };

struct Variable {
  std::string name;
  unsigned value_reference = 0;
  Causality causality = Causality::kOutput;
  std::string unit;         // "" none
  std::string description;
  double start = 0.0;       // inputs and parameters, in `unit`
  int index = 0;            // output: its column (time is 0); input: of LoadedDiagram::inputs; parameter: identifier
  // outputs: the inputs (indices into LoadedDiagram::inputs) it depends on at
  // the same instant, through blocks with direct feedthrough
  std::vector<int> inputs;
};

// Throws InputError when two variables would share a name.
std::vector<Variable> CollectVariables(const diagrams::LoadedDiagram& loaded);

}  // namespace mechflow::fmi
