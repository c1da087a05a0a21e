#pragma once
// Evaluator: turns the text of attributes into numbers -- a plain number as
// written, or an expression of the diagram's identifiers -- with messages that
// start with the caller's `what` ("file:line: block 'k' parameter 'k'").

#include <charconv>
#include <string>
#include <vector>

#include "diagrams/unit_check.h"
#include "mech/errors.h"
#include "scripting/identifiers.h"
#include "scripting/lua_state.h"

namespace mechflow::diagrams {

inline std::string Trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r\n") - first + 1);
}

// Splits at any of `separators`, dropping empty pieces.
inline std::vector<std::string> Split(const std::string& s, const char* separators) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start <= s.size()) {
    const size_t end = s.find_first_of(separators, start);
    const std::string piece = Trim(s.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (!piece.empty()) out.push_back(piece);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

class Evaluator {
 public:
  // `units`: the identifiers' units, to check uses of attributes against
  // (nullptr: no checks)
  Evaluator(scripting::LuaState* lua, const scripting::IdentifierTable* ids, const UnitCheck* units = nullptr)
      : lua_(lua), ids_(ids), units_(units) {}

  // Checks `text` used as `attribute` of SI unit `si_unit` ("" unknown)
  // against the units of the identifiers it names: the whole text, or each
  // item of a list as Numbers splits it.
  void CheckUnit(const std::string& text, bool list, const std::string& attribute, const std::string& si_unit,
                 const std::string& what) const {
    if (!units_ || si_unit.empty()) return;
    if (!list) return units_->CheckAttribute(text, attribute, si_unit, what);
    for (const auto& item : Split(text, " \t\r\n,")) units_->CheckAttribute(item, attribute, si_unit, what);
  }

  double Number(const std::string& text, const std::string& what) const {
    const std::string t = Trim(text);
    if (t.empty()) throw InputError(what + ": expected a number or an expression, found nothing");
    double value = 0.0;
    const auto [end, error] = std::from_chars(t.data(), t.data() + t.size(), value);
    if (error == std::errc() && end == t.data() + t.size()) return value;
    return ids_->EvaluateExpression(*lua_, t, what);
  }

  // Numbers separated by blanks or commas (each may be an expression without blanks).
  std::vector<double> Numbers(const std::string& text, const std::string& what) const {
    std::vector<double> out;
    for (const auto& item : Split(text, " \t\r\n,")) out.push_back(Number(item, what));
    if (out.empty()) throw InputError(what + ": expected at least one number");
    return out;
  }

  std::vector<std::vector<double>> Table(const std::string& text, const std::string& what) const {
    std::vector<std::vector<double>> rows;
    for (const auto& row : Split(text, ";")) rows.push_back(Numbers(row, what + " row " + std::to_string(rows.size() + 1)));
    if (rows.empty()) throw InputError(what + ": expected rows separated by ';'");
    return rows;
  }

  scripting::LuaState* lua() const { return lua_; }
  const scripting::IdentifierTable* identifiers() const { return ids_; }

 private:
  scripting::LuaState* lua_;
  const scripting::IdentifierTable* ids_;
  const UnitCheck* units_;
};

}  // namespace mechflow::diagrams
