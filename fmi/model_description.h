#pragma once
// modelDescription.xml of an exported FMU (FMI 2.0, co-simulation): the
// variables (fmi/variables.h), their units, the default experiment from
// <solver> and <output interval>, and which inputs each output depends on.

#include <string>
#include <vector>

#include "diagrams/loader.h"
#include "fmi/variables.h"

namespace mechflow::fmi {

struct DescriptionInfo {
  std::string model_identifier;  // the binary's name: binaries/linux64/IDENTIFIER.so
  std::string guid;
};

std::string ModelDescriptionXml(const diagrams::LoadedDiagram& loaded, const std::vector<Variable>& variables,
                                const DescriptionInfo& info);

}  // namespace mechflow::fmi
