#include "fmi/variables.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "mech/errors.h"
#include "run/columns.h"

namespace mechflow::fmi {
namespace {

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The signals (offsets into the context's signals) each input reaches at the
// same instant: along connections, and through a block from an input port
// to each output port it feeds through to.
std::vector<std::set<int>> FeedthroughReach(const diagrams::LoadedDiagram& loaded) {
  const blocks::Diagram& d = *loaded.diagram;
  std::vector<std::set<int>> reach;
  for (const diagrams::DiagramInput& in : loaded.inputs) {
    std::set<int> signals;
    std::vector<std::pair<int, int>> todo = {{in.block, 0}};  // (block, output port)
    std::set<std::pair<int, int>> seen(todo.begin(), todo.end());
    while (!todo.empty()) {
      const auto [b, port] = todo.back();
      todo.pop_back();
      const blocks::BlockLayout& layout = d.layout(b);
      for (int i = 0; i < layout.output_width[port]; ++i) signals.insert(layout.output_offset[port] + i);
      for (const blocks::Connection& c : d.connections()) {
        if (c.from_block != b || c.from_port != port) continue;
        const blocks::Block& to = d.block(c.to_block);
        for (int out = 0; out < to.num_outputs(); ++out)
          if (to.HasFeedthrough(c.to_port, out) && seen.insert({c.to_block, out}).second)
            todo.push_back({c.to_block, out});
      }
    }
    reach.push_back(std::move(signals));
  }
  return reach;
}

// Identifiers a top-level mechanism's <input> takes from its port: a value
// set for them would be overwritten at once.
std::set<std::string> PortFedIdentifiers(const diagrams::DiagramDescription& d) {
  std::set<std::string> names;
  for (const diagrams::ElementDesc& m : d.mechanisms)
    for (const diagrams::ElementDesc& e : m.children)
      if (e.tag == "input") names.insert(Lower(e.Text("name")));
  return names;
}

// The <log> a logged column comes from ("" when none names it: a recorder's).
const diagrams::LogDesc* LogOf(const diagrams::DiagramDescription& d, const std::string& column) {
  for (const diagrams::LogDesc& log : d.logs) {
    const std::string& name = log.label.empty() ? log.signal : log.label;
    if (column == name || (column.rfind(name + "[", 0) == 0 && column.back() == ']')) return &log;
  }
  return nullptr;
}

}  // namespace

std::vector<Variable> CollectVariables(const diagrams::LoadedDiagram& loaded) {
  std::vector<Variable> out;
  // what has a name: how it is said, where it is written ("" unknown), and what renaming it takes
  struct Owner {
    std::string what, loc, rename;
  };
  std::map<std::string, Owner> taken;
  const auto add = [&](Variable v, Owner owner) {
    const auto [it, fresh] = taken.emplace(v.name, owner);
    if (!fresh) {
      // a <log>'s label names the output alone: renaming it changes nothing else, so it is the one to rename
      const Owner& first = it->second;
      const bool output_first = first.what.rfind("an output", 0) == 0;
      const Owner& rename = output_first || owner.what.rfind("an output", 0) != 0 ? first : owner;
      const std::string loc = !rename.loc.empty() ? rename.loc : !owner.loc.empty() ? owner.loc : first.loc;
      throw InputError((loc.empty() ? std::string("export-fmu") : loc) + ": the FMU variable '" + v.name +
                       "' would be both " + first.what + " and " + owner.what +
                       "; FMU variables need unique names: " + rename.rename);
    }
    v.value_reference = static_cast<unsigned>(out.size() + 1);
    out.push_back(std::move(v));
  };

  const std::vector<std::string> columns = run::ColumnNames(loaded.logged);
  const std::vector<std::set<int>> reach = FeedthroughReach(loaded);
  int column = 1;
  for (const blocks::SignalRef& s : loaded.logged)
    for (int k = 0; k < s.width; ++k, ++column) {
      Variable v;
      v.name = columns[column];
      v.causality = Causality::kOutput;
      v.unit = column < static_cast<int>(loaded.units.size()) ? loaded.units[column] : "";
      v.index = column;
      for (std::size_t i = 0; i < reach.size(); ++i)
        if (reach[i].count(s.offset + k)) v.inputs.push_back(static_cast<int>(i));
      const diagrams::LogDesc* log = LogOf(loaded.description, columns[column]);
      const std::string where = log ? log->loc.str() : "";
      const std::string name = columns[column];
      add(std::move(v), {"an output (the column of the <log>" + (log ? " at " + where : std::string()) + ")", where,
                         log && !log->label.empty()
                             ? "rename the label of the <log> at " + where + " (label=\"" + log->label +
                                   "_out\", say): it names the output alone, and the diagram runs as before"
                             : "give the <log>" + (log ? " at " + where : std::string()) + " a label of its own (label=\"" +
                                   name + "_out\", say)"});
    }
  for (std::size_t i = 0; i < loaded.inputs.size(); ++i) {
    const diagrams::DiagramInput& in = loaded.inputs[i];
    Variable v;
    v.name = in.name;
    v.causality = Causality::kInput;
    v.unit = in.unit;
    v.description = in.comment;
    v.start = in.start / in.to_si;
    v.index = static_cast<int>(i);
    add(std::move(v), {"an input (" + in.origin + ")", in.origin, "rename the <input> at " + in.origin});
  }
  const scripting::IdentifierTable& ids = *loaded.identifiers;
  const std::set<std::string> port_fed = PortFedIdentifiers(loaded.description);
  for (int i = 0; i < ids.size(); ++i) {
    if (ids.is_expression(i) || port_fed.count(Lower(ids.spelling(i)))) continue;
    Variable v;
    v.name = ids.spelling(i);
    v.causality = Causality::kParameter;
    v.unit = ids.unit(i);
    v.description = ids.comment(i);
    v.start = ids.value(i) / ids.to_si(i);
    v.index = i;
    add(std::move(v), {"a parameter (the identifier at " + ids.origin(i) + ")", ids.origin(i),
                       "rename the identifier at " + ids.origin(i) + " and every use of it"});
  }
  return out;
}

}  // namespace mechflow::fmi
