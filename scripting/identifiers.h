#pragma once
// IdentifierTable: the named real parameters of a diagram (ELEMENTS.md 1.1).
//
// An identifier is defined by a number or by an expression of the identifiers
// ABOVE it (so definitions cannot be circular); the list is evaluated top to
// bottom. Names are case-insensitive (`Mass` and `mass` are one identifier;
// they are stored lower-case). An identifier defined by an expression is
// derived: it cannot be overridden, it follows what it depends on.
//
// Expressions are Lua expressions (`^` is the right-associative power) over
// the identifiers and the functions of the sandbox (sin, sqrt, sqr, ln, pi,
// ...; see LuaState). They are evaluated in an environment whose lookups
// lower-case the name, so `MASS*k^2` finds `mass`; every evaluation runs under
// an instruction limit, so `(function() while true do end end)()` cannot hang
// loading.
//
// Typical use (the diagram loader):
//   ids.Add("m", "10", "d.xml:3");  ids.Add("c", "4*pi^2*m", "d.xml:4");
//   ids.Override("m", 20);          // --set m=20
//   ids.Evaluate(lua);              // c follows m
//   double k = ids.EvaluateExpression(lua, "-c/m", "d.xml:9: block 'k' parameter 'k'");

#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace mechflow::scripting {

class LuaState;

class IdentifierTable {
 public:
  // Appends an identifier. `name` is a Lua name, or an instance path
  // ("d[1].c", scripting/instance_path.h) that expressions know by its Lua
  // name ("d__1__c") and Find by either. `definition` is a number (the whole text, as
  // std::from_chars reads it: "1.5abc" is not a number) or a Lua expression;
  // `origin` is "file:line" for messages. Throws InputError for a name that is
  // not a Lua name, is reserved (a Lua keyword, t, x, v, pi, a built-in
  // function or Lua library name) or is already defined (case-insensitively).
  // Values are SI: a number is in `unit`, taken to SI by `to_si` (the
  // loader's units, diagrams/units.h); an expression computes an SI value
  // from SI values, and `unit` only says how to show it.
  void Add(const std::string& name, const std::string& definition, const std::string& origin,
           const std::string& comment = "", const std::string& unit = "", double to_si = 1.0);

  // A value given from outside (--set, sim:set), in SI: only for identifiers
  // defined by a number, and only a finite one. Call Evaluate afterwards so
  // derived identifiers follow. Throws InputError otherwise (unknown names
  // get a "did you mean").
  void Override(const std::string& name, double value);

  // Evaluates every expression identifier, top to bottom, each seeing only the
  // identifiers above it. Throws InputError starting with the identifier's
  // origin: "<origin>: identifier 'c': ...".
  void Evaluate(LuaState& lua);

  // Evaluates an expression over all identifiers (after Evaluate). Errors are
  // InputError starting with `what` (e.g. "d.xml:12: block 'k' parameter 'k'").
  double EvaluateExpression(LuaState& lua, const std::string& text, const std::string& what) const;

  // As EvaluateExpression, without noting fixed uses: for a caller that
  // evaluates the text again when identifiers change (the shapes of the
  // animation follow a control script's changes).
  double EvaluateFollowing(LuaState& lua, const std::string& text, const std::string& what) const {
    return Eval(lua, text, size(), -1, what);
  }
  // The indices of the identifiers `text` names (a field after '.' or ':' is
  // none; strings are not told apart, so this may name too many, never too few).
  std::vector<int> NamedIn(const std::string& text) const;

  // Fixed uses: places that took an identifier's value once, when the diagram
  // was built (a block parameter, a mass, a time function). A control script
  // may not change such an identifier during a run, since the change could
  // not reach them; compiled expressions and identifier blocks follow changes
  // and are no fixed uses. EvaluateExpression notes the identifiers its text
  // names; other builders call NoteFixedUses. Bookkeeping only, hence const.
  void NoteFixedUses(const std::string& text, const std::string& what) const;
  // Each place once, in the order first noted.
  const std::vector<std::string>& fixed_uses(int i) const;

