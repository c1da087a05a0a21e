// The exact-stick holds of a mechanism (mech/exact_stick.h): which holds
// stick, their holding forces in a full evaluation, the velocities they keep
// at zero, and the slip directions contacts record.

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mech/errors.h"
#include "mech/mechanism.h"
#include "mech/mechanism_parts.h"

namespace mechflow::mech {
namespace {

// Which of element e's holds global hold g is.
int LocalHold(const Mechanism& mechanism, int g) { return g - mechanism.hold_offset(mechanism.hold_element(g)); }

// The stuck holds' relative accelerations after a dynamics pass, into `out`.
void StuckAccelerations(const Mechanism& mechanism, double t, std::span<const double> x,
                        std::span<const double> modes, const MechanismWorkspace& ws, Eigen::VectorXd* out) {
  for (std::size_t i = 0; i < ws.stick.stuck.size(); ++i) {
    const int g = ws.stick.stuck[i], e = mechanism.hold_element(g);
    const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, ws, e);
    (*out)(static_cast<Eigen::Index>(i)) = mechanism.element(e).StickAcceleration(ctx, LocalHold(mechanism, g), ws.dyn,
                                                                                  ws.vdot);
  }
}

// Measures S (mech/exact_stick.h) by one dynamics pass per stuck hold with
// its probe force added to ws->loads_without_holds; the caller has a0.
void MeasureHoldResponse(const Mechanism& mechanism, double t, std::span<const double> x,
                         std::span<const double> modes, MechanismWorkspace* ws) {
  StickWorkspace& s = ws->stick;
  const int k = static_cast<int>(s.stuck.size());
  for (int j = 0; j < k; ++j) {
    const int g = s.stuck[j], e = mechanism.hold_element(g);
    ws->loads = ws->loads_without_holds;
    mechanism.element(e).ApplyStickForce(MakeElementContext(mechanism, t, x, modes, *ws, e), LocalHold(mechanism, g),
                                         s.probe[g], &ws->loads);
    SolveDynamics(mechanism, ws, false);
    for (int i = 0; i < k; ++i) {
      const int gi = s.stuck[i], ei = mechanism.hold_element(gi);
      const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, *ws, ei);
      s.S(i, j) = (mechanism.element(ei).StickAcceleration(ctx, LocalHold(mechanism, gi), ws->dyn, ws->vdot) - s.a0(i)) /
                  s.probe[g];
    }
  }
}

// Solves for the forces of the stuck holds (ws->stick.f); a hold that no
// force can keep at rest is an error naming it.
void SolveHolds(const Mechanism& mechanism, double t, MechanismWorkspace* ws) {
  const int failed = SolveHoldingForces(&ws->stick);
  if (failed < 0) return;
  const int g = ws->stick.stuck[failed];
  const ForceElement& element = mechanism.element(mechanism.hold_element(g));
  if (!element.UnholdableIsError()) return;
  std::ostringstream out;
  out << element.origin() << (element.origin().empty() ? "" : ": ") << element.HoldName(LocalHold(mechanism, g))
      << " sticks, but no holding force can keep it at rest at t = " << t
      << ": the motion it holds is driven by what no force changes (a prescribed motion, a locked coordinate, "
         "or other holds that disagree); let it slide (stick=\"regularised\") or free that motion";
  throw SimulationError(out.str());
}

}  // namespace

void FindStuck(const Mechanism& mechanism, double t, std::span<const double> x, std::span<const double> modes,
               MechanismWorkspace* ws) {
  StickWorkspace& s = ws->stick;
  s.stuck.clear();
  ws->holding.clear();
  for (int e : mechanism.exact_stick_elements()) {
    const ForceElement& element = mechanism.element(e);
    const int first = mechanism.hold_offset(e);
    if (!modes.empty()) {
      const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, *ws, e);
      for (int h = 0; h < element.num_holds(); ++h) {
        if (!element.StuckExactly(ctx, h)) continue;
        s.stuck.push_back(first + h);
        if (ws->holding.empty() || ws->holding.back() != e) ws->holding.push_back(e);
      }
    }
    for (int h = 0; h < element.num_holds(); ++h) s.force[first + h] = 0.0;
  }
}

void EvaluateElementsHoldingLast(const Mechanism& mechanism, double t, std::span<const double> x,
                                 std::span<const double> inputs, std::span<const double> modes,
                                 MechanismWorkspace* ws, std::span<double> all_rates) {
  EvaluatePositions(mechanism, t, x, ws);
  SetParameterArgs(t, inputs, ws);
  ws->loads.Clear();
  if (mechanism.tracks_work()) ws->loads.TrackPower(x.subspan(mechanism.model().nq(), mechanism.model().nv()));
  auto next_holding = ws->holding.begin();
  for (int e = 0; e < mechanism.num_elements(); ++e) {
    if (next_holding != ws->holding.end() && *next_holding == e) {
      ++next_holding;
      continue;
    }
    EvaluateElement(mechanism, e, t, x, modes, ws, all_rates);
  }
  ws->loads_before_holds = ws->loads;
  for (const int e : ws->holding) EvaluateElement(mechanism, e, t, x, modes, ws, all_rates);
}

