#include "cli/report.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "blocks/library/friction_from_normal_force.h"
#include "blocks/library/mechanism_block.h"
#include "blocks/outputs/csv.h"
#include "blocks/solver/analytic_jacobian.h"
#include "blocks/solver/crossing_events.h"
#include "blocks/support/excerpt.h"
#include "blocks/support/input_file.h"
#include "blocks/support/message_number.h"
#include "blocks/support/suggest.h"
#include "cli/instance_tree.h"
#include "diagrams/units.h"
#include "mech/mechanism.h"
#include "scripting/global_reads.h"
#include "scripting/instance_path.h"

namespace mechflow::cli {
namespace {

using blocks::Formatted;

// A number for people to read: a negative zero (a product or a sign
// flipped at rest) is written 0, never "-0".
// Text as DOT shows it. Graphviz reads a quoted string keeping every
// backslash but \" (a quote); a label then turns \\ into a backslash and
// drops the backslash of other escapes. So a name's backslashes are doubled
// (none may escape the closing quote, as in a diagram named "x\"), quotes
// escaped, and control characters and bytes that are not UTF-8 written \xNN.
std::string DotText(const std::string& s, const char* also_escaped = "") {
  std::string out;
  for (const char c : blocks::Excerpt(s, std::string::npos)) {
    if (c == '\\' || c == '"' || (c != '\0' && std::strchr(also_escaped, c))) out += '\\';
    out += c;
  }
  return out;
}

// A quoted DOT string of text that is already DOT (labels with their escapes).
std::string DotQuote(const std::string& dot) { return "\"" + dot + "\""; }

// Text inside a record label: also the characters that structure a record escaped.
std::string RecordText(const std::string& s) { return DotText(s, "{}|<> "); }

}  // namespace

void PrintScriptChanges(const scripting::ControlScript& script, const scripting::IdentifierTable& identifiers,
                        std::ostream& out) {
  out << "control script: " << script.callbacks() << " callbacks";
  const auto& changes = script.changes();
  if (changes.empty()) {
    out << ", no identifier changed\n";
    return;
  }
  out << ", " << changes.size() << " identifier changes:\n";
  for (int id = 0; id < identifiers.size(); ++id) {
    const scripting::ControlScript::Change *first = nullptr, *last = nullptr;
    long count = 0;
    for (const auto& c : changes) {
      if (c.identifier != id) continue;
      if (!first) first = &c;
      last = &c;
      ++count;
    }
    if (!first) continue;
    out << "  " << identifiers.spelling(id) << ": " << count << " times, first " << Formatted("%g", first->value)
        << " at t = " << Formatted("%g", first->time) << " s, last " << Formatted("%g", last->value) << " at t = "
        << Formatted("%g", last->time) << " s\n";
  }
}

void WriteScriptChanges(const scripting::ControlScript& script, const scripting::IdentifierTable& identifiers,
                        std::ostream& file) {
  file << "time,identifier,value\n";
  for (const auto& c : script.changes())
    file << blocks::CsvNumber(c.time) << "," << blocks::CsvField(identifiers.spelling(c.identifier)) << ","
         << blocks::CsvNumber(c.value) << "\n";
}

void PrintStats(const blocks::SolverStats& s, std::ostream& out) {
  out << "solver: " << s.steps << " steps, " << s.rhs_evals << " RHS evaluations (+" << s.jac_rhs_evals
      << " for Jacobians), " << s.jac_evals << " Jacobian evaluations\n"
      << "        " << s.newton_iters << " Newton iterations, " << s.newton_failures << " Newton failures, "
      << s.error_test_failures << " error-test failures\n"
      << "        " << s.events << " events, " << s.sample_hits << " sample hits, " << s.reinits
      << " re-initialisations, " << s.root_evals << " zero-crossing evaluations\n";
  if (s.restarts > 0)
    out << "        " << s.restarts << " restarts after repeated error-test or convergence failures\n";
  const char* from = s.analytic_jacobian ? "analytic" : "difference quotients";
  if (s.krylov)
    out << "        Krylov (GMRES): " << s.linear_iters << " linear iterations, no Jacobian\n";
  else if (s.sparse && s.analytic_jacobian)
    out << "        sparse Jacobian (KLU), analytic: " << s.nonzeros << " nonzeros\n";
  else if (s.sparse)
    out << "        sparse Jacobian (KLU): " << s.colours << " colours, " << s.nonzeros << " nonzeros\n";
  else
    out << "        dense Jacobian, " << from << "\n";
  // only diagrams with a block on a manifold project
  if (s.projections > 0 || s.projection_failures > 0)
    out << "        " << s.projections << " projections, " << s.projection_failures << " projection failures\n";
}

void PrintSignalRanges(const blocks::Results& r, std::ostream& out) {
  if (r.num_rows() == 0 || r.num_columns() < 2) return;
  size_t width = 6;
  for (int c = 1; c < r.num_columns(); ++c) width = std::max(width, r.columns()[c].size());
  out << "signal" << std::string(width - 6, ' ') << "           min    at t [s]            max    at t [s]\n";
  for (int c = 1; c < r.num_columns(); ++c) {
    const blocks::ColumnRange& range = r.range(c);
    out << r.columns()[c] << std::string(width - r.columns()[c].size(), ' ') << Formatted(" %14.6g", range.min)
        << Formatted(" %11.6g", range.min_time) << Formatted(" %14.6g", range.max) << Formatted(" %11.6g", range.max_time)
        << "\n";
  }
}

void PrintFigures(const std::vector<blocks::ReportFigure>& figures, bool finished, std::ostream& out) {
  for (const blocks::ReportFigure& f : figures) {
    out << f.label << ": ";
    const char* upto = finished ? "" : " (up to the failure)";
    if (!f.found) {
      out << (f.kind == blocks::ReportKind::kCrossing ? "the level is never reached"
              : f.kind == blocks::ReportKind::kPeriod ? "fewer than two upward crossings of the level"
                                                     : "not found (the run took no step)")
          << upto << "\n";
      continue;
    }
    if (f.kind == blocks::ReportKind::kCrossing) {
      out << "reached at t = " << Formatted("%.9g", f.value) << " " << (f.unit.empty() ? "s" : f.unit) << upto
          << "\n";  // the time in the report's unit
      continue;
    }
    const bool over_run = !blocks::IsExtremum(f.kind) && f.kind != blocks::ReportKind::kPeriod;
    out << Formatted("%.6g", f.value) << (f.unit.empty() ? "" : " " + f.unit) << (over_run ? " over the run to t = " : " at t = ")
        << Formatted("%.6g", f.time) << " s" << upto << "\n";
  }
}

void PrintEventLog(const blocks::Diagram& diagram, const std::vector<blocks::EventRecord>& events,
                   std::ostream& out) {
  for (const blocks::EventRecord& e : events)
    out << "event: t = " << Formatted("%.9g", e.time) << " s: " << blocks::EventName(diagram, e) << "\n";
}

void PrintEventWarnings(const blocks::Diagram& diagram, const std::vector<blocks::EventRecord>& events,
                        std::ostream& out) {
  std::set<std::pair<int, int>> warned;  // (block, element): once each
  for (const blocks::EventRecord& e : events) {
    const auto* block = dynamic_cast<const blocks::MechanismBlock*>(&diagram.block(e.block));
    if (!block) continue;
    const mech::Mechanism& m = block->mechanism();
    for (int i = 0; i < m.num_elements(); ++i) {
      const int local = e.crossing - m.crossing_offset(i);
      if (local < 0 || local >= m.element(i).num_crossings()) continue;
      const std::string warning = m.element(i).CrossingWarning(local, e.direction);
      if (warning.empty() || !warned.insert({e.block, i}).second) continue;
      out << "warning: t = " << Formatted("%.6g", e.time) << " s: " << m.element(i).origin() << ": "
          << block->name() << "." << m.element(i).name() << ": " << warning << "\n";
    }
  }
}

void PrintRunWarnings(const blocks::Diagram& diagram, const blocks::Context& run, std::ostream& out) {
  for (int b = 0; b < diagram.num_blocks(); ++b)
    if (const auto* friction = dynamic_cast<const blocks::FrictionFromNormalForceBlock*>(&diagram.block(b)))
      if (const std::string warning = friction->PullingWarning(run, b); !warning.empty())
        out << "warning: " << diagram.origin(b) << ": " << warning << "\n";
}

int PrintUnknownGlobals(const diagrams::LoadedDiagram& loaded, std::ostream& out) {
  // each chunk with the file its lines count in and the line of its first
  struct Chunk {
    std::string code, file;
    int first_line;
  };
  std::vector<Chunk> chunks;
  const diagrams::ScriptDesc& script = loaded.description.script;
  if (script.present()) chunks.push_back({script.code, script.chunk_name.substr(1), 1});  // "@file": lines are the file's
  for (const diagrams::BlockDesc& b : loaded.description.blocks) {
    if (b.type != "lua") continue;
    const auto src = std::find_if(b.params.begin(), b.params.end(), [](const auto& a) { return a.name == "src"; });
    if (src != b.params.end()) {
      const std::string folder = std::filesystem::path(b.loc.file).parent_path().string();
      blocks::NamedFile file =
          blocks::ReadNamedFile(src->value, folder, *loaded.reads, src->loc.str() + ": block '" + b.name + "'");
      chunks.push_back({std::move(file.text), std::move(file.path), 1});
    } else {
      chunks.push_back({b.text, b.text_loc.file, b.text_loc.line});
    }
  }
  std::vector<std::string> spellings;
  for (int i = 0; i < loaded.identifiers->size(); ++i) spellings.push_back(loaded.identifiers->spelling(i));
  int count = 0;
  for (const Chunk& c : chunks)
    for (const scripting::GlobalRead& g : scripting::UnknownGlobals(c.code, *loaded.identifiers, *loaded.lua)) {
      out << c.file << ":" << c.first_line + g.line - 1 << ": warning: '" << g.name
          << "' is read as a global but is no identifier, no Lua name and defined nowhere in the chunk"
          << blocks::DidYouMean(g.name, spellings) << "\n";
      ++count;
    }
  return count;
}

namespace {

// "6 deg = 0.1047197551 rad": the value in its own unit, then in SI when
// that unit is not SI; a value without unit as it is
std::string IdentifierValue(const scripting::IdentifierTable& ids, int i) {
  const double si = ids.value(i);
  if (ids.unit(i).empty()) return Formatted("%.10g", si);
  std::string text = Formatted("%.10g", si / ids.to_si(i)) + " " + ids.unit(i);
  std::string error;
  const std::optional<diagrams::Unit> unit = diagrams::ParseUnit(ids.unit(i), &error);
  if (unit && unit->to_si != 1.0) text += " = " + Formatted("%.10g", si) + " " + unit->dimension.SiUnit();
  return text;
}

}  // namespace

void PrintCheck(const diagrams::LoadedDiagram& loaded, std::ostream& out) {
  const blocks::Diagram& d = *loaded.diagram;
  const scripting::IdentifierTable& ids = *loaded.identifiers;
  out << "diagram '" << loaded.description.name << "': " << d.num_blocks() << " blocks, "
      << d.connections().size() << " connections, " << d.num_states() << " continuous states, "
      << d.num_zero_crossings() << " zero-crossing functions\n";
  if (ids.size() > 0) {
    out << "\nidentifiers:\n";
    for (int i = 0; i < ids.size(); ++i)
      out << "  " << ids.spelling(i) << " = " << IdentifierValue(ids, i)
          << (ids.is_expression(i) ? "  (= " + scripting::WithInstancePaths(ids.definition(i)) + ")" : "")
          << (ids.comment(i).empty() ? "" : "  " + ids.comment(i)) << "\n";
  }
  if (!loaded.description.variants.empty()) {
    out << "\nvariants (--variant NAME):\n";
    for (const auto& v : loaded.description.variants) {
      out << "  " << v.group << " / " << v.name << ":";
      for (const auto& a : v.assignments) out << " " << a.name << " = " << a.value;
      out << "\n";
    }
  }
  out << "\nevaluation order (output ports):\n";
  int step = 1;
  for (const auto& node : d.schedule()) {
    if (node.loop >= 0) {
      std::string hops = d.loops()[node.loop].description();  // indented under its number
      for (std::size_t at = hops.find('\n'); at != std::string::npos; at = hops.find('\n', at + 1))
        hops.insert(at + 1, "    ");
      out << "  " << step++ << ". algebraic loop" << hops << "\n";
      continue;
    }
    const blocks::Block& b = d.block(node.block);
    out << "  " << step++ << ". " << b.name() << "." << b.output_port(node.port).name << "  (" << b.type() << ")\n";
  }
  out << "\nalgebraic loops:";
  if (d.loops().empty()) out << " none";
  out << "\n";
  for (const blocks::AlgebraicLoop& loop : d.loops()) {
    out << "  through " << loop.port() << ", solved by Newton on";
    for (const blocks::OutputNode& tear : loop.tears())
      out << " " << d.block(tear.block).name() << "." << d.block(tear.block).output_port(tear.port).name;
    out << " (" << loop.num_unknowns() << " unknown" << (loop.num_unknowns() == 1 ? "" : "s")
        << ") to a relative change of " << blocks::AlgebraicLoop::kRelativeTolerance << "\n";
  }
  out << "\ncontinuous states:\n";
  if (d.num_states() == 0) out << "  (none)\n";
  for (const int bi : d.stateful_blocks()) {
    const blocks::Block& b = d.block(bi);
    for (int i = 0; i < b.num_states(); ++i)
      out << "  x[" << d.layout(bi).first_state + i << "]  " << b.name() << "." << b.state_name(i) << "\n";
  }
  std::string why;
  out << "\nJacobian: "
      << (blocks::AnalyticJacobian::FindBlock(d, &why) >= 0 ? "analytic" : "difference quotients (" + why + ")")
      << "\n";
  out << "\nzero-crossing functions:\n";
  if (d.num_zero_crossings() == 0) out << "  (none)\n";
  static const char* kDirection[] = {"rising", "falling", "either"};
  for (const int bi : d.crossing_blocks()) {
    const blocks::Block& b = d.block(bi);
    for (int i = 0; i < b.num_zero_crossings(); ++i)
      out << "  g[" << d.layout(bi).first_crossing + i << "]  " << b.name() << " #" << i << " ("
          << kDirection[static_cast<int>(b.crossing_direction(i))] << ")\n";
  }
  out << "\nsampled blocks:\n";
  if (d.periodic_blocks().empty()) out << "  (none)\n";
  for (const int bi : d.periodic_blocks()) {
    const auto& st = d.block(bi).sample_time();
    out << "  " << d.block(bi).name() << ": period " << st.period << " s, offset " << st.offset << " s\n";
  }
  if (loaded.control) {
    const auto functions = loaded.control->functions();
    out << "\ncontrol script: " << loaded.control->name() << " ("
        << (functions.empty() ? "defines none of init, step, finish" : "defines " + blocks::JoinNames(functions))
        << ")\n";
  }
  const auto& s = loaded.solver;
  out << "\nsolver: CVODE BDF, t = " << s.t_start << " .. " << s.t_end << " s, rtol " << s.rtol << ", atol "
      << s.atol << ", output every " << s.output_interval << " s\n";
  out << "logged columns: " << loaded.logged.size() << "\n";
  PrintInstanceTree(loaded.description.instances, out);
}

void PrintDot(const diagrams::LoadedDiagram& loaded, std::ostream& out) {
  const blocks::Diagram& d = *loaded.diagram;
  out << "digraph " << DotQuote(DotText(loaded.description.name)) << " {\n"
      << "  rankdir=LR;\n  node [shape=record, fontname=\"sans\", fontsize=10];\n"
      << "  edge [fontname=\"sans\", fontsize=9];\n";
  // each subsystem instance a cluster of the blocks it holds, nested as they are
  std::vector<std::string> subsystems;
  for (const diagrams::InstanceDesc& instance : loaded.description.instances)
    if (instance.kind == "subsystem") subsystems.push_back(instance.path);
  const InstanceTree tree(std::move(subsystems));
  std::vector<std::vector<int>> held(tree.paths().size());  // blocks per instance
  std::vector<int> outside;
  for (int bi = 0; bi < d.num_blocks(); ++bi) {
    const int in = tree.Enclosing(d.block(bi).name());
    (in < 0 ? outside : held[in]).push_back(bi);
  }
  const auto node = [&](int bi, const std::string& indent) {
    const blocks::Block& b = d.block(bi);
    std::ostringstream inputs, outputs;
    for (int p = 0; p < b.num_inputs(); ++p)
      inputs << (p ? "|" : "") << "<i" << p << "> " << RecordText(b.input_port(p).name);
    for (int p = 0; p < b.num_outputs(); ++p)
      outputs << (p ? "|" : "") << "<o" << p << "> " << RecordText(b.output_port(p).name);
    std::string label = "{";
    if (b.num_inputs() > 0) label += "{" + inputs.str() + "}|";
    label += RecordText(b.name()) + "\\n(" + RecordText(b.type()) + ")";
    if (b.num_outputs() > 0) label += "|{" + outputs.str() + "}";
    label += "}";
    out << indent << "b" << bi << " [label=" << DotQuote(label) << "];\n";
  };
  for (const int bi : outside) node(bi, "  ");
  const std::function<void(int, const std::string&)> cluster = [&](int i, const std::string& indent) {
    out << indent << "subgraph cluster_" << i << " {\n" << indent << "  label=" << DotQuote(DotText(tree.paths()[i]))
        << ";\n";
    for (const int bi : held[i]) node(bi, indent + "  ");
    for (const int child : tree.children(i)) cluster(child, indent + "  ");
    out << indent << "}\n";
  };
  for (const int root : tree.roots()) cluster(root, "  ");
  for (const auto& c : d.connections()) {
    const blocks::Block& to = d.block(c.to_block);
    bool feedthrough = false;
    for (int p = 0; p < to.num_outputs(); ++p) feedthrough |= to.HasFeedthrough(c.to_port, p);
    out << "  b" << c.from_block << ":o" << c.from_port << " -> b" << c.to_block << ":i" << c.to_port
        << (feedthrough ? " [style=bold]" : "") << ";\n";
  }
  out << "}\n";
}

}  // namespace mechflow::cli
