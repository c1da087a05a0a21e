#include "diagrams/instance_scope.h"

#include "mech/errors.h"
#include "scripting/instance_path.h"
#include "scripting/lua_lexer.h"

namespace mechflow::diagrams {

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
    if (lower == "index" && index_ && !key) {
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
