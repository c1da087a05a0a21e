#include "diagrams/units.h"

#include <udunits2.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <stdexcept>

#include "diagrams/evaluator.h"

namespace mechflow::diagrams {
namespace {

using Exponents = std::array<double, Dimension::kBases>;

// The basic units of UDUNITS' database, in Dimension's order.
constexpr const char* kBaseSymbols[Dimension::kBases] = {"kg", "m", "s", "A", "K", "mol", "cd", "rad"};

// What a dimension is called in messages (kg, m, s, A, K, mol, cd, rad).
struct Named {
  Exponents exponents;
  const char* name;
  const char* unit;  // the SI unit it is shown in
};
constexpr Named kNamed[] = {
    {{0, 0, 0, 0, 0, 0, 0, 0}, "a number", "1"},
    {{0, 0, 0, 0, 0, 0, 0, 1}, "an angle", "rad"},
    {{1, 0, 0, 0, 0, 0, 0, 0}, "a mass", "kg"},
    {{0, 1, 0, 0, 0, 0, 0, 0}, "a length", "m"},
    {{0, 0, 1, 0, 0, 0, 0, 0}, "a time", "s"},
    {{0, 0, -1, 0, 0, 0, 0, 1}, "an angular velocity", "rad/s"},
    {{0, 0, -1, 0, 0, 0, 0, 0}, "a frequency", "1/s"},
    {{0, 1, -1, 0, 0, 0, 0, 0}, "a velocity", "m/s"},
    {{0, 1, -2, 0, 0, 0, 0, 0}, "an acceleration", "m/s^2"},
    {{1, 1, -2, 0, 0, 0, 0, 0}, "a force", "N"},
    {{1, 2, -2, 0, 0, 0, 0, 0}, "a torque or energy", "N m"},
    {{1, 2, -2, 0, 0, 0, 0, -1}, "a rotational stiffness", "N m/rad"},
    {{1, 2, -1, 0, 0, 0, 0, -1}, "a rotational damping", "N m s/rad"},
    {{1, 0, -2, 0, 0, 0, 0, 0}, "a stiffness", "N/m"},
    {{1, 0, -1, 0, 0, 0, 0, 0}, "a damping", "N s/m"},
    {{1, 2, 0, 0, 0, 0, 0, 0}, "a moment of inertia", "kg m^2"},
    {{1, -1, -2, 0, 0, 0, 0, 0}, "a pressure", "Pa"},
    {{1, -3, 0, 0, 0, 0, 0, 0}, "a density", "kg/m^3"},
};

// What a visit of a parsed unit found: its factor to SI, its dimension, or why
// no factor converts it.
struct Visit {
  double scale = 1.0, offset = 0.0;
  Exponents exponents{};
  std::string problem;
};

ut_status VisitBasic(const ut_unit* unit, void* arg);
ut_status VisitProduct(const ut_unit*, int count, const ut_unit* const* basics, const int* powers, void* arg);
ut_status VisitGalilean(const ut_unit*, double scale, const ut_unit* underlying, double offset, void* arg);
ut_status VisitTimestamp(const ut_unit*, const ut_unit*, double, void* arg) {
  static_cast<Visit*>(arg)->problem = "is a point in time (a timestamp), not a unit a value is measured in";
  return UT_SUCCESS;
}
ut_status VisitLogarithmic(const ut_unit*, double, const ut_unit*, void* arg) {
  static_cast<Visit*>(arg)->problem = "is a logarithmic unit; mechflow converts values by a factor only";
  return UT_SUCCESS;
}
ut_visitor kVisitor = {VisitBasic, VisitProduct, VisitGalilean, VisitTimestamp, VisitLogarithmic};

bool AddBase(const ut_unit* basic, int power, Visit* visit) {
  const char* symbol = ut_get_symbol(basic, UT_ASCII);
  for (int b = 0; symbol && b < Dimension::kBases; ++b)
    if (std::string(symbol) == kBaseSymbols[b]) {
      visit->exponents[b] += power;
      return true;
    }
  visit->problem = std::string("is made of the base unit '") + (symbol ? symbol : "?") + "', which mechflow does not use";
  return false;
}
ut_status VisitBasic(const ut_unit* unit, void* arg) {
  AddBase(unit, 1, static_cast<Visit*>(arg));
  return UT_SUCCESS;
}
ut_status VisitProduct(const ut_unit*, int count, const ut_unit* const* basics, const int* powers, void* arg) {
  for (int i = 0; i < count; ++i)
    if (!AddBase(basics[i], powers[i], static_cast<Visit*>(arg))) break;
  return UT_SUCCESS;
}
ut_status VisitGalilean(const ut_unit*, double scale, const ut_unit* underlying, double offset, void* arg) {
  auto* visit = static_cast<Visit*>(arg);
  visit->scale *= scale;
  visit->offset += offset;
  return ut_accept_visitor(underlying, &kVisitor, arg);
}

// UseUnitsDatabase's file ("" the default place), read by the first use.
std::string& DatabasePath() {
  static std::string path;
  return path;
}
std::mutex& DatabaseMutex() {
  static std::mutex mutex;
  return mutex;
}

// The unit system of UDUNITS' standard database, read once. UDUNITS' parser
// is not reentrant, so every use holds the lock; results are kept by text.
class UnitSystem {
 public:
  static UnitSystem& Instance() {
    static UnitSystem system;
    return system;
  }

