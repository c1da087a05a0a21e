#pragma once
// The friction problems P1-P3 of bench/README.md written directly against
// CVODE, independently of mech/ and blocks/: the reference the benchmark and
// the tests compare mechflow with.
//
// One model covers all three: n point masses on a line along x, coordinates
// x_i [m] measured from the start (every spring is free at x = 0), rates v_i.
//   mass 0 is tied to an anchor moving as V t by a spring-damper (k0, d0);
//   neighbours are joined by spring-dampers (k, d);
//   a force A sin(2 pi f t) pushes the last mass;
//   every mass has a Frictional element (ELEMENTS.md 3.6, the law of
//   mech/frictional_force.cc) against the ground:
//     modes STICK (0), SLIP+ (+1), SLIP- (-1), anchor x_s;
//     force  STICK: -c (x - x_s) - d_s v    SLIP+: -F    SLIP-: +F
//     events (CVODE root finding, with directions):
//       SLIP+ -> STICK when v falls through 0,  SLIP- -> STICK when v rises
//       through 0 (x_s := x); STICK -> SLIP+/- when +-(c (x - x_s) + d_s v)
//       rises through max(ratio F, 1e-9)
//     start: v > 0 SLIP+, v < 0 SLIP-, v = 0 STICK with x_s = x.
//   m_i x_i'' = -k0 (x_0 - V t) - d0 (v_0 - V)        (i = 0)
//               - k (x_i - x_{i-1}) - d (v_i - v_{i-1}) (i > 0)
//               - k (x_i - x_{i+1}) - d (v_i - v_{i+1}) (i < n-1)
//               + A sin(2 pi f t)                       (i = n-1)
//               + friction force of mass i
// P1: n = 1, no springs; P2: n = 1, k0 = 100, V = 0.1; P3: n = N, k0 = k.
//
// The state is interleaved, y = (x_0, v_0, x_1, v_1, ...), so the Jacobian is
// banded (upper bandwidth 2, lower 3). The root functions are 4 per mass in
// the element's order, so events match mechflow's one for one.

#include <vector>

#include <sundials/sundials_nvector.h>

namespace mechflow::bench {

// The Frictional element's parameters (mech/frictional_force.h).
struct FrictionLaw {
  double friction = 0.0;   // sliding force F [N]
  double ratio = 1.2;      // static / dynamic
  double stiffness = 0.0;  // c while stuck [N/m]
  double damping = 0.0;    // d_s while stuck [N s/m]
};

struct FrictionLine {
  std::vector<double> masses;   // [kg], one per mass, at least one
  double anchor_stiffness = 0.0, anchor_damping = 0.0;  // k0 [N/m], d0 [N s/m]
  double anchor_speed = 0.0;    // V [m/s]
  double stiffness = 0.0, damping = 0.0;  // k, d between neighbours
  FrictionLaw friction;         // the same for every mass
  double force_amplitude = 0.0;  // A [N]
  double force_frequency = 0.0;  // f [Hz]

