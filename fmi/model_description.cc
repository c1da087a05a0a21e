#include "fmi/model_description.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>

#include <tinyxml2.h>

#include "diagrams/units.h"

namespace mechflow::fmi {
namespace {

// the shortest decimal that reads back as v: 9.81, not 9.8100000000000005
std::string Number(double v) {
  char text[32];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, v);
    if (std::strtod(text, nullptr) == v) break;
  }
  return text;
}

// <Unit name="N/mm"><BaseUnit kg="1" s="-2" factor="1000"/></Unit>: the SI
// exponents when they are whole numbers (UDUNITS may give halves)
void WriteUnit(tinyxml2::XMLPrinter* p, const std::string& name) {
  p->OpenElement("Unit");
  p->PushAttribute("name", name.c_str());
  std::string error;
  if (const std::optional<diagrams::Unit> unit = diagrams::ParseUnit(name, &error)) {
    static const char* const kBases[] = {"kg", "m", "s", "A", "K", "mol", "cd", "rad"};
    bool whole = true;
    for (const double e : unit->dimension.exponents) whole &= e == std::floor(e);
    if (whole) {
      p->OpenElement("BaseUnit");
      for (int b = 0; b < diagrams::Dimension::kBases; ++b)
        if (const double e = unit->dimension.exponents[b]; e != 0.0)
          p->PushAttribute(kBases[b], static_cast<int>(e));
      if (unit->to_si != 1.0) p->PushAttribute("factor", Number(unit->to_si).c_str());
      p->CloseElement();
    }
  }
  p->CloseElement();
}

const char* CausalityName(Causality c) {
  switch (c) {
    case Causality::kOutput: return "output";
    case Causality::kInput: return "input";
    case Causality::kParameter: return "parameter";
  }
  return "";
}

}  // namespace

std::string ModelDescriptionXml(const diagrams::LoadedDiagram& loaded, const std::vector<Variable>& variables,
                                const DescriptionInfo& info) {
  tinyxml2::XMLPrinter p;
  p.PushHeader(false, true);
  p.OpenElement("fmiModelDescription");
  p.PushAttribute("fmiVersion", "2.0");
  p.PushAttribute("modelName", loaded.description.name.c_str());
  p.PushAttribute("guid", info.guid.c_str());
  if (!loaded.description.comment.empty()) p.PushAttribute("description", loaded.description.comment.c_str());
  p.PushAttribute("generationTool", "mechflow");
  p.PushAttribute("variableNamingConvention", "flat");
  p.PushAttribute("numberOfEventIndicators", 0);

  p.OpenElement("CoSimulation");
  p.PushAttribute("modelIdentifier", info.model_identifier.c_str());
  p.PushAttribute("needsExecutionTool", "false");
  p.PushAttribute("canHandleVariableCommunicationStepSize", "true");
  p.PushAttribute("canInterpolateInputs", "false");
  p.PushAttribute("maxOutputDerivativeOrder", 0);
  p.PushAttribute("canRunAsynchronuously", "false");  // the standard's spelling
  p.PushAttribute("canBeInstantiatedOnlyOncePerProcess", "false");
  p.PushAttribute("canNotUseMemoryManagementFunctions", "true");
  p.PushAttribute("canGetAndSetFMUstate", "false");
  p.PushAttribute("canSerializeFMUstate", "false");
  p.PushAttribute("providesDirectionalDerivative", "false");
  p.CloseElement();

  std::set<std::string> units;
  for (const Variable& v : variables)
    if (!v.unit.empty()) units.insert(v.unit);
  if (!units.empty()) {
    p.OpenElement("UnitDefinitions");
    for (const std::string& u : units) WriteUnit(&p, u);
    p.CloseElement();
  }

  p.OpenElement("LogCategories");
  for (const char* category : {"logStatusDiscard", "logStatusError"}) {
    p.OpenElement("Category");
    p.PushAttribute("name", category);
    p.CloseElement();
  }
  p.CloseElement();

  const blocks::SolverOptions& s = loaded.solver;
  p.OpenElement("DefaultExperiment");
  p.PushAttribute("startTime", Number(s.t_start).c_str());
  p.PushAttribute("stopTime", Number(s.t_end).c_str());
  p.PushAttribute("tolerance", Number(s.rtol).c_str());
  const double interval = s.output_interval > 0.0 ? s.output_interval : (s.t_end - s.t_start) / 1000.0;
  p.PushAttribute("stepSize", Number(interval).c_str());
  p.CloseElement();

  p.OpenElement("ModelVariables");
  for (const Variable& v : variables) {
    p.OpenElement("ScalarVariable");
    p.PushAttribute("name", v.name.c_str());
    p.PushAttribute("valueReference", v.value_reference);
    if (!v.description.empty()) p.PushAttribute("description", v.description.c_str());
    p.PushAttribute("causality", CausalityName(v.causality));
    // outputs and inputs change continuously; parameters are fixed: they are
    // applied when the run starts, so changing one later would do nothing
    p.PushAttribute("variability", v.causality == Causality::kParameter ? "fixed" : "continuous");
    if (v.causality == Causality::kParameter) p.PushAttribute("initial", "exact");
    p.OpenElement("Real");
    if (!v.unit.empty()) p.PushAttribute("unit", v.unit.c_str());
    if (v.causality != Causality::kOutput) p.PushAttribute("start", Number(v.start).c_str());
    p.CloseElement();
    p.CloseElement();
  }
  p.CloseElement();

  // ModelStructure: index is the 1-based position in ModelVariables
  std::vector<unsigned> input_position;
  for (std::size_t k = 0; k < variables.size(); ++k)
    if (variables[k].causality == Causality::kInput) input_position.push_back(static_cast<unsigned>(k + 1));
  p.OpenElement("ModelStructure");
  p.OpenElement("Outputs");
  for (std::size_t k = 0; k < variables.size(); ++k) {
    const Variable& v = variables[k];
    if (v.causality != Causality::kOutput) continue;
    p.OpenElement("Unknown");
    p.PushAttribute("index", static_cast<unsigned>(k + 1));
    std::string deps, kinds;
    for (const int i : v.inputs) {
      deps += (deps.empty() ? "" : " ") + std::to_string(input_position[i]);
      kinds += kinds.empty() ? "dependent" : " dependent";
    }
    p.PushAttribute("dependencies", deps.c_str());
    if (!deps.empty()) p.PushAttribute("dependenciesKind", kinds.c_str());
    p.CloseElement();
  }
  p.CloseElement();
  // every output is calculated at initialisation, from every input and parameter
  p.OpenElement("InitialUnknowns");
  for (std::size_t k = 0; k < variables.size(); ++k) {
    if (variables[k].causality != Causality::kOutput) continue;
    p.OpenElement("Unknown");
    p.PushAttribute("index", static_cast<unsigned>(k + 1));
    p.CloseElement();
  }
  p.CloseElement();
  p.CloseElement();

  p.CloseElement();
  return p.CStr();
}

}  // namespace mechflow::fmi
