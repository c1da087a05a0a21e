#pragma once
// Loader: turns a diagram file into everything a run needs.
//
//   read XML (shape checked)  ->  identifiers (overrides applied, evaluated top
//   to bottom)  ->  blocks (parameters checked against the block type and
//   evaluated)  ->  connections  ->  Build() (schedule, loops)  ->  solver and
//   output settings, logged signals.
//
// Every error is an InputError naming file:line.

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "blocks/framework/block_factory.h"
#include "blocks/framework/diagram.h"
#include "blocks/solver/simulator.h"
#include "blocks/support/input_file.h"
#include "diagrams/description.h"
#include "scripting/control_script.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

namespace mechflow::diagrams {

struct LoadOptions {
  std::vector<std::string> variants;                      // --variant NAME, applied in order
  std::vector<std::pair<std::string, double>> overrides;  // --set NAME=VALUE, in order, after the variants
  // --set NAME=EXPR (an expression of identifiers), in order, after the numbers
  std::vector<std::pair<std::string, std::string>> expression_overrides;
  std::optional<double> t_end;                            // --t-end
  std::optional<double> rtol, atol, interval;             // --rtol, --atol, --interval
  std::optional<std::string> results;                     // --results NAME (the CSV file)
  bool unsafe_lua = false;
  // --allow-read DIR: folders whose trees the files the diagram names may lie
  // in, besides its own folder's (blocks/support/input_file.h)
  std::vector<std::string> allow_read;
  // --library DIR: folders subsystem and part files are looked up in when
  // they are not beside the file that names them
  std::vector<std::string> library;

  bool operator==(const LoadOptions&) const = default;
};

// Logged columns shown in one plot panel.
struct PlotGroup {
  std::string name;
  std::vector<int> columns;  // indices into the results' columns
  // The axis label: the name, with " [unit]" added when every column has
  // that unit and the name gives none.
  std::string axis_label;
};

// <spectrum>: the PSD of a logged column after the run (cli/psd_output.h).
struct SpectrumRequest {
  std::string column;      // a column of the results
  int segment = 0;         // 0: the default
  double overlap = 0.5;
  std::string window = "hann";
  double from = -1e300;    // [s]
  int peaks = 5;
  double max_frequency = 0.0;  // > 0: the plot ends there [Hz]
  std::string origin;      // file:line
};

// <xy>: a panel of the plot with one logged column against another.
struct XYPlotRequest {
  std::string title, x_label, y_label;
  std::vector<std::pair<int, int>> curves;  // (x column, y column) of the results
};

// A top-level <input>: a held value (blocks/library/held_input.h) that a
// co-simulation sets; its block is `block` of the diagram.
struct DiagramInput {
  std::string name;     // as written, the block's name
  int block = -1;
  std::string unit;     // as written ("" SI)
  double to_si = 1.0;   // a value in `unit` times this is SI
  double start = 0.0;   // SI
  std::string comment;
  std::string origin;   // file:line
};

struct LoadedDiagram {
  DiagramDescription description;
  // declared before the diagram: blocks may hold compiled Lua, so Lua goes last
  std::unique_ptr<scripting::LuaState> lua;
  std::unique_ptr<scripting::IdentifierTable> identifiers;
  std::unique_ptr<blocks::Diagram> diagram;
  // the <script>, if any (refers to the Lua state and the diagram; declared
  // after them, so it goes first); give it to the simulator with SetControl
  std::unique_ptr<scripting::ControlScript> control;
  blocks::SolverOptions solver;
  std::vector<DiagramInput> inputs;       // the <input>s, in file order
  std::vector<blocks::SignalRef> logged;  // in column order; name = column label
  // per results column, time ("s") first; "" unknown. A column's values are
  // in its unit: the <log>'s (converted from SI), else the signal's own.
  std::vector<std::string> units;
  // "file:line: warning: ..." found while loading (units that disagree)
  std::vector<std::string> warnings;
  std::vector<PlotGroup> groups;
  std::vector<blocks::ReportRequest> reports;  // <report>s, signals resolved
  std::vector<SpectrumRequest> spectra;        // <spectrum>s, columns checked
  std::vector<XYPlotRequest> xy_plots;         // <xy>s, panels after the time ones
  std::string csv_file;   // relative to the output folder; never empty
  std::string plot_file;  // relative to the output folder; empty: no plot
  std::string animation_file;  // <output animation=...>: relative to the output folder; empty: none
  std::string gltf_file;       // <output gltf=...>: the same as glTF binary (.glb)
  std::optional<blocks::ReadPolicy> reads;  // where files the diagram names may be read from
};

LoadedDiagram LoadDiagram(const std::string& path, const LoadOptions& options = {});
LoadedDiagram LoadDiagramDescription(DiagramDescription description, const LoadOptions& options = {});

// The registry with every block type a diagram may use.
void RegisterAllBlocks(blocks::BlockRegistry* registry, scripting::LuaState* lua,
                       const scripting::IdentifierTable* identifiers);

}  // namespace mechflow::diagrams
