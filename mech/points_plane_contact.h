#pragma once
// Points-plane contact (ELEMENTS.md 5.1, 5.2, 5.4): points fixed on body 1
// against an unbounded plane fixed on body 2 (a point P0 and the external
// normal N, normalised).
//
//   penetration  delta_i = -(p_i - P0) . N,   rate delta_i' = -w . N
//   normal force N_i = max(0, c delta^n + D(delta) delta')    (never pulls)
//   D(delta) = d                                  when depth = 0
//            = d * STEP(delta; 0 -> depth)        otherwise (no jump at touch)
//   friction F_t = -mu(|w_t|) N_i w_t / sqrt(|w_t|^2 + v_eps^2)
//            (regularised Coulomb: a loaded body creeps at about
//            v_eps tan(theta)/mu), with a static peak that falls to the
//            sliding value over the Stribeck velocity v_s:
//            mu(s) = mu + (mu_static - mu) exp(-(s / v_s)^2)
// w is the velocity of the point relative to the material point of body 2
// under it. Touching and leaving are events: each point has a mode (in
// contact or not) switched when its penetration crosses zero, so the force
// (and a constant damping's jump) never switches inside a step.
// Sensors: normal (sum of N_i), penetration (largest), slip (speed of the
// most loaded point), friction (size of the summed friction force), energy
// (stored in the contact springs of the points in contact).
//
// With law.exact_stick (stick="exact") the friction is that of
// mech/contact_stick.h instead: the points in contact and at rest hold
// their slips, sliding ones slide by Coulomb's law. The stuck points of one
// contact lie on one body, so their slips are those of one rigid motion in
// the plane: the contact holds that motion -- the slip of the material
// point of body 1 at the stuck points' centroid, holds 0 and 1, and the
// relative spin about the normal, hold 2, while it can be held (two or more
// points pressed) -- rather than each point's two slips (four corners of a
// box would hold three motions eight times over, redundant and, once the
// box has rocked a little on its contacts, nearly but not quite: no force
// decides that). The holding force F (at the centroid) and moment M act on
// the bodies as such; for each point's cone and the sensors they are shared
// as a bolt group shares them, in proportion to the normal forces N_i about
// their centre c:
//   f_i = N_i / sum N  F  +  M_c N_i (n x r_i) / sum N_j |r_j|^2,  r_i = p_i - c,
// M_c being M moved to c; so each point compares its own f_i with its cone
// mu_s N_i, and a uniform pull breaks every point away at once.
// Modes: [touching per point | ContactStick's per point]; crossings:
// [penetration per point | max_penetration | ContactStick's per point];
// sensors also mode_1 ... mode_n (0 open, 1 stuck, 2 sliding).

#include <array>
#include <optional>
#include <vector>

#include "mech/contact_law.h"
#include "mech/contact_stick.h"
#include "mech/force_element.h"

