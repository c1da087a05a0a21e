#pragma once
// IdentifierTable: the named real parameters of a diagram.
//
// An identifier is defined by a number or by an expression of the identifiers
// ABOVE it (so definitions cannot be circular); the list is evaluated top to
// bottom. Names are case-insensitive (`Mass` and `mass` are one identifier;
// they are stored lower-case). An identifier defined by an expression is
// derived: it cannot be overridden, it follows what it depends on.

#include <string>
#include <vector>

namespace mechflow::scripting {

class LuaState;

class IdentifierTable {
 public:
  // `definition` is a number or a Lua expression; `origin` is "file:line" for
  // messages. Throws InputError for a bad or duplicate name.
  void Add(const std::string& name, const std::string& definition, const std::string& origin,
           const std::string& comment = "", const std::string& unit = "");

  // A value given from outside (--set): only for identifiers defined by a number.
  void Override(const std::string& name, double value);

  // Evaluates every identifier, top to bottom. Throws InputError naming the
  // identifier's origin on any error.
  void Evaluate(LuaState& lua);

  // Evaluates an expression over all identifiers (after Evaluate). Errors are
  // InputError starting with `what` (e.g. "d.xml:12: block 'k' parameter 'k'").
  double EvaluateExpression(LuaState& lua, const std::string& text, const std::string& what) const;

  int size() const { return static_cast<int>(items_.size()); }
  int Find(const std::string& name) const;  // index or -1, case-insensitive
  bool Has(const std::string& name) const { return Find(name) >= 0; }
  double Value(const std::string& name) const;  // throws std::out_of_range when unknown
  std::vector<std::string> Names() const;

  const std::string& name(int i) const { return items_.at(i).name; }
  const std::string& definition(int i) const { return items_.at(i).definition; }
  double value(int i) const { return items_.at(i).value; }
  bool is_expression(int i) const { return items_.at(i).is_expression; }
  const std::string& comment(int i) const { return items_.at(i).comment; }
  const std::string& unit(int i) const { return items_.at(i).unit; }
  const std::string& origin(int i) const { return items_.at(i).origin; }

 private:
  struct Item {
    std::string name, definition, origin, comment, unit;
    bool is_expression = false;
    bool overridden = false;
    double value = 0.0;
  };
  // Evaluates `text` seeing identifiers [0, visible); on an unknown name
  // stores it in `*unknown` and throws.
  double Eval(LuaState& lua, const std::string& text, int visible, const std::string& what) const;

  std::vector<Item> items_;
};

// Lower-case copy (identifier names are case-insensitive).
std::string ToLower(std::string s);

// A plain number written in full ("1.5", "-2e3"), or false.
bool ParseNumber(const std::string& text, double* value);

}  // namespace mechflow::scripting
