#pragma once
// The SI units that attributes of a diagram are in, where the attribute
// alone decides it (read from the element table, diagrams/element_table.h): a body's mass is in kg, a rotational
// joint's q0 in rad, a linear force law's c in N/m, the solver's t_end in s.
// An identifier used as such an attribute must have that dimension
// (diagrams/unit_check.h); attributes whose unit depends on more (a
// joint_force's c is N/m or N m/rad by its coordinate, a contact's stiffness
// N/m^n by its exponent) are not listed and not checked.

#include <string>

namespace mechflow::diagrams {

// The SI unit of `attribute` of element `tag` of type `type` (a joint's,
// force's, <et>'s type; "" for none), e.g. "kg", "rad/s", "N s/m"; "" when
// the table does not know it. Solver and output settings are tag "solver"
// and "output".
std::string AttributeUnit(const std::string& tag, const std::string& type, const std::string& attribute);

}  // namespace mechflow::diagrams
