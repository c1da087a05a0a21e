#include "diagrams/instance_scope.h"

#include <set>
#include <vector>

#include "mech/errors.h"
#include "scripting/instance_path.h"
#include "scripting/lua_lexer.h"

namespace mechflow::diagrams {
namespace {

// The names Lua code binds itself (lower case): after `local`, the parameters
// of a `function`, the variables of a `for`. They are the code's own, not
// names of the instance or the diagram.
std::set<std::string> BoundNames(const std::string& text) {
  std::vector<std::string> tokens;  // no blanks nor comments
  for (std::size_t i = 0; i < text.size();) {
    std::size_t end = i;
    const scripting::LuaToken kind = scripting::NextLuaToken(text, i, &end);
    if (kind != scripting::LuaToken::kSpace && kind != scripting::LuaToken::kComment)
      tokens.push_back(text.substr(i, end - i));
    i = end;
  }
  std::set<std::string> bound;
  // a list of names separated by commas from tokens[k]
  const auto names_from = [&](std::size_t k) {
    for (; k < tokens.size() && scripting::IsLuaName(tokens[k]); k += 2) {
      bound.insert(scripting::ToLower(tokens[k]));
      if (k + 1 >= tokens.size() || tokens[k + 1] != ",") break;
    }
  };
  for (std::size_t k = 0; k + 1 < tokens.size(); ++k) {
    if (tokens[k] == "local") {
      names_from(tokens[k + 1] == "function" ? k + 2 : k + 1);
    } else if (tokens[k] == "for") {
      names_from(k + 1);
    } else if (tokens[k] == "function") {
      std::size_t open = k + 1;
      while (open < tokens.size() && tokens[open] != "(") ++open;
      names_from(open + 1);
    }
  }
  return bound;
}

}  // namespace

InstanceScope InstanceScope::Instance(const InstanceScope& parent, const std::string& path,
                                      const ComponentDesc& component, const SourceLoc& included_at,
                                      std::optional<int> index, std::optional<int> count,
                                      const scripting::IdentifierTable* identifiers) {
  InstanceScope s;
  s.path_ = path;
  s.prefix_ = path + ".";
  const std::string line = included_at.file + ":" + std::to_string(included_at.line);
  s.included_lines_ = parent.included_lines_.empty() ? line : line + ", " + parent.included_lines_;
  s.context_ = "in " + path + " (" + s.included_lines_ + ")";
  s.description_ = component.kind + " '" + component.name + "' (" + component.file + ") as " + path;
  s.index_ = index;
  s.count_ = count;
  s.identifiers_ = identifiers;
  return s;
}

InstanceScope InstanceScope::WithIndex(std::optional<int> index, std::optional<int> count) const {
  InstanceScope s = *this;
  s.index_ = index;
  s.count_ = count;
  return s;
}

void InstanceScope::DeclareLater(const std::string& name, const std::string& where) {
  later_.emplace(scripting::ToLower(name), where);
}

std::string InstanceScope::Declare(const std::string& name) {
  later_.erase(scripting::ToLower(name));
  const std::string path = prefix_ + name;
  renames_[scripting::ToLower(name)] = scripting::ToLower(scripting::InstancePathLuaName(path));
  return path;
}

std::string InstanceScope::PathOf(const std::string& name) const { return is_diagram() ? name : prefix_ + name; }

std::string InstanceScope::Rewrite(const std::string& text, const std::string& what) const {
  if (is_diagram() && !index_ && !count_) return text;
  const std::set<std::string> bound = is_diagram() ? std::set<std::string>{} : BoundNames(text);
  std::string out;
  out.reserve(text.size() + 16);
  bool field = false;  // the last token that was not blank is '.' or ':': a name now is a field
  for (std::size_t i = 0; i < text.size();) {
    std::size_t end = i;
    const scripting::LuaToken kind = scripting::NextLuaToken(text, i, &end);
    const std::string token = text.substr(i, end - i);
    i = end;
    if (kind != scripting::LuaToken::kName || field || !scripting::IsLuaName(token)) {
      out += token;
      if (kind != scripting::LuaToken::kSpace && kind != scripting::LuaToken::kComment)
        field = token == "." || token == ":";
      continue;
    }
    field = false;
    // a table constructor's key ({mu = 1}) is no name read
    std::size_t next = i;
    while (next < text.size() && (text[next] == ' ' || text[next] == '\t')) ++next;
    const bool key = next < text.size() && text[next] == '=' && (next + 1 >= text.size() || text[next + 1] != '=');
    const std::string lower = scripting::ToLower(token);
    if (bound.count(lower)) {
      // the code's own variable: shadowing a parameter of the instance would read neither as meant
      if (const auto it = renames_.find(lower); it != renames_.end())
        throw InputError(what + ": the code binds '" + token + "' (local, function parameter or for variable), " +
                         "which is also a parameter or identifier of " + description_ + "; rename one of them");
      out += token;
    } else if (lower == "index" && index_ && !key) {
      out += std::to_string(*index_);
    } else if (lower == "count" && count_ && !key) {
      out += std::to_string(*count_);
    } else if (const auto it = renames_.find(lower); it != renames_.end()) {
      out += it->second;
    } else {
      if (const auto later = later_.find(lower); later != later_.end() && !key)
        throw InputError(what + ": '" + token + "' is declared below it (" + later->second +
                         "); parameters and identifiers may use those declared above them: move it up");
      if (!is_diagram() && !key && identifiers_ && identifiers_->Has(lower))
        throw InputError(what + ": '" + token + "' is not visible inside " + description_ +
                         ": only its parameters and identifiers are; declare <parameter name=\"" + token +
                         "\"/> in " + description_.substr(0, description_.find(" as ")) +
                         " and give it with <param name=\"" + token + "\" value=\"" + token + "\"/> where it is used");
      out += token;
    }
  }
  return out;
}

}  // namespace mechflow::diagrams
