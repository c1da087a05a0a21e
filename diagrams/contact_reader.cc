// Contacts of a <mechanism> (diagrams/FORMAT.md, "Force elements").

#include "diagrams/mechanism_reader.h"
#include "mech/circle_plane_contact.h"
#include "mech/points_plane_contact.h"

namespace mechflow::diagrams {

std::unique_ptr<mech::ForceElement> ReadContact(const MechanismReader& r, const ElementDesc& e,
                                                const mech::Model& model) {
  const std::string name = e.Text("name");
  const std::string type = e.Text("type");
  if (type != "points_plane" && type != "circle_plane")
    throw InputError(r.What(e, "type") + ": unknown contact type '" + type + "'; expected points_plane or circle_plane");
  const int b1 = BodyIndex(model, e, "body1"), b2 = BodyIndex(model, e, "body2");
  mech::ContactLaw law;
  law.stiffness = r.Number(e, "stiffness", 0.0);
  law.exponent = r.Number(e, "exponent", 1.0);
  law.damping = r.Number(e, "damping", 0.0);
  law.damping_depth = r.Number(e, "damping_depth", 0.0);
  law.mu = r.Number(e, "mu", 0.0);
  law.mu_static = r.Has(e, "mu_static") ? r.Number(e, "mu_static", 0.0) : law.mu;
  law.stribeck_velocity = r.Number(e, "stribeck_velocity", 1e-3);
  law.v_eps = r.Number(e, "v_eps", 1e-4);
  law.max_penetration = r.Number(e, "max_penetration", mech::ContactLaw::kDefaultMaxPenetration);
  const std::string stick = e.Text("stick", "regularised");
  if (stick != "regularised" && stick != "exact")
    throw InputError(r.What(e, "stick") + ": unknown stick model '" + stick +
                     "'; expected regularised (friction a steep function of the slip) or exact (a point at rest "
                     "held by a constraint force)");
  law.exact_stick = stick == "exact";
  if (law.exact_stick && r.Has(e, "v_eps"))
    throw InputError(r.What(e, "v_eps") + ": with stick=\"exact\" a point at rest is held exactly and sliding "
                     "friction is Coulomb's, so a regularisation velocity would have no effect; remove v_eps, or "
                     "use stick=\"regularised\"");
  // settings of a part of the law that is absent would change nothing
  if (law.mu == 0.0 && law.mu_static == 0.0)
    for (const char* attribute : {"stribeck_velocity", "v_eps", "stick"})
      if (r.Has(e, attribute))
        throw InputError(r.What(e, attribute) + ": shapes the friction, but mu and mu_static are 0 (no friction); "
                         "give mu, or remove " + attribute);
  if (law.damping == 0.0 && r.Has(e, "damping_depth"))
    throw InputError(r.What(e, "damping_depth") + ": ramps up the damping, but damping is 0; give damping, or "
                     "remove damping_depth");
  if (type == "circle_plane")
    return std::make_unique<mech::CirclePlaneContact>(
        name, e.loc.str(), b1, BodyPoint(r, model, e, "centre", b1), r.Vector(e, "circle_normal", Vec3::UnitX()),
        r.Number(e, "radius", 0.0), b2, r.Vector(e, "plane_point", Vec3::Zero()), r.Vector(e, "normal", Vec3::UnitZ()),
        law);
  std::vector<Vec3> points;
  for (const auto& row : Split(e.Text("points"), ";")) {
    r.eval().CheckUnit(row, true, "points", AttributeUnit(e.tag, type, "points"), r.What(e, "points"));
    const auto v = r.eval().Numbers(row, r.What(e, "points"));
    if (v.size() != 3) throw InputError(r.What(e, "points") + ": each point is 'x y z', separated by ';'");
    points.push_back({v[0], v[1], v[2]});
  }
  return std::make_unique<mech::PointsPlaneContact>(name, e.loc.str(), b1, points, b2,
                                                    r.Vector(e, "plane_point", Vec3::Zero()),
                                                    r.Vector(e, "normal", Vec3::UnitZ()), law);
}

}  // namespace mechflow::diagrams
