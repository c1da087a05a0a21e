#include "bench/friction_direct.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_band.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_band.h>
#include <sunmatrix/sunmatrix_dense.h>

#if defined(__SSE__) || defined(__x86_64__)
#include <xmmintrin.h>
#define MECHFLOW_BENCH_HAVE_MXCSR 1
#endif

#include "bench/direct_cvode.h"

namespace mechflow::bench {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kStick = 0.0, kSlipPlus = 1.0, kSlipMinus = -1.0;
enum Crossing { kSlipPlusStops, kSlipMinusStops, kBreaksForward, kBreaksBackward, kCrossingsPerMass };

// The static limit of the break-away crossings, floored as in mech/frictional_force.h.
double Limit(const FrictionLaw& law) { return std::max(law.ratio * law.friction, 1e-9); }

double FrictionForce(const FrictionLaw& law, double mode, double x, double v, double anchor) {
  return mode == kStick ? -law.stiffness * (x - anchor) - law.damping * v : -mode * law.friction;
}

// Net force on mass i (y interleaved).
double Force(const FrictionLine& l, double t, const double* y, int i, double mode, double anchor) {
  const int n = l.size();
  const double x = y[2 * i], v = y[2 * i + 1];
  double f = FrictionForce(l.friction, mode, x, v, anchor);
  if (i == 0) f -= l.anchor_stiffness * (x - l.anchor_speed * t) + l.anchor_damping * (v - l.anchor_speed);
  if (i > 0) f -= l.stiffness * (x - y[2 * i - 2]) + l.damping * (v - y[2 * i - 1]);
  if (i < n - 1) f -= l.stiffness * (x - y[2 * i + 2]) + l.damping * (v - y[2 * i + 3]);
  if (i == n - 1 && l.force_amplitude != 0.0) f += l.force_amplitude * std::sin(2.0 * kPi * l.force_frequency * t);
  return f;
}

}  // namespace

void FrictionLine::Accelerations(double t, const double* y, const double* modes, const double* anchors,
                                 double* a) const {
  for (int i = 0; i < size(); ++i) a[i] = Force(*this, t, y, i, modes[i], anchors[i]) / masses[i];
}

double FrictionLine::MechanicalEnergy(double t, const double* y) const {
  double e = 0.0;
  for (int i = 0; i < size(); ++i) {
    e += 0.5 * masses[i] * y[2 * i + 1] * y[2 * i + 1];
    if (i > 0) e += 0.5 * stiffness * (y[2 * i] - y[2 * i - 2]) * (y[2 * i] - y[2 * i - 2]);
  }
  const double s0 = y[0] - anchor_speed * t;
  return e + 0.5 * anchor_stiffness * s0 * s0;
}

FrictionLaw StickAt(double mass, double hz, double friction, double ratio) {
  const double c = mass * 4.0 * kPi * kPi * hz * hz;
  return {friction, ratio, c, 2.0 * 0.1 * std::sqrt(mass * c)};
}

FrictionLine FreeSlideLine() {
  FrictionLine l;
  l.masses = {10.0};
  l.friction = StickAt(10.0, 50.0, 10.0, 1.2);
  return l;
}

FrictionLine StickSlipLine(double stick_hz) {
  const double m = 1.0, g = 9.81, mu_s = 0.6, mu_d = 0.4;
  FrictionLine l;
  l.masses = {m};
  l.anchor_stiffness = 100.0;
  l.anchor_speed = 0.1;
  l.friction = StickAt(m, stick_hz, mu_d * m * g, mu_s / mu_d);
  return l;
}

FrictionLine ChainLine(int n) {
  if (n < 1) throw std::invalid_argument("ChainLine: needs at least one mass, got " + std::to_string(n));
  FrictionLine l;
  l.masses.assign(static_cast<std::size_t>(n), 1.0);
  l.anchor_stiffness = l.stiffness = 1e4;
  l.anchor_damping = l.damping = 10.0;
  l.friction = StickAt(1.0, 50.0, 0.3 * 9.81, 1.2);
  l.force_amplitude = 50.0;
  l.force_frequency = 5.0;
  return l;
}