  int size() const { return static_cast<int>(masses.size()); }
  // x_i'' for the given modes (0, +1, -1) and stick anchors; allocates nothing.
  void Accelerations(double t, const double* y, const double* modes, const double* anchors, double* a) const;
  // Kinetic energy plus the energy of the springs k0, k (not the stick springs) [J].
  double MechanicalEnergy(double t, const double* y) const;
};

// P1: the box of ElastFriction, variant Free (m 10, F 10, ratio 1.2, stiff
// stick at 50 Hz, damping ratio 0.1); start v0 = 1.5 m/s.
FrictionLine FreeSlideLine();
// P2: body m 1 pulled by c 100 from a leader at 0.1 m/s, mu_s 0.6, mu_d 0.4,
// g 9.81: sliding force mu_d m g, ratio mu_s/mu_d; the stick rings at
// `stick_hz` (c = m (2 pi stick_hz)^2) with damping ratio 0.1, as in P1.
FrictionLine StickSlipLine(double stick_hz = 50.0);
// P3: n masses of 1 kg, spring-dampers 1e4 N/m and 10 N s/m, friction
// 0.3*9.81 N (ratio 1.2, stick at 50 Hz with damping ratio 0.1 as in P1),
// 50 sin(2 pi 5 t) N on the last mass.
FrictionLine ChainLine(int n);
// The stick stiffness and damping of the problems: a mass m sticking rings at
// hz with damping ratio 0.1.
FrictionLaw StickAt(double mass, double hz, double friction, double ratio);

// Closed forms.
struct SlideStop {
  double time, distance;  // t = m v0/F, s = m v0^2/(2F)
};
SlideStop FreeSlideStop(double mass, double v0, double friction);

// Coulomb stick-slip with rigid stick: body m pulled through spring k by a
// leader at speed V, static limit mu_s m g, sliding force mu_d m g. The stick
// ends when k y = mu_s m g (y the spring's extension) and the slip is a
// harmonic arc about y_d = mu_d m g/k at omega = sqrt(k/m), starting with
// y - y_d = D = (mu_s - mu_d) m g/k and y' = V; it ends when the body stops
// (y' = V again), at y - y_d = -D. So
//   stick = 2 D / V,   slip = (2 pi - 2 atan(D omega / V)) / omega.
struct StickSlipCycle {
  double stick, slip;  // [s]
  double period() const { return stick + slip; }
};
StickSlipCycle CoulombStickSlip(double mass, double k, double speed, double mu_s, double mu_d, double g);

enum class LinearSolver {
  kDenseDifferenceQuotient,  // dense LU, CVODE's difference-quotient Jacobian (what blocks::Simulator uses)
  kBandAnalytic,             // band LU (mu 2, ml 3) with the analytic Jacobian
};

struct FrictionRunOptions {
  double rtol = 1e-6, atol = 1e-8;
  double t_end = 1.0;          // [s], from t = 0
  int num_outputs = 1000;      // CVode is called at t_end k/num_outputs (CV_NORMAL), as the simulator does
  LinearSolver solver = LinearSolver::kDenseDifferenceQuotient;
  bool flush_subnormals = false;  // FTZ/DAZ during the solve (x86 SSE), restored after
  // Appends the work of the force A sin(2 pi f t) and the energy the dampers
  // d0, d dissipate as two more states (dense solver only); without friction
  // and with V = 0, E(t) + dissipated - work = E(0).
  bool energy_states = false;
  long max_steps = 500000;     // per output interval
  // Installs other operations on the state vector (CVODE's clones inherit
  // them): mechflow's compiled ones, to compare with equal vector kernels.
  void (*vector_ops)(N_Vector) = nullptr;
  // What each output time (and t = 0) appends to FrictionRunResult::rows, as
  // a program writing a diagram's logged columns would: nothing; t and
  // (x_i, v_i) per mass; or t and (x_i, v_i, friction force, mode) per mass.
  enum class Rows { kNone, kStates, kStatesAndFriction };
  Rows rows = Rows::kNone;
};

struct FrictionEvent {
  double time;
  int mass;
  int crossing;  // 0 SLIP+ stops, 1 SLIP- stops, 2 breaks forward, 3 breaks backward (the element's order)
};

struct FrictionRunResult {
  double seconds = 0.0;  // SUNDIALS set-up, integration, teardown
  long steps = 0, rhs_evals = 0, jac_rhs_evals = 0, jac_evals = 0, root_evals = 0;
  std::vector<double> x, v;           // at t_end
  std::vector<double> modes, anchors;  // at t_end
  std::vector<FrictionEvent> events;  // every handled crossing, in order
  double work = 0.0, dissipated = 0.0;  // with energy_states
  std::vector<double> rows;           // row after row, FrictionRunOptions::rows
  int row_width = 0;
};

// Integrates the line from (x0, v0) (sizes of the line) with BDF + Newton;
// every SUNDIALS call is checked (std::runtime_error naming the call).
FrictionRunResult RunFrictionLine(const FrictionLine& line, const std::vector<double>& x0,
                                  const std::vector<double>& v0, const FrictionRunOptions& options);

}  // namespace mechflow::bench
