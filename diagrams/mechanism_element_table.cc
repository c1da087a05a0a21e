// The mechanism elements' half of the element table (diagrams/element_table.h):
// FORMAT.md's "Mechanisms" reference, attribute by attribute.

#include "diagrams/element_table.h"

namespace mechflow::diagrams {
namespace {

// A stick model belongs to the frictional element alone.
const std::pair<std::string, std::string> kNoStick = {
    "stick", "the slider already sticks exactly (its stiffness is the elastic link in series); remove stick"};

std::vector<ElementVariant> LawVariants(const std::string& tag) {
  // On a joint coordinate the units of c, d, x0, f0 follow the coordinate
  // (m or rad), so they are not checked there.
  const bool bipolar = tag == "force";
  const std::string n_m = bipolar ? "N/m" : "", n_s_m = bipolar ? "N s/m" : "", m = bipolar ? "m" : "",
                    n = bipolar ? "N" : "";
  const std::string x = bipolar ? "length" : "coordinate";
  std::vector<ElementVariant> v = {
      {"linear",
       "-c (x - x0) - d v + f0",
       {Opt("c", "0", n_m, "stiffness, >= 0; may use inputs and t"),
        Opt("x0", "the initial " + x, m, "free " + x + "; may use inputs and t"),
        Opt("d", "0", n_s_m, "damping, >= 0; may use inputs and t"),
        Opt("f0", "0", n, "preload; may use inputs and t")}},
      {"points",
       "table(x) - d v",
       {Opt("points", "", "", "\"x1 F1; x2 F2; ...\", x increasing (needed)"),
        Opt("interpolation", "linear", "", "linear or spline"),
        Opt("extrapolation", "linear", "", "linear (the end slopes continue) or clamp"),
        Opt("d", "0", n_s_m, "damping")}},
      {"expression", "as written", {Opt("expression", "", "", "Lua of x, v, t, identifiers and inputs (needed)")}},
      {"frictional",
       "stick / slip+ / slip- modes switched by events",
       {Opt("friction", "0", n, "sliding force (or moment on a rotation), >= 0"),
        Opt("ratio", "1.2", "1", "static over dynamic friction, >= 1"),
        Opt("c", "0", n_m, "stiffness while stuck (not with stick=\"exact\")"),
        Opt("d", "0", n_s_m, "damping while stuck (not with stick=\"exact\")"),
        Opt("stick", "spring", "", "spring (held by c and d) or exact (held by a constraint force)")}},
  };
  if (!bipolar) return v;
  v.push_back({"elastic_friction",
               "a spring c and damper d in series with a Coulomb slider",
               {Opt("friction", "0", "N", "sliding force, >= 0"), Opt("ratio", "1.2", "1", "static over dynamic friction"),
                Opt("c", "0", "N/m", "stiffness of the link in series"),
                Opt("d", "0", "N s/m", "damping of the link in series")},
               {},
               {kNoStick}});
  v.push_back({"elastic_friction2",
               "a spring c1 in series with a slider and a spring c2 in parallel with it",
               {Opt("c1", "0", "N/m", "spring in series, > 0"),
                Opt("c2", "0", "N/m", "spring in parallel with the slider, >= 0"),
                Opt("mu", "0", "1", "dynamic friction coefficient"),
                Opt("mu0", "mu", "1", "static friction coefficient, not below mu"),
                Opt("l0", "the initial length", "m", "free length"),
                Opt("limit", "transmitted", "", "friction limit: transmitted (mu |T|), spring (mu |c2 x2|) or constant"),
                Opt("normal_force", "", "N", "the normal force of limit=\"constant\" (only there)")},
               {},
               {kNoStick}});
  return v;
}

std::vector<ElementVariant> JointVariants() {
  const AttributeSpec axis = Opt("axis", "0 0 1", "", "the axis, in the attachment frame");
  const AttributeSpec locked = Opt("locked", "0", "", "1: the coordinate is held at q0");
  return {
      {"rotational",
       "rv(axis): one coordinate, named after the joint",
       {axis, Opt("q0", "0", "rad", "initial angle"), Opt("v0", "0", "rad/s", "initial rate"), locked}},
      {"translational",
       "tv(axis): one coordinate, named after the joint",
       {axis, Opt("q0", "0", "m", "initial displacement"), Opt("v0", "0", "m/s", "initial rate"), locked}},
      {"fixed", "no coordinate", {}},
      {"cardan6",
       "tv x, tv y, tv z, rv x, rv y, rv z: coordinates j.x j.y j.z j.rx j.ry j.rz",
       {Opt("q0", "0 0 0 0 0 0", "", "six initial coordinates [m, rad]"),
        Opt("v0", "0 0 0 0 0 0", "", "six initial rates [m/s, rad/s]"),
        Opt("locked", "0 0 0 0 0 0", "", "six flags: 1 holds that coordinate")}},
      {"quaternion",
       "a free joint with a unit quaternion",
       {Opt("position", "0 0 0", "m", "initial position"),
        Opt("angles", "0 0 0", "rad", "initial Cardan 1-2-3 angles"),
        Opt("velocity", "0 0 0", "m/s", "initial velocity (joint-frame axes)"),
        Opt("angular_velocity", "0 0 0", "rad/s", "initial angular velocity (body axes)")}},
      {"generalized", "its <et> children, in order", {}, {"et"}},
      {"convel",
       "a constant-velocity joint, always a constraint",
       {Opt("axis1", "0 0 1", "", "shaft axis on body 1 (body axes)"),
        Opt("axis2", "0 0 1", "", "shaft axis on body 2 (body axes)"),
        Opt("reference1", "zero twist at the start", "", "zero-phase direction on body 1"),
        Opt("reference2", "zero twist at the start", "", "zero-phase direction on body 2")}},
  };
}

std::vector<ElementVariant> TransformationVariants() {
  const AttributeSpec axis = Opt("axis", "", "", "the axis, in the frame the transformations before produced (needed)");
  const std::pair<std::string, std::string> no_signal = {
      "signal", "'signal' drives a prescribed transformation; use type \"tt\" or \"rt\""};
  const AttributeSpec signal = Opt("signal", "", "", "the name of a driving input port of width 3 (q, q', q'')");
  return {
      {"tc",
       "a constant translation",
       {axis, Opt("value", "0", "m", "the translation along axis"),
        Opt("vector", "", "m", "the translation as a vector (instead of axis and value)")},
       {},
       {no_signal}},
      {"rc", "a constant rotation", {axis, Opt("value", "0", "rad", "the angle")}, {}, {no_signal}},
      {"tt", "a translation, a function of time or a signal", {axis, Opt("value", "", "m", "a function of t"), signal}},
      {"rt", "a rotation, a function of time or a signal", {axis, Opt("value", "", "rad", "a function of t"), signal}},
      {"tv",
       "a translation, a degree of freedom",
       {axis, Opt("q0", "0", "m", "initial coordinate"), Opt("v0", "0", "m/s", "initial rate"),
        Opt("locked", "0", "", "1: held at q0"), Opt("name", "the joint's name", "", "the coordinate's name")},
       {},
       {no_signal}},
      {"rv",
       "a rotation, a degree of freedom",
       {axis, Opt("q0", "0", "rad", "initial coordinate"), Opt("v0", "0", "rad/s", "initial rate"),
        Opt("locked", "0", "", "1: held at q0"), Opt("name", "the joint's name", "", "the coordinate's name")},
       {},
       {no_signal}},
  };
}

std::vector<ElementVariant> ContactVariants() {
  return {
      {"points_plane", "points of body 1 against a plane of body 2", {Req("points", "m", "\"x y z; x y z; ...\" on body1")}},
      {"circle_plane",
       "a circle of body 1 against a plane of body 2",
       {Opt("centre", "0 0 0", "m", "the circle's centre on body1 (or a point's name)"),
        Opt("circle_normal", "1 0 0", "", "the circle's axis (either sign)"), Opt("radius", "0", "m", "the radius")}},
  };
}

std::vector<ElementVariant> SensorVariants() {
  const AttributeSpec dof = Req("dof", "", "a coordinate's name");
  const AttributeSpec body = Req("body", "", "a body's name");
  const AttributeSpec point = Opt("point", "the body origin", "", "a point on the body [m] (or a point's name)");
  const AttributeSpec component = Opt("component", "all three", "", "x, y or z: one component");
  const AttributeSpec joint = Req("joint", "", "a joint's name (tree or loop-closing)");
  return {
      {"coordinate", "the coordinate (width 1)", {dof}},
      {"velocity", "its rate (width 1)", {dof}},
      {"acceleration", "its acceleration (width 1)", {dof}},
      {"reaction_force", "force on body 2, global axes (width 3)", {joint, component}},
      {"reaction_torque", "moment about body 2's attachment point, global axes (width 3)", {joint, component}},
      {"element",
       "an output of a force element (width 1)",
       {Req("element", "", "the element's name"),
        Opt("quantity", "force", "", "its output: force, energy, work, dissipated, ...")}},
      {"position", "a point's position (width 3)", {body, point, component}},
      {"point_velocity", "a point's velocity (width 3)", {body, point, component}},
      {"point_acceleration", "a point's acceleration (width 3)", {body, point, component}},
      {"angles", "Cardan 1-2-3 angles of the body in the global frame (width 3)", {body, component}},
      {"angular_velocity", "the body's angular velocity (width 3)", {body, component}},
      {"kinetic_energy", "kinetic energy [J] (width 1)", {Opt("body", "the whole mechanism", "", "a body's name")}},
      {"potential_energy", "gravitational energy [J] (width 1)",
       {Opt("body", "the whole mechanism", "", "a body's name")}},
      {"energy_balance", "energy gained minus the elements' and drives' work [J] (width 1)", {}},
  };
}

std::vector<ElementVariant> ShapeVariants() {
  const AttributeSpec axis = Opt("axis", "0 0 1", "", "the axis");
  const AttributeSpec samples = Opt("samples", "100", "", "points along u");
  const AttributeSpec x = Opt("x", "", "", "expression of u (and v) [m]"), y = Opt("y", "", "", "expression [m]"),
                      z = Opt("z", "", "", "expression [m]");
  const AttributeSpec u = Opt("u", "", "", "\"from to\": the range of u"), v = Opt("v", "", "", "\"from to\"");
  return {
      {"box", "a centred box", {Opt("size", "1 1 1", "", "edge lengths along x, y, z [m]")}},
      {"sphere", "a sphere", {Opt("radius", "0.1", "", "[m]")}},
      {"ellipsoid", "an ellipsoid", {Opt("size", "0.1 0.1 0.1", "", "the radii along x, y, z [m]")}},
      {"cylinder",
       "a centred cylinder",
       {Opt("radius", "0.05", "", "[m]"), Opt("length", "0.2", "", "[m]"), axis}},
      {"cone",
       "a cone from its base at the position",
       {Opt("radius", "0.05", "", "base radius [m]"), Opt("radius2", "0", "", "tip radius [m]"),
        Opt("length", "0.2", "", "[m]"), axis}},
      {"plane", "a patch in the shape's x-y plane", {Opt("size", "1 1", "", "edges \"a b\" [m]")}},
      {"gear",
       "a centred gear with trapezoidal teeth",
       {Opt("radius", "0.1", "", "pitch radius [m]"), Opt("width", "0.05", "", "[m]"),
        Opt("tooth_height", "0.2 radius", "", "[m]"), Opt("teeth", "20", "", "number of teeth"),
        Opt("taper", "1", "", "the +axis face's radius over the other's"), Opt("axis", "1 0 0", "", "the axis")}},
      {"surface",
       "a parametric surface",
       {x, y, z, u, v, Opt("samples", "32 16", "", "\"nu nv\"")}},
      {"polyline", "a guide, a path", {Opt("points", "", "", "\"x y z; x y z; ...\", at least two [m]")}},
      {"circle", "a circle in the shape's x-y plane", {Opt("radius", "0.1", "", "[m]")}},
      {"curve", "a parametric curve", {x, y, z, u, samples}},
      {"spring",
       "a helix between two points",
       {Opt("body2", "Base0", "", "the body of point2"), Opt("point1", "0 0 0", "", "on body [m]"),
        Opt("point2", "0 0 0", "", "on body2 [m]"), Opt("radius", "0.03", "", "[m]"),
        Opt("coils", "8", "", "number of coils")}},
  };
}

}  // namespace

std::vector<ElementSpec> MechanismElementSpecs() {
  const AttributeSpec name = Req("name", "", "the element's name");
  const AttributeSpec body1 = Req("body1", "", "body 1's name (Base0: the ground)");
  const AttributeSpec body2 = Req("body2", "", "body 2's name");
  const AttributeSpec point1 = Opt("point1", "0 0 0", "m", "attachment on body1 (or a point's name)");
  const AttributeSpec point2 = Opt("point2", "0 0 0", "m", "attachment on body2 (or a point's name)");
  const AttributeSpec type = Req("type", "", "which kind of element");
  return {
      {"mechanism",
       "a multibody model, one block of the diagram",
       {Req("name", "", "the block's name"), Opt("src", "", "", "a file whose root is this <mechanism>"),
        Opt("gravity", "0 0 -9.81", "m/s^2", "gravitational acceleration"), Opt("comment", "", "", "free text")},
       {"input", "body", "joint", "force", "joint_force", "bushing", "applied_force", "contact", "gearing", "sensor",
        "shape", "include"}},
      {"part",
       "the root of a part file: mechanism elements used by <include part=...>",
       {Req("name", "", "the part's name"), Opt("comment", "", "", "free text")},
       {"parameter", "attach", "body", "joint", "force", "joint_force", "bushing", "applied_force", "contact",
        "gearing", "sensor", "shape", "include"}},
      {"attach", "a body a part refers to but does not own, named where it is included", {Req("name", "", "its name inside")}},
      {"include",
       "a part's elements, their names prefixed with the instance's",
       {Req("part", "", "the part's file"), Req("name", "", "the instance's name"),
        Opt("count", "", "", "make name[0] .. name[count-1]"),
        Opt("attach", "", "", "\"point=body ...\": the bodies its attach points are"),
        Opt("first", "", "", "with count: the attach of name[0]"), Opt("comment", "", "", "free text")},
       {"param"}},
      {"input", "an identifier whose value comes from the input port of its name", {Req("name", "", "an identifier")}},
      {"body",
       "a rigid body",
       {name, Req("mass", "kg", "mass, > 0"), Req("inertia", "kg m^2", "\"Ixx Iyy Izz\" about the centre of mass"),
        Opt("com", "0 0 0", "m", "centre of mass"), Opt("products", "0 0 0", "kg m^2", "\"Ixy Ixz Iyz\""),
        Opt("comment", "", "", "free text")},
       {"point"}},
      {"point", "a named point of a body", {name, Req("at", "m", "its position in the body frame")}},
      {"joint",
       "a joint from a frame on body 1 to one on body 2",
       {name, type, body1, body2, point1, point2, Opt("rotation1", "0 0 0", "rad", "Cardan 1-2-3 angles of frame 1"),
        Opt("rotation2", "0 0 0", "rad", "Cardan 1-2-3 angles of frame 2")},
       {},
       "type",
       JointVariants()},
      {"et", "an elementary transformation of a generalized joint", {Req("type", "", "tc rc tt rt tv rv")}, {}, "type",
       TransformationVariants()},
      {"force",
       "a force along the line between two body points (positive pushes them apart)",
       {name, type, body1, body2, point1, point2},
       {},
       "type",
       LawVariants("force")},
      {"joint_force",
       "a force or moment on a joint coordinate",
       {name, type, Req("dof", "", "a coordinate's name")},
       {},
       "type",
       LawVariants("joint_force")},
      {"bushing",
       "springs and dampers along and about the axes of body 1",
       {name, body1, body2, point1, Opt("point2", "the point of body 2 at point1 initially", "m", "on body2"),
        Opt("c", "0 0 0", "N/m", "three stiffnesses"), Opt("d", "0 0 0", "N s/m", "three dampings"),
        Opt("ca", "0 0 0", "N m/rad", "three angular stiffnesses"),
        Opt("da", "0 0 0", "N m s/rad", "three angular dampings"), Opt("preload", "0 0 0", "N", "preload force"),
        Opt("preload_moment", "0 0 0", "N m", "preload moment")}},
      {"applied_force",
       "a force and torque on a body point (may use inputs and t)",
       {name, Req("body", "", "the body's name"), Opt("point", "0 0 0", "m", "the point (or a point's name)"),
        Opt("force", "0 0 0", "N", "three components"), Opt("torque", "0 0 0", "N m", "three components"),
        Opt("axes", "global", "", "global or body")}},
      {"contact",
       "a compliant contact with Coulomb friction (regularised or exact stick)",
       {name, type, body1, body2, Opt("plane_point", "0 0 0", "m", "a point of the plane on body2"),
        Opt("normal", "0 0 1", "", "the plane's external normal"),
        Opt("stiffness", "0", "", "c [N/m^exponent]"), Opt("exponent", "1", "1", "n >= 1"),
        Opt("damping", "0", "N s/m", "damping"),
        Opt("damping_depth", "0", "m", "penetration over which damping builds up (0: constant; needs damping)"),
        Opt("mu", "0", "1", "friction coefficient while sliding"),
        Opt("mu_static", "mu", "1", "at rest, not below mu"),
        Opt("stribeck_velocity", "1e-3", "m/s", "the coefficient falls from mu_static to mu (needs friction)"),
        Opt("v_eps", "1e-4", "m/s", "regularisation velocity (needs friction; not with stick=\"exact\")"),
        Opt("stick", "regularised", "",
            "regularised (friction a steep function of the slip) or exact (a point at rest held by a constraint "
            "force; needs friction)"),
        Opt("max_penetration", "0.05", "m", "a sanity bound; deeper warns")},
       {},
       "type",
       ContactVariants()},
      {"gearing",
       "a gear mesh between two bodies (spur or bevel)",
       {name, body1, body2, Opt("centre1", "0 0 0", "m", "gear 1's centre on body1"),
        Opt("axis1", "1 0 0", "", "gear 1's axis"), Opt("centre2", "0 0 0", "m", "gear 2's centre on body2"),
        Opt("axis2", "axis1's components", "", "gear 2's axis"), Opt("ratio", "1", "1", "i = r1/r2"),
        Opt("clearance", "0", "m", "total backlash along the pitch tangent"),
        Opt("stiffness", "0", "N/m", "mesh stiffness"), Opt("damping", "0", "N s/m", "mesh damping")}},
      {"sensor", "an output port of the mechanism", {name, Req("kind", "", "what it measures")}, {}, "kind",
       SensorVariants()},
      {"shape",
       "what a body looks like in the animation (no mass)",
       {Req("type", "", "which shape"), Opt("name", "type and number", "", "shown on hover"),
        Opt("body", "Base0", "", "the body it hangs on"), Opt("position", "0 0 0", "", "in the body frame [m]"),
        Opt("rotation", "0 0 0", "", "Cardan 1-2-3 angles [rad]"), Opt("color", "#8899aa", "", "#rrggbb"),
        Opt("opacity", "1", "", "0..1")},
       {},
       "type",
       ShapeVariants()},
  };
}

}  // namespace mechflow::diagrams