SlideStop FreeSlideStop(double mass, double v0, double friction) {
  return {mass * v0 / friction, mass * v0 * v0 / (2.0 * friction)};
}

StickSlipCycle CoulombStickSlip(double mass, double k, double speed, double mu_s, double mu_d, double g) {
  const double d = (mu_s - mu_d) * mass * g / k;  // half the swing of the extension about y_d
  const double omega = std::sqrt(k / mass);
  return {2.0 * d / speed, (2.0 * kPi - 2.0 * std::atan2(d * omega, speed)) / omega};
}

namespace {

using Clock = std::chrono::steady_clock;

// What the callbacks see.
struct Problem {
  const FrictionLine* line;
  int n;
  bool energy;
  std::vector<double> modes, anchors;
};

int Rhs(double t, N_Vector yv, N_Vector ydotv, void* user) {
  const Problem& p = *static_cast<const Problem*>(user);
  const FrictionLine& l = *p.line;
  const double* y = N_VGetArrayPointer(yv);
  double* dy = N_VGetArrayPointer(ydotv);
  for (int i = 0; i < p.n; ++i) {
    dy[2 * i] = y[2 * i + 1];
    dy[2 * i + 1] = Force(l, t, y, i, p.modes[i], p.anchors[i]) / l.masses[i];
  }
  if (p.energy) {
    const int last = 2 * (p.n - 1) + 1;
    dy[2 * p.n] = l.force_amplitude * std::sin(2.0 * kPi * l.force_frequency * t) * y[last];
    const double w0 = y[1] - l.anchor_speed;
    double dissipated = l.anchor_damping * w0 * w0;
    for (int i = 1; i < p.n; ++i) {
      const double w = y[2 * i + 1] - y[2 * i - 1];
      dissipated += l.damping * w * w;
    }
    dy[2 * p.n + 1] = dissipated;
  }
  return 0;
}

// The banded analytic Jacobian (CVODE zeroes J before the call).
int BandJacobian(double, N_Vector, N_Vector, SUNMatrix j, void* user, N_Vector, N_Vector, N_Vector) {
  const Problem& p = *static_cast<const Problem*>(user);
  const FrictionLine& l = *p.line;
  for (int i = 0; i < p.n; ++i) {
    const sunindextype rx = 2 * i, rv = 2 * i + 1;
    const double inv_m = 1.0 / l.masses[i];
    SM_ELEMENT_B(j, rx, rv) = 1.0;
    double dx = 0.0, dv = 0.0;  // d force / d (x_i, v_i)
    if (p.modes[i] == kStick) dx -= l.friction.stiffness, dv -= l.friction.damping;
    if (i == 0) dx -= l.anchor_stiffness, dv -= l.anchor_damping;
    if (i > 0) {
      dx -= l.stiffness, dv -= l.damping;
      SM_ELEMENT_B(j, rv, rx - 2) = l.stiffness * inv_m;
      SM_ELEMENT_B(j, rv, rx - 1) = l.damping * inv_m;
    }
    if (i < p.n - 1) {
      dx -= l.stiffness, dv -= l.damping;
      SM_ELEMENT_B(j, rv, rx + 2) = l.stiffness * inv_m;
      SM_ELEMENT_B(j, rv, rx + 3) = l.damping * inv_m;
    }
    SM_ELEMENT_B(j, rv, rx) = dx * inv_m;
    SM_ELEMENT_B(j, rv, rv) = dv * inv_m;
  }
  return 0;
}

// Per mass, in the element's order; an inactive function sits at a constant
// on the side that cannot trigger (as mech/frictional_force.cc does).
int Roots(double, N_Vector yv, double* g, void* user) {
  const Problem& p = *static_cast<const Problem*>(user);
  const FrictionLaw& law = p.line->friction;
  const double* y = N_VGetArrayPointer(yv);
  const double limit = Limit(law);
  for (int i = 0; i < p.n; ++i) {
    const double x = y[2 * i], v = y[2 * i + 1], mode = p.modes[i];
    double* gi = g + kCrossingsPerMass * i;
    gi[kSlipPlusStops] = mode == kSlipPlus ? v : 1.0;
    gi[kSlipMinusStops] = mode == kSlipMinus ? v : -1.0;
    const double holding = law.stiffness * (x - p.anchors[i]) + law.damping * v;
    gi[kBreaksForward] = mode == kStick ? holding - limit : -1.0;
    gi[kBreaksBackward] = mode == kStick ? -holding - limit : -1.0;
  }
  return 0;
}

using direct::Check;
using direct::CheckPointer;
using direct::Solver;

// Flush-to-zero and denormals-are-zero for its lifetime (the subnormal trap of bench/README.md:
// the far end of a long chain fills with subnormals).
struct FlushSubnormals {
  explicit FlushSubnormals(bool on) {
#ifdef MECHFLOW_BENCH_HAVE_MXCSR
    saved = _mm_getcsr();
    if (on) _mm_setcsr(saved | 0x8040u);  // FTZ (bit 15) | DAZ (bit 6)
#else
    (void)on;
#endif
  }
  ~FlushSubnormals() {
#ifdef MECHFLOW_BENCH_HAVE_MXCSR
    _mm_setcsr(saved);
#endif
  }
  unsigned saved = 0;
};

}  // namespace

