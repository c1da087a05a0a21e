#pragma once
// Exact stick of a contact point (stick="exact" on points-plane and
// circle-plane contacts; docs/ELEMENTS.md 5.5): the two-component
// stick/slip mode machine of one point, the 2-D case of mech/stick_slip.h.
//
// A point in contact is STUCK, STARTING or SLIDING. While stuck, its two
// tangential slip components s_k = t_k . w (w: body 1's material velocity at
// the contact point minus body 2's; t_1, t_2 tangents fixed in body 2) are
// held at zero by holding forces f_1, f_2 that the mechanism solves for with
// every other stuck hold (mech/exact_stick.h); the normal force stays the
// penalty law. Otherwise friction is Coulomb's with the contact's Stribeck
// curve, mu(|w_t|) N against the slip. Its direction:
//   STARTING  (a slip slower than kSteerSpeed): -d, d being the direction
//             the slip set off in. Near w_t = 0 the slip's own direction
//             means nothing: a slip whose sideways part is driven by other
//             holds (the second rim of a wheel set rocking on its
//             contacts) would turn the friction round faster than any step
//             resolves; friction against the breakaway's direction turns
//             it only at the events below.
//   SLIDING   -(w_t + 2 kEndSpeed d) / |..|: against the slip (d as below).
//
//   crossings, events (never `if`s inside a step):
//     STUCK -> STARTING  when |f_t| - mu_s N rises through 0; the slip
//                        starts along -f_t (the way the holding force
//                        resisted). A hold whose N falls to zero lets go
//                        the same way.
//     STARTING -> SLIDING  when |w_t| rises through kSteerSpeed.
//     STARTING, SLIDING -> STUCK  when w_t . d + kEndSpeed falls through 0,
//                        d being the slip's direction (at its start, or at
//                        the end of the last step while sliding): the slip
//                        reverses within a step (Simbody's lesson: rather
//                        than |w_t| = 0, which an integrator steps over).
//                        The offset keeps the function off zero where a
//                        slip starts (w_t = 0), so that a slip that sets off
//                        backwards is seen too; a sliding friction's
//                        direction turns round only after the crossing
//                        (else it would chatter about w_t = 0 before the
//                        slip could end). If the point still moves sideways
//                        faster than kStopSpeed where the slip ends, it goes
//                        on slipping with d := the new slip direction.
//   a stuck hold beyond its cone at an event (a load applied at once) slips
//   at once; the velocity a stuck point keeps from the root finder (about
//   1e-12 m/s) is removed by the mechanism at the event (mech/mechanism.h).
//
// Modes per point: [slip state (kStuck, kSliding, kStarting), d_1, d_2] (d
// in the tangents' components); crossings per point: [breakaway, slip ends,
// slip steers].

#include <cmath>
#include <span>

#include "mech/force_element.h"
#include "mech/contact_law.h"

namespace mechflow::mech {

// A contact point and how it moves.
struct ContactPointMotion {
  int body1 = 0, body2 = 0;
  Vec3 point = Vec3::Zero();       // the contact point (global)
  Vec3 point_rate = Vec3::Zero();  // its velocity as a geometric point (a rim's deepest point moves over the rim)
  Vec3 normal = Vec3::Zero();      // the plane's external normal (global)
  Vec3 t1 = Vec3::Zero(), t2 = Vec3::Zero();  // the tangents (global), fixed in body 2
  Vec3 slip = Vec3::Zero();        // w
  double s1 = 0.0, s2 = 0.0;       // t_k . w
  double speed() const { return std::hypot(s1, s2); }
};

// Two unit tangents of a plane with unit normal n (body 2's frame), n = t1 x t2.
void PlaneTangents(const Vec3& n, Vec3* t1, Vec3* t2);
// Measures the point of body 1 at `point` against body 2's plane with global
// normal `normal` and local tangents; `point_rate` as in ContactPointMotion.
ContactPointMotion MeasureContactPoint(const Kinematics& kin, int body1, int body2, const Vec3& point,
                                       const Vec3& point_rate, const Vec3& normal, const Vec3& tangent1,
                                       const Vec3& tangent2);

class ContactStick {
 public:
  static constexpr double kStuck = 0.0, kSliding = 1.0, kStarting = 2.0;
  static constexpr int kModesPerPoint = 3, kCrossingsPerPoint = 3;
  // A slip that ends while the point still moves sideways faster than this
  // [m/s] turns instead of sticking.
  static constexpr double kStopSpeed = 1e-6;
  // A slip has ended when w_t . d falls below -kEndSpeed [m/s].
  static constexpr double kEndSpeed = 1e-9;
  // A starting slip's friction turns to the slip's own direction [m/s].
  static constexpr double kSteerSpeed = 1e-5;

  explicit ContactStick(const ContactLaw& law) : law_(law) {}

  // The directions of a point's crossings.
  static Crossing BreakawayDirection() { return Crossing::kRising; }
  static Crossing SlipEndDirection() { return Crossing::kFalling; }
  static Crossing SteerDirection() { return Crossing::kRising; }
  // What crossing `which` of a point is, for the event log.
  static const char* CrossingName(int which);

  // The state a point takes on touching (or at the start): stuck when it
  // moves slower than kStopSpeed, else slipping along its slip.
  static void Start(const ContactPointMotion& m, std::span<double> modes);
  // The friction on body 1 (global): the holding forces f while stuck, the
  // sliding law's otherwise; N is the point's normal force.
  Vec3 Friction(const ContactPointMotion& m, double N, std::span<const double> modes,
                std::span<const double> f) const;
  // After a step: a sliding point's direction d turns to its slip (once
  // the slip is well above kEndSpeed, where its direction means something;
  // a starting slip keeps its d).
  static void Follow(const ContactPointMotion& m, std::span<double> modes);
  // A point's two crossing values (touching: whether it is in contact).
  void ZeroCrossings(const ContactPointMotion& m, double N, bool touching, std::span<const double> modes,
                     std::span<const double> f, std::span<double> values) const;
  // Crossing `which` (0 breakaway, 1 slip ends, 2 slip steers) fired.
  static void OnCrossing(int which, const ContactPointMotion& m, std::span<const double> f, std::span<double> modes);
  // After an event: a stuck point beyond its cone slides at once (along
  // -f_t). Returns true when it switched.
  bool Update(double N, std::span<const double> f, std::span<double> modes) const;
  // Whether a stuck point's holding force f is beyond its cone.
  bool Exceeds(double N, std::span<const double> f) const { return std::hypot(f[0], f[1]) > Limit(N); }
  // The rate of s_k (k = 0, 1) after a dynamics pass.
  static double HoldAcceleration(const Model& model, const Kinematics& kin, const DynamicsWorkspace& dyn,
                                 const ContactPointMotion& m, int k);
  // Adds holding force f along t_k on body 1 at the point (and -f on body 2).
  static void ApplyHoldForce(const Kinematics& kin, const ContactPointMotion& m, int k, double f, Loads* loads);

 private:
  // mu_s N with a floor of 1e-9 N (a limit that starts at exactly zero must
  // still give a crossing the solver can see).
  double Limit(double N) const;
  ContactLaw law_;
};

}  // namespace mechflow::mech