  std::optional<Unit> Parse(const std::string& text, std::string* error) {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (const auto it = cache_.find(text); it != cache_.end()) {
      if (!it->second.unit) *error = it->second.error;
      return it->second.unit;
    }
    Parsed& parsed = cache_[text];
    parsed.unit = ParseLocked(text, &parsed.error);
    if (!parsed.unit) *error = parsed.error;
    return parsed.unit;
  }

 private:
  struct Parsed {
    std::optional<Unit> unit;
    std::string error;
  };

  UnitSystem() {
    // UDUNITS prints notes on stderr (overridden definitions while reading
    // its own database, every failed parse); mechflow says what failed itself
    ut_set_error_message_handler(ut_ignore);
    {
      const std::lock_guard<std::mutex> lock(DatabaseMutex());
      system_ = ut_read_xml(DatabasePath().empty() ? nullptr : DatabasePath().c_str());
    }
    if (!system_) return;
    // common symbols the database lacks: deg (it has "degree" and the degree
    // sign) and rev (it has "revolution", 2 pi rad)
    for (const auto& [symbol, name] : {std::pair{"deg", "arc_degree"}, std::pair{"rev", "revolution"}})
      if (ut_unit* unit = ut_get_unit_by_name(system_, name)) {
        ut_map_symbol_to_unit(symbol, UT_ASCII, unit);
        ut_free(unit);
      }
  }
  ~UnitSystem() { ut_free_system(system_); }

  std::optional<Unit> ParseLocked(const std::string& text, std::string* error) {
    if (!system_) {
      *error = "the units database of UDUNITS-2 could not be read (" + std::string(std::getenv("UDUNITS2_XML_PATH")
                                                                               ? "UDUNITS2_XML_PATH is set"
                                                                               : "its default place") +
               "); install the Debian package libudunits2-data (scripts/install-deps.sh does)";
      return std::nullopt;
    }
    const std::string trimmed = Trim(text);
    ut_unit* unit = ut_parse(system_, trimmed.c_str(), UT_UTF8);
    if (!unit) {
      *error = "unknown unit '" + trimmed +
               "' (units are read by UDUNITS-2, e.g. m, mm, kg, g, s, ms, N, kN, N/mm, N m, N*m, deg, rad, rev, "
               "rpm, rad/s, Hz, bar, Pa)";
      return std::nullopt;
    }
    Visit visit;
    const ut_status status = ut_accept_visitor(unit, &kVisitor, &visit);
    ut_free(unit);
    if (status != UT_SUCCESS && visit.problem.empty()) visit.problem = "could not be taken apart into SI units";
    if (visit.problem.empty() && visit.offset != 0.0)
      visit.problem = "is a scale with an offset (a temperature such as degC or degF); mechflow converts values by "
                      "a factor only: write it in K";
    if (visit.problem.empty() && !(std::isfinite(visit.scale) && visit.scale > 0.0))
      visit.problem = "has no finite positive factor to SI";
    if (!visit.problem.empty()) {
      *error = "unit '" + trimmed + "' " + visit.problem;
      return std::nullopt;
    }
    Unit parsed;
    parsed.text = trimmed;
    parsed.to_si = visit.scale;
    parsed.dimension.exponents = visit.exponents;
    return parsed;
  }

  std::mutex mutex_;
  ut_system* system_ = nullptr;
  std::map<std::string, Parsed> cache_;
};

std::string Exponent(double e) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", e);
  return text;
}

}  // namespace

bool Dimension::SameAs(const Dimension& other) const {
  for (int b = 0; b < kRadian; ++b)
    if (std::abs(exponents[b] - other.exponents[b]) > 1e-9) return false;
  return true;
}

Dimension Dimension::Times(const Dimension& other, double power) const {
  Dimension d;
  for (int b = 0; b < kBases; ++b) d.exponents[b] = exponents[b] + power * other.exponents[b];
  return d;
}

Dimension Dimension::Power(double power) const {
  Dimension d;
  for (int b = 0; b < kBases; ++b) d.exponents[b] = exponents[b] * power;
  return d;
}

std::string Dimension::Text() const {
  std::string text;
  for (int b = 0; b < kBases; ++b) {
    if (std::abs(exponents[b]) < 1e-9) continue;
    text += (text.empty() ? "" : " ") + std::string(kBaseSymbols[b]) +
            (std::abs(exponents[b] - 1.0) < 1e-9 ? "" : "^" + Exponent(exponents[b]));
  }
  return text.empty() ? "1" : text;
}

std::string Dimension::Describe() const {
  // the exact name first (rad/s is an angular velocity), then up to the radian
  for (const Named& n : kNamed)
    if (*this == Dimension{n.exponents}) return n.name;
  for (const Named& n : kNamed)
    if (SameAs(Dimension{n.exponents})) return n.name;
  return "a quantity in " + Text();
}

std::string Dimension::SiUnit() const {
  for (const Named& n : kNamed)
    if (*this == Dimension{n.exponents}) return n.unit;
  return Text();
}

void UseUnitsDatabase(const std::string& xml) {
  const std::lock_guard<std::mutex> lock(DatabaseMutex());
  DatabasePath() = xml;
}

std::optional<Unit> ParseUnit(const std::string& text, std::string* error) {
  return UnitSystem::Instance().Parse(text, error);
}

}  // namespace mechflow::diagrams