FrictionRunResult RunFrictionLine(const FrictionLine& line, const std::vector<double>& x0,
                                  const std::vector<double>& v0, const FrictionRunOptions& options) {
  const int n = line.size();
  if (n < 1 || static_cast<int>(x0.size()) != n || static_cast<int>(v0.size()) != n)
    throw std::invalid_argument("RunFrictionLine: initial state of size " + std::to_string(x0.size()) + " + " +
                                std::to_string(v0.size()) + " for " + std::to_string(n) + " masses");
  if (options.num_outputs < 1 || !(options.t_end > 0.0))
    throw std::invalid_argument("RunFrictionLine: needs t_end > 0 and at least one output time");
  if (options.energy_states && options.solver != LinearSolver::kDenseDifferenceQuotient)
    throw std::invalid_argument("RunFrictionLine: energy states need the dense solver");

  FrictionRunResult result;
  const auto start = Clock::now();
  {
    const FlushSubnormals flush(options.flush_subnormals);
    Problem p{&line, n, options.energy_states, std::vector<double>(n), std::vector<double>(x0)};
    for (int i = 0; i < n; ++i) p.modes[i] = v0[i] > 0 ? kSlipPlus : v0[i] < 0 ? kSlipMinus : kStick;
    result.events.reserve(1024);

    const sunindextype size = 2 * n + (options.energy_states ? 2 : 0);
    Solver s;
    Check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
    s.y = CheckPointer(N_VNew_Serial(size, s.ctx), "N_VNew_Serial");
    if (options.vector_ops) options.vector_ops(s.y);
    double* y = N_VGetArrayPointer(s.y);
    std::fill(y, y + size, 0.0);
    for (int i = 0; i < n; ++i) y[2 * i] = x0[i], y[2 * i + 1] = v0[i];
    if (options.solver == LinearSolver::kBandAnalytic) {
      s.a = CheckPointer(SUNBandMatrix(size, 2, 3, s.ctx), "SUNBandMatrix");
      s.ls = CheckPointer(SUNLinSol_Band(s.y, s.a, s.ctx), "SUNLinSol_Band");
    } else {
      s.a = CheckPointer(SUNDenseMatrix(size, size, s.ctx), "SUNDenseMatrix");
      s.ls = CheckPointer(SUNLinSol_Dense(s.y, s.a, s.ctx), "SUNLinSol_Dense");
    }
    s.cvode = CheckPointer(CVodeCreate(CV_BDF, s.ctx), "CVodeCreate");
    void* mem = s.cvode;
    Check(CVodeInit(mem, Rhs, 0.0, s.y), "CVodeInit");
    Check(CVodeSetUserData(mem, &p), "CVodeSetUserData");
    Check(CVodeSStolerances(mem, options.rtol, options.atol), "CVodeSStolerances");
    Check(CVodeSetLinearSolver(mem, s.ls, s.a), "CVodeSetLinearSolver");
    if (options.solver == LinearSolver::kBandAnalytic) Check(CVodeSetJacFn(mem, BandJacobian), "CVodeSetJacFn");
    Check(CVodeSetMaxNumSteps(mem, options.max_steps), "CVodeSetMaxNumSteps");
    const int num_roots = kCrossingsPerMass * n;
    Check(CVodeRootInit(mem, num_roots, Roots), "CVodeRootInit");
    std::vector<int> directions(num_roots), found(num_roots);
    for (int i = 0; i < n; ++i) {
      directions[kCrossingsPerMass * i + kSlipPlusStops] = -1;
      directions[kCrossingsPerMass * i + kSlipMinusStops] = +1;
      directions[kCrossingsPerMass * i + kBreaksForward] = +1;
      directions[kCrossingsPerMass * i + kBreaksBackward] = +1;
    }
    Check(CVodeSetRootDirection(mem, directions.data()), "CVodeSetRootDirection");
    Check(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");

    // the counters restart at every re-initialisation: accumulate them
    auto accumulate = [&] {
      long v = 0;
      Check(CVodeGetNumSteps(mem, &v), "CVodeGetNumSteps"), result.steps += v;
      Check(CVodeGetNumRhsEvals(mem, &v), "CVodeGetNumRhsEvals"), result.rhs_evals += v;
      Check(CVodeGetNumLinRhsEvals(mem, &v), "CVodeGetNumLinRhsEvals"), result.jac_rhs_evals += v;
      Check(CVodeGetNumJacEvals(mem, &v), "CVodeGetNumJacEvals"), result.jac_evals += v;
      Check(CVodeGetNumGEvals(mem, &v), "CVodeGetNumGEvals"), result.root_evals += v;
    };

    using Rows = FrictionRunOptions::Rows;
    const int per_mass = options.rows == Rows::kNone ? 0 : options.rows == Rows::kStates ? 2 : 4;
    result.row_width = per_mass > 0 ? 1 + per_mass * n : 0;
    result.rows.reserve(static_cast<std::size_t>(result.row_width) * (options.num_outputs + 1));
    auto record = [&](double t_row) {
      if (per_mass == 0) return;
      result.rows.push_back(t_row);
      for (int i = 0; i < n; ++i) {
        const double x = y[2 * i], v = y[2 * i + 1];
        result.rows.push_back(x);
        result.rows.push_back(v);
        if (per_mass < 4) continue;
        result.rows.push_back(FrictionForce(line.friction, p.modes[i], x, v, p.anchors[i]));
        result.rows.push_back(p.modes[i]);
      }
    };
    record(0.0);

    const double t_end = options.t_end, interval = t_end / options.num_outputs;
    double t = 0.0;
    long next_output = 1;
    while (t < t_end) {
      const double t_out = std::min(next_output * interval, t_end);
      if (t_out <= t) {  // an output time that coincides with the last event
        record(t);
        ++next_output;
        continue;
      }
      Check(CVodeSetStopTime(mem, t_end), "CVodeSetStopTime");
      const int flag = CVode(mem, t_out, s.y, &t, CV_NORMAL);
      Check(flag, "CVode");
      if (flag == CV_ROOT_RETURN) {
        // the element's OnCrossing, then continue from the located instant
        Check(CVodeGetRootInfo(mem, found.data()), "CVodeGetRootInfo");
        for (int r = 0; r < num_roots; ++r) {
          if (found[r] == 0) continue;
          const int i = r / kCrossingsPerMass, kind = r % kCrossingsPerMass;
          if (kind == kSlipPlusStops || kind == kSlipMinusStops) {
            p.modes[i] = kStick;
            p.anchors[i] = y[2 * i];
          } else {
            p.modes[i] = kind == kBreaksForward ? kSlipPlus : kSlipMinus;
          }
          result.events.push_back({t, i, kind});
        }
        accumulate();
        Check(CVodeReInit(mem, t, s.y), "CVodeReInit");
        continue;
      }
      if (t >= t_out) {
        record(t);
        ++next_output;
      }
    }
    accumulate();
    result.x.resize(n);
    result.v.resize(n);
    for (int i = 0; i < n; ++i) result.x[i] = y[2 * i], result.v[i] = y[2 * i + 1];
    result.modes = p.modes;
    result.anchors = p.anchors;
    if (options.energy_states) result.work = y[2 * n], result.dissipated = y[2 * n + 1];
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

}  // namespace mechflow::bench
