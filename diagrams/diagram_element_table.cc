// The diagram-level half of the element table (diagrams/element_table.h):
// FORMAT.md's <diagram>, identifiers, variants, blocks, connections, solver
// and output, attribute by attribute.

#include "diagrams/element_table.h"

namespace mechflow::diagrams {
std::vector<ElementSpec> DiagramElementSpecs() {
  const AttributeSpec comment = Opt("comment", "", "", "free text");
  std::vector<AttributeSpec> report = {};
  for (const char* kind : {"peak", "min", "peak_abs", "mean", "rms", "integral", "final", "crossing", "period"})
    report.push_back(Opt(kind, "", "", std::string("the ") + kind + " of this signal (one figure per <report>)"));
  report.push_back(Opt("level", "0", "", "the level of crossing and period (needed by crossing)"));
  report.push_back(Opt("label", "e.g. peak of SIGNAL", "", "the figure's name"));
  report.push_back(Opt("unit", "SI", "", "the unit the figure is printed in"));
  report.push_back(Opt("index", "", "", "0-based element of a vector signal (needed then)"));
  return {
      {"diagram",
       "the file's root",
       {Opt("name", "the file's name", "", "the diagram's name (results NAME.csv)"), comment},
       {"identifiers", "input", "variants", "mechanism", "blocks", "connections", "solver", "output", "script"}},
      {"diagram input",
       "a value set from outside (an FMU's input; mechflow run holds its start value): a signal source NAME",
       {Req("name", "", "the signal's name, as a block's"), Opt("unit", "SI", "", "the unit start is written in"),
        Opt("start", "0", "", "its value until it is set"), comment}},
      {"script", "a control script (Lua), as content or a file", {Opt("src", "", "", "a .lua file instead of content")}},
      {"identifiers", "the diagram's named values", {}, {"identifier"}},
      {"identifier",
       "a named value: a number or an expression of identifiers",
       {Req("name", "", "the name"), Req("value", "", "a number or expression"), comment,
        Opt("unit", "SI", "", "the unit the value is written in")}},
      {"variants", "a group of alternative settings", {Req("name", "", "the group's name"), comment}, {"variant"}},
      {"variant", "one alternative (--variant NAME)", {Req("name", "", "the variant's name"), comment}, {"set"}},
      {"set",
       "an identifier's value in a variant",
       {Req("identifier", "", "the identifier"), Req("value", "", "its value in this variant")}},
      {"blocks", "the signal blocks", {}, {"block"}},
      {"block",
       "a signal block; its other attributes are its type's parameters (mechflow help TYPE); "
       "type=\"subsystem\" takes src=, count= and <param> children",
       {Req("type", "", "the block type"), Req("name", "", "the block's name")},
       {"param"},
       "",
       {},
       true},
      {"subsystem",
       "the root of a subsystem file: blocks with ports, used as <block type=\"subsystem\" src=...>",
       {Req("name", "", "the subsystem's name"), comment},
       {"parameter", "input", "output", "identifiers", "mechanism", "blocks", "connections"}},
      {"parameter",
       "a value a subsystem or part takes from where it is used (<param>)",
       {Req("name", "", "the name inside"), Opt("default", "", "", "its value when no <param> gives one"),
        Opt("unit", "SI", "", "the unit a number is written in"), comment}},
      {"subsystem input",
       "an input port of a subsystem (<input> in a subsystem file)",
       {Req("name", "", "the port's name"), Opt("width", "1", "", "the number of values it carries")}},
      {"subsystem output", "an output port of a subsystem (<output> in a subsystem file)",
       {Req("name", "", "the port's name")}},
      {"param",
       "the value of a subsystem's or part's <parameter> where it is used",
       {Req("name", "", "the parameter"), Req("value", "", "a number or an expression of the including scope")}},
      {"connections", "the signal connections", {}, {"connect"}},
      {"connect",
       "a connection from an output port to an input port",
       {Req("from", "", "block.port (or block)"), Req("to", "", "block.port (or block)")}},
      {"solver",
       "CVODE BDF settings",
       {Opt("t_start", "0", "s", "start time"), Opt("t_end", "1", "s", "end time, > t_start"),
        Opt("rtol", "1e-6", "", "relative tolerance, > 0"), Opt("atol", "1e-8", "", "absolute tolerance, > 0"),
        Opt("max_step", "0 (none)", "s", "largest step"), Opt("initial_step", "0 (automatic)", "s", "first step"),
        Opt("max_steps", "500000", "", "steps allowed between two output times"),
        Opt("linear_solver", "auto", "", "dense, sparse, krylov or auto"),
        Opt("jacobian", "auto", "", "analytic, difference or auto")}},
      {"output",
       "what a run writes",
       {Opt("interval", "(t_end - t_start) / 1000", "s", "output grid step, > 0"),
        Opt("csv", "NAME.csv", "", "results file (a plain file name)"),
        Opt("plot", "", "", ".png or .svg, drawn by gnuplot"),
        Opt("animation", "", "", "an HTML animation file"), Opt("gltf", "", "", "a glTF binary file")},
       {"log", "report", "spectrum", "xy"}},
      {"log",
       "a logged signal: columns of the results and a plot curve",
       {Req("signal", "", "block.port or block"), Opt("group", "the signal name", "", "plot panel"),
        Opt("label", "the signal name", "", "column name"), Opt("unit", "SI", "", "the column's unit")}},
      {"report", "one figure of one signal over the run, with its time", report},
      {"spectrum",
       "the power spectral density of a logged column (Welch)",
       {Req("signal", "", "the column's name"),
        Opt("segment", "a power of two up to a quarter of the rows", "", "samples per segment"),
        Opt("overlap", "0.5", "", "0 to 0.99"), Opt("window", "hann", "", "hann or rectangular"),
        Opt("from", "t_start", "s", "leaves out the rows before"), Opt("peaks", "5", "", "peaks printed"),
        Opt("max_frequency", "", "Hz", "ends the plot's axis")}},
      {"xy",
       "an x-y panel of the plot",
       {Req("curves", "", "X:Y pairs of logged columns"), Opt("title", "the first pair", "", "panel title"),
        Opt("x_label", "the first X", "", "x axis label"), Opt("y_label", "the first Y", "", "y axis label")}},
  };
}

}  // namespace mechflow::diagrams