  // Every value, in order, and their restoration (a control script's changes
  // undone before the next run).
  std::vector<double> Values() const;
  void SetValues(const std::vector<double>& values);
  // One value, unchecked, for a control script that re-evaluated a derived
  // identifier from its compiled definition.
  void SetValue(int i, double value) { items_.at(i).value = value; }

  int size() const { return static_cast<int>(items_.size()); }
  int Find(const std::string& name) const;  // index or -1, case-insensitive
  int FindLowerCase(std::string_view lower) const noexcept;  // index or -1, for a name already lower-case
  bool Has(const std::string& name) const { return Find(name) >= 0; }
  double Value(const std::string& name) const;  // throws std::out_of_range when unknown
  std::vector<std::string> Names() const;       // lower-case, in order (Lua names)
  // As messages show them: paths for instances' parameters ("d[1].mu").
  std::vector<std::string> ShownNames() const;

  // The i-th identifier, 0 <= i < size(). Names are lower-case.
  const std::string& name(int i) const { return items_.at(i).name; }
  // The name as the diagram wrote it (for what a user reads: tables, files).
  const std::string& spelling(int i) const { return items_.at(i).spelling; }
  const std::string& definition(int i) const { return items_.at(i).definition; }
  double value(int i) const { return items_.at(i).value; }
  bool is_expression(int i) const { return items_.at(i).is_expression; }
  bool is_overridden(int i) const { return items_.at(i).overridden; }
  const std::string& comment(int i) const { return items_.at(i).comment; }
  const std::string& unit(int i) const { return items_.at(i).unit; }
  // value in SI = value in unit(i) * to_si(i) (1 without a unit)
  double to_si(int i) const { return items_.at(i).to_si; }
  const std::string& origin(int i) const { return items_.at(i).origin; }

 private:
  struct Item {
    std::string name, spelling, definition, origin, comment, unit;
    bool is_expression = false;
    bool overridden = false;
    double value = 0.0;  // SI
    double to_si = 1.0;
    mutable std::vector<std::string> fixed_uses;  // may hold repeats until fixed_uses(i) removes them
    mutable std::size_t unique_uses = 0;          // the first unique_uses entries hold none
  };
  // Hashes std::string and std::string_view alike, so lookups need no copy.
  struct NameHash {
    using is_transparent = void;
    std::size_t operator()(std::string_view s) const noexcept { return std::hash<std::string_view>()(s); }
  };
  // The name messages give: the path of an instance's parameter, else the lower-case name.
  static const std::string& Shown(const Item& item) {
    return item.spelling.find_first_of(".[") != std::string::npos ? item.spelling : item.name;
  }
  // Evaluates `text` seeing identifiers [0, visible); `self` is the index of
  // the identifier being defined, or -1. Errors start with `what`.
  double Eval(LuaState& lua, const std::string& text, int visible, int self, const std::string& what) const;
  // " (with k = 800, m = -2 in SI)": the identifiers among [0, visible) that
  // `text` names, with their values; "" when it names none.
  std::string ValuesNamedIn(const std::string& text, int visible) const;

  std::vector<Item> items_;
  // lower-case name -> index into items_ (names are only ever appended)
  std::unordered_map<std::string, int, NameHash, std::equal_to<>> index_;
};

// Lower-case copy (identifier names are case-insensitive).
std::string ToLower(std::string s);

// A finite number written in full, surrounding blanks and a leading '+'
// allowed ("1.5", " -2e3", "+4"); false for anything else ("1.5abc", "inf").
bool ParseNumber(const std::string& text, double* value);

// True for a Lua name (letter or '_', then letters, digits, '_') that is not a
// Lua keyword.
bool IsLuaName(const std::string& name);

}  // namespace mechflow::scripting