void HoldStuckElements(const Mechanism& mechanism, double t, std::span<const double> x,
                       std::span<const double> modes, MechanismWorkspace* ws, std::span<double> all_rates) {
  StickWorkspace& s = ws->stick;
  ws->loads_without_holds = ws->loads;
  SolveDynamics(mechanism, ws, false);
  StuckAccelerations(mechanism, t, x, modes, *ws, &s.a0);
  MeasureHoldResponse(mechanism, t, x, modes, ws);
  SolveHolds(mechanism, t, ws);
  for (std::size_t i = 0; i < s.stuck.size(); ++i) s.force[s.stuck[i]] = s.f(static_cast<Eigen::Index>(i));
  ws->loads = ws->loads_before_holds;
  for (int e : ws->holding) EvaluateElement(mechanism, e, t, x, modes, ws, all_rates);
}

bool AnyStuckExactly(const Mechanism& mechanism, double t, std::span<const double> x, std::span<const double> modes,
                     const MechanismWorkspace& ws) {
  if (modes.empty()) return false;
  for (int e : mechanism.exact_stick_elements()) {
    const ForceElement& element = mechanism.element(e);
    const ElementContext ctx = MakeElementContext(mechanism, t, x, modes, ws, e);
    for (int h = 0; h < element.num_holds(); ++h)
      if (element.StuckExactly(ctx, h)) return true;
  }
  return false;
}

void FollowSlips(const Mechanism& mechanism, double t, std::span<const double> x, std::span<double> modes,
                 MechanismWorkspace* ws) {
  EvaluatePositions(mechanism, t, x, ws);
  for (int e : mechanism.exact_stick_elements()) {
    const ForceElement& element = mechanism.element(e);
    element.FollowSlip(MakeElementContext(mechanism, t, x, modes, *ws, e),
                       modes.subspan(mechanism.mode_offset(e), element.num_modes()));
  }
}

bool ZeroStuckVelocities(const Mechanism& mechanism, double t, std::span<double> x, std::span<const double> modes,
                         MechanismWorkspace* ws) {
  if (mechanism.exact_stick_elements().empty() || modes.empty()) return false;
  StickWorkspace& s = ws->stick;
  // The probes' sizes: the holding forces of the step just taken, so that S's
  // differences lose no digits to a large load. Changed between steps only:
  // within a step (its Newton iterations and Jacobian) the right-hand side
  // must be one function of the state, and a probe following every
  // evaluation's forces made it depend on the evaluations before (round-off
  // that kept the Falling cube rocking at rest, its Newton iterations failing).
  for (std::size_t g = 0; g < s.probe.size(); ++g) s.probe[g] = std::max(1.0, std::abs(s.force[g]));
  EvaluatePositions(mechanism, t, x, ws);
  FindStuck(mechanism, t, x, modes, ws);
  const int k = static_cast<int>(s.stuck.size());
  double largest = 0.0;
  for (int i = 0; i < k; ++i) {
    const int g = s.stuck[i], e = mechanism.hold_element(g);
    s.f(i) = mechanism.element(e).HoldVelocity(MakeElementContext(mechanism, t, x, modes, *ws, e),
                                               LocalHold(mechanism, g));
    largest = std::max(largest, std::abs(s.f(i)));
  }
  // round-off of a velocity already zeroed: no change, so that settling the modes ends
  const int nq = mechanism.model().nq();
  double speed = 1.0;
  for (int j = 0; j < mechanism.model().nv(); ++j) speed = std::max(speed, std::abs(x[nq + j]));
  if (!(largest > 1e-13 * speed)) return false;
  // S does not depend on the loads: measured from none
  ws->loads.Clear();
  ws->loads_without_holds = ws->loads;
  SolveDynamics(mechanism, ws, false);
  ws->vdot_free = ws->vdot;
  StuckAccelerations(mechanism, t, x, modes, *ws, &s.a0);
  MeasureHoldResponse(mechanism, t, x, modes, ws);
  for (int i = 0; i < k; ++i) s.a0(i) = s.f(i);
  SolveHoldingForces(&s);  // velocities no impulse can reach (redundant and at odds) stay: least squares
  ws->loads = ws->loads_without_holds;
  for (int i = 0; i < k; ++i) {
    const int g = s.stuck[i], e = mechanism.hold_element(g);
    mechanism.element(e).ApplyStickForce(MakeElementContext(mechanism, t, x, modes, *ws, e), LocalHold(mechanism, g),
                                         s.f(i), &ws->loads);
  }
  SolveDynamics(mechanism, ws, false);
  ws->accelerations_valid = false;
  // what least squares already left where it is (holds at odds) is no change
  double change = 0.0;
  for (int j = 0; j < mechanism.model().nv(); ++j) change = std::max(change, std::abs(ws->vdot[j] - ws->vdot_free[j]));
  if (!(change > 1e-13 * speed)) return false;
  for (int j = 0; j < mechanism.model().nv(); ++j) x[nq + j] += ws->vdot[j] - ws->vdot_free[j];
  return true;
}

}  // namespace mechflow::mech
