#pragma once
// Analytic Jacobian of a sliding mechanism (the friction chains' Newton
// matrix without a difference quotient per state).
//
// A sliding mechanism is a sliding model (mech/sliding_structure.h: only
// translations, perpendicular along every path, so M is constant and
// diagonal) without closed loops. Nothing depends on products of velocities:
//   q' = v,   v_i' = (Q_i + constant) / M_ii,   s' = the element states' rates
// with Q the elements' generalized forces. Each element knows its law along
// its coordinate (ForceElement::Derivatives); for a line from point A (body
// 1) to point B (body 2), d = B - A, x = |d|, u = d / x, w = d' and D_c =
// dd/dq_c (+-a_b on the ends' coordinates):
//   dx/dq_c = u.D_c = dx'/dv_c,   dx'/dq_c = (w - (u.w) u).D_c / x
//   Q_r = (u.D_r) f
//   dQ_r/dq_c = (u.D_r)(f_x dx/dq_c + f_v dx'/dq_c) + f (D_r.D_c - (u.D_r)(u.D_c)) / x
//   dQ_r/dv_c = (u.D_r) f_v (u.D_c)
// and an element on a joint coordinate acts on that coordinate alone. At
// zero length a line has no direction (its force must then be zero): its
// entries are left out.
//
// This is the class of the friction chains (bench/README.md P1-P3):
// large, stiff and cheap to differentiate. Mechanisms that turn keep
// difference quotients (or the Krylov solver).

#include <span>
#include <string>
#include <vector>

#include "mech/mechanism.h"
#include "mech/sliding_structure.h"

namespace mechflow::mech {

class SlidingJacobian {
 public:
  // One entry of dx'/dx, mechanism-local state indices; entries may repeat
  // (they add).
  struct Entry {
    int row, column;
    double value;
  };

  // Empty when `mechanism` is a sliding mechanism whose every element gives
  // its derivatives; else why not, as a sentence naming the joint or element.
  static std::string Unavailable(const Mechanism& mechanism);

  // Throws std::logic_error when Unavailable() is not empty.
  explicit SlidingJacobian(const Mechanism& mechanism);

  // dx'/dx at (t, x) in `modes`, inputs held, from the workspace of an
  // EvaluateElements at the same (t, x, inputs, modes) (kinematics,
  // parameters, sensors). Replaces `entries`; allocates nothing once the
  // vector has held this many entries.
  void Evaluate(const Mechanism& mechanism, double t, std::span<const double> x, std::span<const double> modes,
                const MechanismWorkspace& ws, std::vector<Entry>* entries) const;

 private:
  const SlidingStructure* structure_;  // the model's
};

}  // namespace mechflow::mech
