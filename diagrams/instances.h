#pragma once
// Flattening: every <block type="subsystem"> and every <include part=...>
// of a diagram becomes plain blocks, mechanisms, mechanism elements and
// identifiers with instance paths for names ("d[1].fr", "m.s[2].Box"), so
// that nothing after the loader knows a subsystem or part existed.
//
//   instance   its parameters (from <param>, evaluated where it is used, or
//              their defaults) and identifiers become the diagram's,
//              named by path; its expressions are rewritten to see them
//              and nothing else (diagrams/instance_scope.h)
//   array      count="N" makes name[0] .. name[N-1]; `index` and `count`
//              are numbers inside
//   ports      a subsystem's <input>/<output> vanish: connections through
//              them join the blocks on either side; an output stays
//              reachable by its path as a signal alias
//   parts      elements are named "s.Box"; their references to bodies,
//              joints, coordinates and elements are prefixed likewise,
//              attach points replaced by the bodies the include names
//
// Items made from an included file keep that file's lines and carry the
// instance and the including lines (SourceLoc::context), so messages read
// "stage.xml:12: in s[2] (chain.xml:30): ...".

#include <functional>
#include <string>

#include "diagrams/description.h"
#include "scripting/identifiers.h"

namespace mechflow::diagrams {

// What flattening needs of the loader's identifiers.
struct InstanceIdentifiers {
  // adds a parameter or identifier of an instance: name = its path, value =
  // its definition as rewritten, unit and comment as declared
  std::function<void(const IdentifierDesc&)> add;
  // the value of an expression over the identifiers added so far (a count=)
  std::function<double(const std::string& text, const std::string& what)> evaluate;
  // every identifier of the diagram (names an instance may not see)
  const scripting::IdentifierTable* table = nullptr;
};

// Flattens `d` in place (blocks, connections, mechanisms; fills instances,
// signal_aliases and input_widths). InputError for bad input, naming the line and instance.
void MakeInstances(DiagramDescription* d, const InstanceIdentifiers& identifiers);

// Names a diagram writes for blocks, mechanisms and instances: "" when
// `name` may be one, else why not (paths are made by flattening only).
std::string WrittenNameProblem(const std::string& name);

}  // namespace mechflow::diagrams
