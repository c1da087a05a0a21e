// Force elements of a <mechanism> (diagrams/FORMAT.md, "Force elements"):
// force laws, frictional elements, bushings, gears and applied forces.

#include "diagrams/mechanism_reader.h"
#include "mech/applied_force.h"
#include "mech/bipolar_force.h"
#include "mech/bushing.h"
#include "mech/elastic_friction2_force.h"
#include "mech/elastic_friction_force.h"
#include "mech/frictional_force.h"
#include "mech/gearing.h"
#include "mech/joint_force.h"

namespace mechflow::diagrams {
namespace {

std::unique_ptr<mech::ForceLaw> ReadLaw(const MechanismReader& r, const ElementDesc& e, double initial_x) {
  const std::string type = e.Text("type");
  if (type == "linear") {
    const mech::Parameter c = r.Param(e, "c", 0.0), d = r.Param(e, "d", 0.0);
    RequireAtLeast(r, e, "c", c, 0.0, "the stiffness c must not be negative");
    RequireAtLeast(r, e, "d", d, 0.0, "the damping d must not be negative");
    return std::make_unique<mech::LinearLaw>(c, r.Param(e, "x0", initial_x), d, r.Param(e, "f0", 0.0));
  }
  if (type == "points") {
    if (!r.Has(e, "points")) r.Fail(e, "a points law needs points=\"x1 F1; x2 F2; ...\"");
    std::vector<double> xs, fs;
    for (const auto& row : Split(e.Text("points"), ";")) {
      const std::vector<double> pair = r.eval().Numbers(row, r.What(e, "points"));
      if (pair.size() != 2) throw InputError(r.What(e, "points") + ": each point is 'x F'");
      xs.push_back(pair[0]);
      fs.push_back(pair[1]);
    }
    const std::string interp = e.Text("interpolation", "linear"), extrap = e.Text("extrapolation", "linear");
    if (interp != "linear" && interp != "spline") throw InputError(r.What(e, "interpolation") + ": linear or spline");
    if (extrap != "linear" && extrap != "clamp") throw InputError(r.What(e, "extrapolation") + ": linear or clamp");
    return std::make_unique<mech::PointsLaw>(
        xs, fs, interp == "spline" ? mech::PointsLaw::Interpolation::kSpline : mech::PointsLaw::Interpolation::kLinear,
        extrap == "clamp" ? mech::PointsLaw::Extrapolation::kClamp : mech::PointsLaw::Extrapolation::kLinear,
        r.Param(e, "d", 0.0), r.What(e, "points"));
  }
  if (type == "expression") {
    if (!r.Has(e, "expression")) r.Fail(e, "an expression law needs expression=\"...\" (of x, v, t)");
    return std::make_unique<mech::ExpressionLaw>(r.Function(e.Text("expression"), {"x", "v", "t"}, r.What(e, "expression")),
                                                 r.MentionsInput(e.Text("expression")));
  }
  const std::vector<std::string> laws = {"linear",     "points",           "expression",
                                         "frictional", "elastic_friction", "elastic_friction2"};
  throw InputError(r.What(e, "type") + ": unknown law '" + type + "'" + blocks::DidYouMean(type, laws) +
                   "; expected one of " + blocks::JoinNames(laws));
}

mech::FrictionalParameters ReadFrictional(const MechanismReader& r, const ElementDesc& e) {
  mech::FrictionalParameters p;
  const std::string stick = e.Text("stick", "spring");
  if (stick != "spring" && stick != "exact")
    throw InputError(r.What(e, "stick") + ": unknown stick model '" + stick +
                     "'; expected spring (held by the stiffness c and damping d) or exact (held by a constraint "
                     "force)");
  p.exact_stick = stick == "exact";
  if (p.exact_stick && (r.Has(e, "c") || r.Has(e, "d")))
    throw InputError(r.What(e, r.Has(e, "c") ? "c" : "d") +
                     ": with stick=\"exact\" the element is held by a constraint force, so a stick stiffness c "
                     "and damping d would have no effect; remove them, or use stick=\"spring\"");
  p.friction = r.Param(e, "friction", 0.0);
  p.ratio = r.Param(e, "ratio", 1.2);
  p.stiffness = r.Param(e, "c", 0.0);
  p.damping = r.Param(e, "d", 0.0);
  RequireAtLeast(r, e, "friction", p.friction, 0.0, "the friction force must not be negative");
  RequireAtLeast(r, e, "ratio", p.ratio, 1.0,
                 "the ratio of static to dynamic friction must be at least 1 (static below dynamic friction)");
  RequireAtLeast(r, e, "c", p.stiffness, 0.0, "the stiffness c must not be negative");
  RequireAtLeast(r, e, "d", p.damping, 0.0, "the damping d must not be negative");
  return p;
}

}  // namespace

std::unique_ptr<mech::ForceElement> ReadElement(const MechanismReader& r, const ElementDesc& e,
                                                const mech::Model& model, const mech::Kinematics& kin0) {
  const std::string name = e.Text("name");
  if (e.tag == "force") {
    const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
    const Vec3 p1 = BodyPoint(r, model, e, "point1", b1), p2 = BodyPoint(r, model, e, "point2", b2);
    if (e.Text("type") == "frictional" || e.Text("type") == "elastic_friction") {
      const mech::FrictionalParameters p = ReadFrictional(r, e);
      if (e.Text("type") == "elastic_friction")
        return std::make_unique<mech::ElasticFrictionForce>(name, e.loc.str(), b1, p1, b2, p2, p);
      return std::make_unique<mech::FrictionalForce>(name, e.loc.str(), b1, p1, b2, p2, p);
    }
    if (e.Text("type") == "elastic_friction2") {
      mech::ElasticFriction2Parameters p;
      p.series_stiffness = r.Param(e, "c1", 0.0);
      p.parallel_stiffness = r.Param(e, "c2", 0.0);
      p.mu = r.Param(e, "mu", 0.0);
      p.mu0 = r.Has(e, "mu0") ? r.Param(e, "mu0", 0.0) : p.mu;
      p.free_length = r.Param(e, "l0", mech::BipolarLength(kin0, b1, p1, b2, p2));
      const std::string limit = e.Text("limit", "transmitted");
      const std::vector<std::string> limits = {"transmitted", "spring", "constant"};
      if (std::find(limits.begin(), limits.end(), limit) == limits.end())
        throw InputError(r.What(e, "limit") + ": unknown friction limit '" + limit + "'" +
                         blocks::DidYouMean(limit, limits) + "; expected one of " + blocks::JoinNames(limits));
      p.limit = limit == "spring" ? mech::FrictionLimit::kSpring
                : limit == "constant" ? mech::FrictionLimit::kConstant
                                      : mech::FrictionLimit::kTransmitted;
      if (p.limit == mech::FrictionLimit::kConstant && !r.Has(e, "normal_force"))
        r.Fail(e, "the constant friction limit needs normal_force (the limit is mu * normal_force)");
      if (p.limit != mech::FrictionLimit::kConstant && r.Has(e, "normal_force"))
        throw InputError(r.What(e, "normal_force") + ": is the normal force of limit=\"constant\" only; with limit=\"" +
                         limit + "\" it would change nothing; give limit=\"constant\", or remove normal_force");
      p.normal_force = r.Param(e, "normal_force", 0.0);
      return std::make_unique<mech::ElasticFriction2Force>(name, e.loc.str(), b1, p1, b2, p2, p);
    }
    return std::make_unique<mech::BipolarForce>(name, e.loc.str(), b1, p1, b2, p2,
                                                ReadLaw(r, e, mech::BipolarLength(kin0, b1, p1, b2, p2)));
  }
  if (e.tag == "joint_force") {
    const mech::Dof& dof = model.dofs()[DofIndex(model, e, "dof")];
    if (e.Text("type") == "frictional")
      return std::make_unique<mech::FrictionalForce>(name, e.loc.str(), dof, ReadFrictional(r, e));
    if (e.Text("type") == "elastic_friction" || e.Text("type") == "elastic_friction2")
      throw InputError(r.What(e, "type") + ": '" + e.Text("type") +
                       "' acts between two body points (<force>); on a joint coordinate use type=\"frictional\" "
                       "(friction, ratio, and the stick stiffness c and damping d)");
    return std::make_unique<mech::JointForce>(name, e.loc.str(), dof, ReadLaw(r, e, model.initial_q()[dof.q_index]));
  }
  if (e.tag == "bushing") {
    const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
    const Vec3 p1 = BodyPoint(r, model, e, "point1", b1);
    // Without point2: the point of body 2 that coincides with P1 initially.
    const Vec3 p2 = r.Has(e, "point2") ? BodyPoint(r, model, e, "point2", b2)
                                       : kin0.body_pose[b2].Inverse() * mech::PointPosition(kin0, b1, p1);
    mech::BushingParameters p;
    auto three = [&](const char* attribute, std::array<double, 3>* out) {
      if (!r.Has(e, attribute)) return;
      const Vec3 v = r.Vector(e, attribute, Vec3::Zero());
      for (int i = 0; i < 3; ++i)
        RequireAtLeast(r, e, attribute, v(i), 0.0, "stiffness and damping must not be negative");
      *out = {v.x(), v.y(), v.z()};
    };
    three("c", &p.stiffness);
    three("d", &p.damping);
    three("ca", &p.angular_stiffness);
    three("da", &p.angular_damping);
    p.preload_force = r.Vector(e, "preload", Vec3::Zero());
    p.preload_moment = r.Vector(e, "preload_moment", Vec3::Zero());
    return std::make_unique<mech::Bushing>(name, e.loc.str(), b1, p1, b2, p2, p, kin0);
  }
  if (e.tag == "gearing") {
    const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
    mech::GearParameters p;
    p.ratio = r.Number(e, "ratio", 1.0);
    p.clearance = r.Number(e, "clearance", 0.0);
    p.stiffness = r.Number(e, "stiffness", 0.0);
    p.damping = r.Number(e, "damping", 0.0);
    // axis2 defaults to axis1's components (in gear 2's frame)
    const Vec3 axis1 = r.Vector(e, "axis1", Vec3::UnitX());
    return std::make_unique<mech::Gearing>(name, e.loc.str(), b1, BodyPoint(r, model, e, "centre1", b1), axis1, b2,
                                           BodyPoint(r, model, e, "centre2", b2), r.Vector(e, "axis2", axis1), p,
                                           kin0);
  }
  if (e.tag == "contact") return ReadContact(r, e, model);
  // applied_force: components may follow inputs
  const int body = BodyIndex(model, e, "body");
  auto components = [&](const char* attribute) {
    std::array<mech::Parameter, 3> out{};
    if (!r.Has(e, attribute)) return out;
    const std::vector<std::string> parts = Split(e.Text(attribute), " \t,");
    if (parts.size() != 3) throw InputError(r.What(e, attribute) + ": expected three components");
    for (int i = 0; i < 3; ++i) {
      const std::string component = std::string(attribute) + "[" + std::to_string(i) + "]";
      ElementDesc one{e.tag, {{component, parts[i], e.Find(attribute)->loc}, {"name", name, e.loc}}, {}, e.loc};
      out[i] = r.Param(one, component, 0.0);
    }
    return out;
  };
  const std::string axes = e.Text("axes", "global");
  if (axes != "global" && axes != "body") throw InputError(r.What(e, "axes") + ": 'global' or 'body'");
  return std::make_unique<mech::AppliedForce>(name, e.loc.str(), body, BodyPoint(r, model, e, "point", body),
                                              components("force"), components("torque"), axes == "body");
}

}  // namespace mechflow::diagrams
