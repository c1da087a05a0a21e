#pragma once
// Helpers for tests: load a diagram from inline XML and run it.

#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"
#include "mech/errors.h"

namespace mechflow::testing {

struct XmlRun {
  diagrams::LoadedDiagram loaded;
  std::unique_ptr<blocks::Simulator> sim;
  blocks::RunOutcome outcome;

  std::vector<double> Column(const std::string& name) const {
    const int c = sim->results().FindColumn(name);
    if (c < 0) throw std::runtime_error("no column " + name);
    return sim->results().Column(c);
  }
};

// The text of diagrams/examples/`example` ("" when it cannot be read).
inline std::string ReadExample(const std::string& example) {
  std::ifstream in(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/" + example);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// `xml` with every contact's regularised friction (its v_eps) replaced by exact stick.
inline std::string WithExactStick(std::string xml) {
  for (std::size_t at; (at = xml.find(" v_eps=\"")) != std::string::npos;)
    xml.replace(at, xml.find('"', at + 8) + 1 - at, " stick=\"exact\"");
  return xml;
}

// Loads `xml` (named test.xml in messages) and builds it; throws what the loader throws.
inline diagrams::LoadedDiagram LoadXml(const std::string& xml, const diagrams::LoadOptions& options = {}) {
  return diagrams::LoadDiagramDescription(diagrams::ReadDiagramText(xml, "test.xml"), options);
}

// Loads and runs a description with its reports and control script.
inline XmlRun RunDescription(diagrams::DiagramDescription description, const diagrams::LoadOptions& options = {}) {
  XmlRun run{diagrams::LoadDiagramDescription(std::move(description), options), nullptr, {}};
  run.sim = std::make_unique<blocks::Simulator>(*run.loaded.diagram, run.loaded.solver, run.loaded.logged);
  run.sim->SetReports(run.loaded.reports);
  run.sim->SetControl(run.loaded.control.get());
  run.outcome = run.sim->Run();
  return run;
}

inline XmlRun RunXml(const std::string& xml, const diagrams::LoadOptions& options = {}) {
  return RunDescription(diagrams::ReadDiagramText(xml, "test.xml"), options);
}

// The message of the InputError `f` throws, or "" if it throws none.
template <typename F>
std::string InputErrorOf(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace mechflow::testing
