#include "mech/applied_force.h"

namespace mechflow::mech {

AppliedForce::AppliedForce(std::string name, std::string origin, int body, Vec3 point, std::array<Parameter, 3> force,
                           std::array<Parameter, 3> torque, bool body_axes)
    : ForceElement(std::move(name), std::move(origin)),
      body_(body),
      point_(point),
      force_(force),
      torque_(torque),
      body_axes_(body_axes) {
  DeclareBodies({body_});
  for (int i = 0; i < 3; ++i) DeclareDependsOnInputs(force_[i].uses_inputs || torque_[i].uses_inputs);
  for (const char* s : {"fx", "fy", "fz", "mx", "my", "mz"}) DeclareSensor(s);
}

void AppliedForce::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>,
                            std::span<double> sensors) const {
  const Kinematics& kin = *ctx.kin;
  Vec3 f, m;
  for (int i = 0; i < 3; ++i) {
    f(i) = force_[i].Get(ctx);
    m(i) = torque_[i].Get(ctx);
    sensors[i] = f(i);
    sensors[3 + i] = m(i);
  }
  if (body_axes_) {
    f = kin.body_pose[body_].R * f;
    m = kin.body_pose[body_].R * m;
  }
  loads->AddForce(kin, body_, PointPosition(kin, body_, point_), f);
  loads->AddTorque(kin, body_, m);
}

}  // namespace mechflow::mech