namespace mechflow::mech {

// How deep the global point p lies beyond the plane of body 2 through
// plane_point with unit external normal `normal` (both in body 2's frame).
double PlaneDepth(const Kinematics& kin, int body2, const Vec3& plane_point, const Vec3& normal, const Vec3& p);
// The load warning of contact `name` whose body 1 starts `depth` into the
// plane of body 2; empty within law.max_penetration (a preloaded rest state).
// When body 1's centre of mass lies beyond the plane too, more of the body is
// inside than out: the normal most likely points into the body it should
// hold, and the warning says so (not for a body 1 fixed to the ground, whose
// centre of mass says nothing).
std::string StartPenetrationWarning(const ElementContext& ctx, const std::string& name, const ContactLaw& law,
                                    double depth, int body1, int body2, const Vec3& plane_point, const Vec3& normal);
// What `mechflow modes` says of a contact linearised with these point modes
// (nonzero: touching).
std::string ContactLinearisedAs(std::span<const double> touching_modes, bool exact_stick);

class PointsPlaneContact final : public ForceElement {
 public:
  PointsPlaneContact(std::string name, std::string origin, int body1, std::vector<Vec3> points, int body2,
                     Vec3 plane_point, Vec3 normal, ContactLaw law);
  void Initialize(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  void Evaluate(const ElementContext& ctx, Loads* loads, std::span<double> state_rate,
                std::span<double> sensors) const override;
  ElementCoordinate Coordinate(const std::string& component) const override;
  void ZeroCrossings(const ElementContext& ctx, std::span<double> values) const override;
  void OnCrossing(int index, int direction, const ElementContext& ctx, std::span<double> state,
                  std::span<double> modes) const override;
  // A point exactly on the plane and moving into it is in contact: the solver
  // would not see a crossing that starts at zero.
  bool UpdateModes(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  // At rest: as UpdateModes, and a sliding point (stick="exact") sticks.
  bool ModesAtRest(const ElementContext& ctx, std::span<double> state, std::span<double> modes) const override;
  // The last crossing is the deepest point passing max_penetration.
  std::string CrossingWarning(int index, int direction) const override;
  // The deepest point starts beyond max_penetration.
  std::string StartWarning(const ElementContext& ctx) const override;
  std::string LinearisedAs(std::span<const double> modes) const override;
  std::string CrossingName(int index, int direction) const override;
  // Its points measured once per kinematics (Measured).
  std::unique_ptr<ElementScratch> MakeScratch() const override;

  // Exact stick (law.exact_stick): the stuck points' common slip and spin (above).
  bool StuckExactly(const ElementContext& ctx, int hold) const override;
  void ApplyStickForce(const ElementContext& ctx, int hold, double f, Loads* loads) const override;
  double StickAcceleration(const ElementContext& ctx, int hold, const DynamicsWorkspace& dyn,
                           std::span<const double> vdot) const override;
  double HoldVelocity(const ElementContext& ctx, int hold) const override;
  std::string HoldName(int hold) const override;
  bool UnholdableIsError() const override { return true; }
  void FollowSlip(const ElementContext& ctx, std::span<double> modes) const override;

 private:
  double Penetration(const ElementContext& ctx, int i, Vec3* p) const;
  // Point i as the stick model sees it; its penetration into *delta.
  ContactPointMotion Motion(const ElementContext& ctx, int i, double* delta) const;
  // Every point's penetration on ctx's kinematics, measured on the first call
  // for those kinematics (the scratch); a point's motion and normal force on
  // the first call for it (most calls ask only for the points that touch).
  struct Measured;
  Measured& Measure(const ElementContext& ctx) const;
  struct MeasuredPoint {
    ContactPointMotion motion;
    double normal = 0.0;  // normal force (0 when not pressed)
  };
  const MeasuredPoint& Point(const ElementContext& ctx, int i) const;
  double NormalForce(const ContactPointMotion& m, double delta) const {
    return ContactNormalForce(law_, std::max(delta, 0.0), -m.slip.dot(m.normal));
  }
  int num_points() const { return static_cast<int>(points_.size()); }
  // Point i's slice of the stick model's modes.
  std::span<double> StickModes(std::span<double> modes, int i) const {
    return modes.subspan(num_points() + ContactStick::kModesPerPoint * i, ContactStick::kModesPerPoint);
  }
  std::span<const double> StickModes(std::span<const double> modes, int i) const {
    return modes.subspan(num_points() + ContactStick::kModesPerPoint * i, ContactStick::kModesPerPoint);
  }
  // The stuck points as one: their centroid (the held point), the centre c
  // of their normal forces, sum N and sum N |r|^2 about c (equal weights
  // while none presses; 0: the spin is not held).
  struct Patch {
    int stuck = 0;
    double normal = 0.0, spin_inertia = 0.0;
    Vec3 held = Vec3::Zero(), centre = Vec3::Zero();
    Vec3 n = Vec3::Zero();  // the plane's normal (global)
    ContactPointMotion held_motion;  // the held point as a material point of body 1
  };
  // The patch of ctx.modes' stuck points, kept in the scratch until the
  // kinematics or the stuck set change.
  const Patch& MeasurePatch(const ElementContext& ctx) const;
  // Point i's share of holding force F (t1, t2 components) and moment M.
  std::array<double, 2> Share(const ElementContext& ctx, const Patch& patch, int i, double F1, double F2,
                              double M) const;
  std::array<double, 2> HoldingForce(const ElementContext& ctx, const Patch& patch, int i) const {
    if (ctx.stick_forces.empty() || !Stuck(ctx.modes, i)) return {0.0, 0.0};
    return Share(ctx, patch, i, ctx.stick_forces[0], ctx.stick_forces[1], ctx.stick_forces[2]);
  }
  // The loads of holding force (or moment) f on `hold`: F at the held point,
  // M a pure moment about n -- what the holds' velocities are the work
  // rates of, so that the holds' response S is symmetric. The points'
  // shares are statically the same in the plane.
  void ApplyHold(const ElementContext& ctx, const Patch& patch, int hold, double f, Loads* loads) const;
  // The stuck points' shares of the holding force (ctx.modes' stuck set);
  // *beyond: some share is beyond its point's cone.
  std::vector<std::array<double, 2>> Shares(const ElementContext& ctx, bool* beyond) const;
  // Every stuck point slides, along -(its share).
  void ReleaseAll(const ElementContext& ctx, const std::vector<std::array<double, 2>>& shares,
                  std::span<double> modes) const;
  bool Stuck(std::span<const double> modes, int i) const {
    return modes[i] != 0.0 && StickModes(modes, i)[0] == ContactStick::kStuck;
  }

  int body1_, body2_;
  std::vector<Vec3> points_;
  Vec3 plane_point_, normal_;
  Vec3 tangent1_, tangent2_;  // body 2's frame
  ContactLaw law_;
  std::optional<ContactStick> stick_;  // with law.exact_stick
};

}  // namespace mechflow::mech
