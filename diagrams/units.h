#pragma once
// Units of measure: the text of a `unit=` attribute ("deg", "mm", "N/mm",
// "rpm", "kN*m") read by UDUNITS-2 with its standard database, as the factor
// that takes a value to SI and the dimension it has.
//
// Values are SI everywhere inside mechflow; a unit is applied once, when the
// diagram is loaded (identifiers) or written (logged columns). Units with an
// offset (degC, degF), timestamps and logarithmic units are refused: a
// mechanism attribute never needs them, and a factor could not convert them.
//
// The radian is kept as a dimension of its own (UDUNITS does, as a
// dimensionless base unit), so messages can say "an angle"; comparisons
// ignore it, as SI does: an angle attribute takes rad, deg, rev or a plain
// number, and N m/rad is N m.

#include <array>
#include <optional>
#include <string>

namespace mechflow::diagrams {

struct Dimension {
  // the exponents of kg, m, s, A, K, mol, cd and rad (halves come from sqrt)
  enum Base { kKilogram, kMetre, kSecond, kAmpere, kKelvin, kMole, kCandela, kRadian, kBases };
  std::array<double, kBases> exponents{};

  // equal up to the radian
  bool SameAs(const Dimension& other) const;
  bool operator==(const Dimension& other) const { return exponents == other.exponents; }
  Dimension Times(const Dimension& other, double power = 1.0) const;  // this * other^power
  Dimension Power(double power) const;
  bool IsNumber() const { return Dimension().SameAs(*this); }
  // "kg m^2 s^-2", "1" for none
  std::string Text() const;
  // "a length", "an angle", "a stiffness", else "a quantity in kg m^-1"
  std::string Describe() const;
  // the SI unit it is shown in: "m", "rad/s", "N/m", else Text()
  std::string SiUnit() const;
};

struct Unit {
  std::string text;     // as written, trimmed
  double to_si = 1.0;   // value in SI = value in this unit * to_si
  Dimension dimension;
};

// Reads the units database from `xml` (UDUNITS-2's udunits2.xml and the
// files beside it) instead of its default place: an exported FMU carries
// its own copy. Takes effect only before the first ParseUnit of the process.
void UseUnitsDatabase(const std::string& xml);

// Parses `text` with the units database (loaded once, shared by every thread).
// nullopt and *error (what is wrong and what to write instead) when the text
// is no unit or one that no factor converts.
std::optional<Unit> ParseUnit(const std::string& text, std::string* error);

}  // namespace mechflow::diagrams
