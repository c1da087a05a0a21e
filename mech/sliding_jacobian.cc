#include "mech/sliding_jacobian.h"

#include <stdexcept>

#include "mech/bipolar_force.h"

namespace mechflow::mech {
namespace {

// A body moves along at most three perpendicular axes.
constexpr int kMaxPath = 3;

// One end of a line on a coordinate: dd/dq = D.
struct End {
  int q, v;  // the coordinate's position and velocity indices
  Vec3 D;
};

}  // namespace

std::string SlidingJacobian::Unavailable(const Mechanism& mechanism) {
  const Model& model = mechanism.model();
  if (!mechanism.constraints().empty()) return "it has a closed loop or a constraint";
  if (!model.sliding()) return model.not_sliding();
  if (mechanism.tracks_work() || mechanism.drive_work_state() >= 0) return "it integrates work (energy sensors)";
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    const ForceElement& element = mechanism.element(e);
    const std::string name = "element '" + element.name() + "' (" + element.origin() + ")";
    const DerivativeSupport support = element.derivative_support();
    if (support == DerivativeSupport::kNone) return name + " gives no derivatives";
    if (support == DerivativeSupport::kStateIndependent) {
      if (element.num_states() > 0) return name + " has states but gives no derivatives";
      continue;
    }
    const ElementCoordinate::Kind kind = element.Coordinate("").kind;
    if (kind != ElementCoordinate::Kind::kLine && kind != ElementCoordinate::Kind::kJoint)
      return name + " acts along no line or joint coordinate";
    if (element.num_states() > ElementDerivatives::kMaxStates) return name + " has too many states";
  }
  return "";
}

SlidingJacobian::SlidingJacobian(const Mechanism& mechanism) : structure_(mechanism.model().sliding()) {
  const std::string why = Unavailable(mechanism);
  if (!why.empty()) throw std::logic_error("SlidingJacobian: not a sliding mechanism: " + why);
}

void SlidingJacobian::Evaluate(const Mechanism& mechanism, double t, std::span<const double> x,
                               std::span<const double> modes, const MechanismWorkspace& ws,
                               std::vector<Entry>* entries) const {
  const Model& model = mechanism.model();
  const Kinematics& kin = ws.kin;
  const int nq = model.nq();
  entries->clear();
  for (const Dof& dof : model.dofs()) entries->push_back({dof.q_index, nq + dof.v_index, 1.0});
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    const ForceElement& element = mechanism.element(e);
    if (element.derivative_support() != DerivativeSupport::kAlongCoordinate) continue;
    const ElementCoordinate coordinate = element.Coordinate("");
    const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, ws, e);
    const int first_state = mechanism.state_offset(e), ns = element.num_states();
    ElementDerivatives d;
    if (coordinate.kind == ElementCoordinate::Kind::kJoint) {
      const int c = coordinate.v_index, row = nq + c;
      element.Derivatives(ctx, x[coordinate.q_index], x[nq + c], &d);
      const double inverse_mass = 1.0 / structure_->coordinate_mass[c];
      entries->push_back({row, coordinate.q_index, d.force_x * inverse_mass});
      entries->push_back({row, row, d.force_v * inverse_mass});
      for (int k = 0; k < ns; ++k) {
        entries->push_back({row, first_state + k, d.force_s[k] * inverse_mass});
        entries->push_back({first_state + k, coordinate.q_index, d.rate_x[k]});
        entries->push_back({first_state + k, row, d.rate_v[k]});
        for (int m = 0; m < ns; ++m) entries->push_back({first_state + k, first_state + m, d.rate_s[k][m]});
      }
      continue;
    }
    const BipolarGeometry g = MeasureBipolar(kin, coordinate.body1, coordinate.point1, coordinate.body2,
                                             coordinate.point2);
    element.Derivatives(ctx, g.x, g.v, &d);
    for (int k = 0; k < ns; ++k)
      for (int m = 0; m < ns; ++m) entries->push_back({first_state + k, first_state + m, d.rate_s[k][m]});
    if (!(g.x > 0.0)) continue;  // no direction (see the header)
    End ends[2 * kMaxPath];
    int num_ends = 0;
    for (const auto& [body, sign] : {std::pair{coordinate.body2, 1.0}, std::pair{coordinate.body1, -1.0}}) {
      for (int k = structure_->path_start[body]; k < structure_->path_start[body + 1]; ++k) {
        const int i = structure_->path_segments[k];
        const Segment& seg = model.segments()[i];
        ends[num_ends++] = {seg.q_index, seg.v_index, sign * structure_->axis[i]};
      }
    }
    const Vec3 w = PointVelocity(kin, coordinate.body2, coordinate.point2) -
                   PointVelocity(kin, coordinate.body1, coordinate.point1);
    const Vec3 w_across = (w - g.u.dot(w) * g.u) / g.x;  // dx'/dd
    const double f = ws.sensors[mechanism.sensor_offset(e) + coordinate.force_sensor] * coordinate.force_sign;
    for (int i = 0; i < num_ends; ++i) {
      const End& r = ends[i];
      const double ur = g.u.dot(r.D), inverse_mass = 1.0 / structure_->coordinate_mass[r.v];
      const int row = nq + r.v;
      for (int j = 0; j < num_ends; ++j) {
        const End& c = ends[j];
        const double uc = g.u.dot(c.D), rate_q = w_across.dot(c.D);
        const double dq = ur * (d.force_x * uc + d.force_v * rate_q) + f * (r.D.dot(c.D) - ur * uc) / g.x;
        entries->push_back({row, c.q, dq * inverse_mass});
        entries->push_back({row, nq + c.v, ur * d.force_v * uc * inverse_mass});
      }
      for (int k = 0; k < ns; ++k) entries->push_back({row, first_state + k, ur * d.force_s[k] * inverse_mass});
    }
    for (int k = 0; k < ns; ++k) {
      for (int j = 0; j < num_ends; ++j) {
        const End& c = ends[j];
        const double uc = g.u.dot(c.D), rate_q = w_across.dot(c.D);
        entries->push_back({first_state + k, c.q, d.rate_x[k] * uc + d.rate_v[k] * rate_q});
        entries->push_back({first_state + k, nq + c.v, d.rate_v[k] * uc});
      }
    }
  }
}

}  // namespace mechflow::mech
