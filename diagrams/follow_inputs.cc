#include "diagrams/follow_inputs.h"

#include <set>
#include <vector>

#include "scripting/lua_lexer.h"

namespace mechflow::diagrams {
namespace {

// Attributes that name things rather than compute a value.
const std::set<std::string> kNames = {"name", "type", "kind", "body",   "body1", "body2",
                                      "joint", "dof", "element", "signal", "component", "quantity"};

class InputFollower {
 public:
  InputFollower(const ElementDesc& m, const scripting::IdentifierTable& ids) : ids_(ids), expanded_(ids.size()) {
    std::vector<bool> follows(ids.size(), false);
    for (const ElementDesc& e : m.children)
      if (e.tag == "input")
        if (const int i = ids.Find(e.Text("name")); i >= 0) follows[i] = true;
    // definitions name only identifiers above them: one pass in order
    for (int i = 0; i < ids.size(); ++i) {
      if (follows[i] || !ids.is_expression(i)) continue;
      for (const int used : ids.NamedIn(ids.definition(i)))
        if (follows[used]) {
          follows[i] = true;
          expanded_[i] = "(" + Expand(ids.definition(i)) + ")";
          any_ = true;
          break;
        }
    }
  }

  bool any() const { return any_; }

  // `text` with the identifiers that follow inputs written out.
  std::string Expand(const std::string& text) const {
    std::string out;
    bool field = false;
    for (std::size_t i = 0; i < text.size();) {
      std::size_t end = i;
      const scripting::LuaToken kind = scripting::NextLuaToken(text, i, &end);
      const std::string token = text.substr(i, end - i);
      i = end;
      const int id = kind == scripting::LuaToken::kName && !field ? ids_.Find(token) : -1;
      out += id >= 0 && !expanded_[id].empty() ? expanded_[id] : token;
      if (kind != scripting::LuaToken::kSpace && kind != scripting::LuaToken::kComment)
        field = token == "." || token == ":";
    }
    return out;
  }

  ElementDesc Apply(const ElementDesc& e) const {
    ElementDesc out = e;
    if (e.tag == "input") return out;
    for (Attribute& a : out.attributes)
      if (!kNames.count(a.name)) a.value = Expand(a.value);
    for (ElementDesc& child : out.children) child = Apply(child);
    return out;
  }

 private:
  const scripting::IdentifierTable& ids_;
  std::vector<std::string> expanded_;  // by identifier: its definition written out, "" when it follows no input
  bool any_ = false;
};

}  // namespace

ElementDesc FollowInputs(const ElementDesc& m, const scripting::IdentifierTable& identifiers) {
  const InputFollower follower(m, identifiers);
  if (!follower.any()) return m;
  ElementDesc out = m;
  for (ElementDesc& e : out.children) e = follower.Apply(e);
  return out;
}

}  // namespace mechflow::diagrams
