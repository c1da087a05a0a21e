// Fuzz target: Lua code from a diagram, in the three places it can be --
// an expression block's expression, a Lua block's code, a control script --
// loaded and run for a few output steps. The first byte chooses the place;
// the rest is the code.

#include <string>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"
#include "tests/fuzz/fuzz_target.h"

namespace {

// Text as the value of an XML attribute in double quotes.
std::string Attribute(const std::string& text) {
  std::string out;
  for (const char c : text) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

void LoadAndRun(const std::string& input) {
  if (input.empty()) return;
  const std::string code = input.substr(1);
  std::string blocks, script;
  switch (static_cast<unsigned char>(input[0]) % 3) {
    case 0:
      blocks = "<block type=\"expression\" name=\"f\" inputs=\"u\" expr=\"" + Attribute(code) + "\"/>";
      break;
    case 1:
      if (code.find("]]>") != std::string::npos) return;
      blocks = "<block type=\"lua\" name=\"f\" inputs=\"u\" outputs=\"y\" states=\"x\" initial=\"1\" "
               "feedthrough=\"y:u\"><![CDATA[" + code + "]]></block>";
      break;
    default:
      if (code.find("]]>") != std::string::npos) return;
      blocks = "<block type=\"gain\" name=\"f\" k=\"2\"/>";
      script = "<script><![CDATA[" + code + "]]></script>";
  }
  const std::string xml = "<diagram name=\"fuzz\"><identifiers><identifier name=\"k\" value=\"2\"/></identifiers>"
                          "<blocks><block type=\"sine\" name=\"s\"/>" + blocks + "</blocks>"
                          "<connections><connect from=\"s.y\" to=\"f.u\"/></connections>" + script +
                          "<solver t_end=\"0.02\"/><output interval=\"0.01\"/></diagram>";
  mechflow::diagrams::LoadedDiagram loaded =
      mechflow::diagrams::LoadDiagramDescription(mechflow::diagrams::ReadDiagramText(xml, "fuzz.xml"));
  mechflow::blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  sim.SetControl(loaded.control.get());
  sim.Run();
}

}  // namespace

MECHFLOW_FUZZ_TARGET(LoadAndRun)
