#include "diagrams/attribute_units.h"

#include <initializer_list>

namespace mechflow::diagrams {
namespace {

struct Row {
  const char* tag;
  const char* types;  // the types the row is for, space-separated; "" any
  const char* attributes;  // space-separated
  const char* unit;
};

// FORMAT.md's element reference, attribute by attribute.
constexpr Row kTable[] = {
    {"mechanism", "", "gravity", "m/s^2"},
    {"body", "", "mass", "kg"},
    {"body", "", "com", "m"},
    {"body", "", "inertia products", "kg m^2"},
    {"point", "", "at", "m"},
    {"joint", "", "point1 point2", "m"},
    {"joint", "", "rotation1 rotation2", "rad"},
    {"joint", "rotational", "q0", "rad"},
    {"joint", "rotational", "v0", "rad/s"},
    {"joint", "translational", "q0", "m"},
    {"joint", "translational", "v0", "m/s"},
    {"joint", "quaternion", "position", "m"},
    {"joint", "quaternion", "angles", "rad"},
    {"joint", "quaternion", "velocity", "m/s"},
    {"joint", "quaternion", "angular_velocity", "rad/s"},
    {"et", "tc tt", "value vector", "m"},
    {"et", "rc rt", "value", "rad"},
    {"et", "tv", "q0", "m"},
    {"et", "tv", "v0", "m/s"},
    {"et", "rv", "q0", "rad"},
    {"et", "rv", "v0", "rad/s"},
    {"force", "", "point1 point2", "m"},
    {"force", "linear", "c", "N/m"},
    {"force", "linear points", "d", "N s/m"},
    {"force", "linear", "x0", "m"},
    {"force", "linear", "f0", "N"},
    {"force", "frictional elastic_friction", "friction", "N"},
    {"force", "frictional elastic_friction", "c", "N/m"},
    {"force", "frictional elastic_friction", "d", "N s/m"},
    {"force", "frictional elastic_friction", "ratio", "1"},
    {"force", "elastic_friction2", "c1 c2", "N/m"},
    {"force", "elastic_friction2", "l0", "m"},
    {"force", "elastic_friction2", "normal_force", "N"},
    {"force", "elastic_friction2", "mu mu0", "1"},
    {"joint_force", "frictional", "ratio", "1"},
    {"bushing", "", "point1 point2", "m"},
    {"bushing", "", "c", "N/m"},
    {"bushing", "", "d", "N s/m"},
    {"bushing", "", "ca", "N m/rad"},
    {"bushing", "", "da", "N m s/rad"},
    {"bushing", "", "preload", "N"},
    {"bushing", "", "preload_moment", "N m"},
    {"gearing", "", "centre1 centre2 clearance", "m"},
    {"gearing", "", "ratio", "1"},
    {"gearing", "", "stiffness", "N/m"},
    {"gearing", "", "damping", "N s/m"},
    {"contact", "", "damping", "N s/m"},
    {"contact", "", "damping_depth max_penetration radius plane_point centre points", "m"},
    {"contact", "", "mu mu_static exponent", "1"},
    {"contact", "", "stribeck_velocity v_eps", "m/s"},
    {"applied_force", "", "point", "m"},
    {"applied_force", "", "force", "N"},
    {"applied_force", "", "torque", "N m"},
    {"solver", "", "t_start t_end max_step initial_step", "s"},
    {"output", "", "interval", "s"},
};

// True when the space-separated `list` holds `word`.
bool Lists(const char* list, const std::string& word) {
  const std::string padded = " " + std::string(list) + " ";
  return padded.find(" " + word + " ") != std::string::npos;
}

}  // namespace

std::string AttributeUnit(const std::string& tag, const std::string& type, const std::string& attribute) {
  for (const Row& row : kTable)
    if (tag == row.tag && (!*row.types || Lists(row.types, type)) && Lists(row.attributes, attribute)) return row.unit;
  return "";
}

}  // namespace mechflow::diagrams
