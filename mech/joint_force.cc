#include "mech/joint_force.h"

namespace mechflow::mech {

JointForce::JointForce(std::string name, std::string origin, const Dof& dof, std::unique_ptr<ForceLaw> law)
    : ForceElement(std::move(name), std::move(origin)), q_index_(dof.q_index), v_index_(dof.v_index),
      law_(std::move(law)) {
  DeclareCoordinates({v_index_});
  DeclareDependsOnInputs(law_->depends_on_inputs());
  DeclareSensor("force");
  DeclareSensor("length");
  DeclareSensor("rate");
  if (law_->has_energy()) DeclareSensor("energy");  // stored in its spring
}

void JointForce::Evaluate(const ElementContext& ctx, Loads* loads, std::span<double>,
                          std::span<double> sensors) const {
  const double x = ctx.q[q_index_], v = ctx.v[v_index_];
  const double f = law_->Force(x, v, ctx);
  loads->AddGeneralizedForce(v_index_, f);
  sensors[0] = f;
  sensors[1] = x;
  sensors[2] = v;
  if (law_->has_energy()) sensors[3] = law_->Energy(x, ctx);
}

ElementCoordinate JointForce::Coordinate(const std::string& component) const {
  return component.empty() ? ElementCoordinate::Joint(q_index_, v_index_) : ElementCoordinate{};
}

}  // namespace mechflow::mech
