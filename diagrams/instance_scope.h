#pragma once
// InstanceScope: what the expressions inside one subsystem or part instance
// may name, and how they read once the instance is flattened into the
// diagram.
//
// Inside an instance only its parameters, its own identifiers and the
// built-ins are visible (Modelica's components, Simulink's masked
// subsystems): each becomes an identifier of the diagram with a path name
// ("d[1].c"), and the expressions that name it are rewritten to its Lua name
// ("d__1__c", scripting/instance_path.h). In an array, `index` and `count`
// read as numbers. A name of the including diagram that the instance does
// not see is refused, not quietly taken from outside.

#include <map>
#include <optional>
#include <string>

#include "diagrams/description.h"
#include "scripting/identifiers.h"

namespace mechflow::diagrams {

class InstanceScope {
 public:
  // The diagram's own scope: every identifier visible, nothing rewritten.
  InstanceScope() = default;

  // The scope of instance `path` of `component` (its kind and file, for
  // messages), included at `included_at` from `parent`; `index`/`count` for an
  // array's element. `identifiers`: the diagram's, which the instance may
  // not see unless declared in it.
  static InstanceScope Instance(const InstanceScope& parent, const std::string& path, const ComponentDesc& component,
                                const SourceLoc& included_at, std::optional<int> index, std::optional<int> count,
                                const scripting::IdentifierTable* identifiers);

  // The same scope, seeing `index` and `count` of an array element being
  // made (a <param> value is written in the including scope, but its index
  // is the new instance's).
  InstanceScope WithIndex(std::optional<int> index, std::optional<int> count) const;

  // Names the instance declares further down (`where`: its line): an
  // expression naming one before it is declared is refused as such.
  void DeclareLater(const std::string& name, const std::string& where);
  // Declares a parameter or identifier `name` of this instance; its path.
  std::string Declare(const std::string& name);
  bool Declares(const std::string& name) const { return renames_.count(scripting::ToLower(name)) > 0; }
  // The path of a declared name ("d[1].F"); the name itself at the diagram's level.
  std::string PathOf(const std::string& name) const;

  // `text` (an expression, a list of them, Lua code) with the names this
  // scope declares written as their Lua names. InputError starting with
  // `what` when it names an identifier of the diagram this scope does not see.
  std::string Rewrite(const std::string& text, const std::string& what) const;

  // "d[1]." -- what the names made here begin with; "" at the diagram's level.
  const std::string& prefix() const { return prefix_; }
  const std::string& path() const { return path_; }
  bool is_diagram() const { return path_.empty(); }
  // The traceback items made here carry (SourceLoc::context).
  const std::string& context() const { return context_; }
  // Describes the instance for messages: "subsystem 'damper' (parts/damper.xml) as d[1]".
  const std::string& description() const { return description_; }

 private:
  std::string path_, prefix_, context_, description_;
  std::string included_lines_;  // "chain.xml:30, ..." the including lines, innermost first
  std::map<std::string, std::string> renames_;  // lower-case name -> Lua name of its path
  std::map<std::string, std::string> later_;    // lower-case name -> where it is declared, not yet
  std::optional<int> index_, count_;
  const scripting::IdentifierTable* identifiers_ = nullptr;
};

}  // namespace mechflow::diagrams
