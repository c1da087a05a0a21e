// Benchmark: damped oscillator, mechflow diagram versus a hand-written CVODE program.
//
// Problem (diagrams/examples/damped_oscillator_blocks.xml, the seed model DampingRatio):
//   x' = v,  v' = -(c x + d v) / m
//   m = 1000 kg, f = 1 Hz, beta = 0.1 (damping ratio),
//   c = 4 pi^2 f^2 m [N/m],  d = 2 beta sqrt(m c) [N s/m],
//   x(0) = 0.5 m, v(0) = 0; interval, rtol, atol and output grid from the diagram's
//   <solver> and <output> elements (t_end = 10 s, rtol 1e-8, atol 1e-10, every 0.01 s).
//
// Two runs of the same equations in one process:
//   mechflow   the diagram loaded with diagrams::LoadDiagram (outside the timing) and
//              run with blocks::Simulator (construction + Run are timed).
//   reference  the equations written directly against CVODE: BDF, Newton, dense
//              direct solver with CVODE's difference-quotient Jacobian (what the
//              simulator uses too, so both should take the same steps), the same
//              tolerances, the same stop time and output times (CV_NORMAL, the
//              solver interpolates back to each output time), storing t, x, v per
//              output time into a buffer reserved up front, as the simulator does.
// Runs alternate (mechflow, reference, reference, mechflow, ...) so slow phases of a
// noisy machine hit both; the wall time reported is the median over the runs.
//
// Usage: bench_damped_oscillator [diagram.xml] [--repeat N]   (N >= 1, default 7)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "bench/direct_cvode.h"
#include "blocks/solver/grid_time.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"

namespace {

using Clock = std::chrono::steady_clock;

const double kPi = 3.14159265358979323846;

// Physical constants; taken from the diagram's identifiers when it defines them, so an
// edited diagram is still compared with the same equations.
struct Oscillator {
  double m = 1000.0;   // [kg]
  double f = 1.0;      // [Hz]
  double beta = 0.1;   // damping ratio [-]
  double x0 = 0.5;     // [m]
  double v0 = 0.0;     // [m/s]

  double c() const { return 4.0 * kPi * kPi * f * f * m; }        // [N/m]
  double d() const { return 2.0 * beta * std::sqrt(m * c()); }     // [N s/m]

  // Underdamped closed form (beta < 1).
  double ExactX(double t) const {
    const double w = 2.0 * kPi * f, wd = w * std::sqrt(1.0 - beta * beta);
    return std::exp(-beta * w * t) * (x0 * std::cos(wd * t) + (v0 + beta * w * x0) / wd * std::sin(wd * t));
  }
};

// Counters of one run, named as in blocks::SolverStats.
struct Counters {
  long steps = 0;
  long rhs_evals = 0;      // by the integrator
  long jac_rhs_evals = 0;  // by the difference-quotient Jacobian
  long jac_evals = 0;
};

// One run's output: rows of (t, x, v) and its counters.
struct Run {
  std::vector<double> rows;  // 3 values per output time
  Counters counters;
  double seconds = 0.0;
  int num_rows() const { return static_cast<int>(rows.size() / 3); }
};

// ---------------------------------------------------------------------------
// reference: the same problem written directly against CVODE

struct ReferenceData {
  double c_over_m = 0.0;  // [1/s^2]
  double d_over_m = 0.0;  // [1/s]
};

// y = (x, v)
int ReferenceRhs(double, N_Vector y, N_Vector ydot, void* user) {
  const auto* p = static_cast<const ReferenceData*>(user);
  const double* s = N_VGetArrayPointer(y);
  double* ds = N_VGetArrayPointer(ydot);
  ds[0] = s[1];
  ds[1] = -(p->c_over_m * s[0] + p->d_over_m * s[1]);
  return 0;
}

using mechflow::bench::direct::Check;
using mechflow::bench::direct::CheckPointer;
using ReferenceSolver = mechflow::bench::direct::Solver;

Run RunReference(const Oscillator& osc, const mechflow::blocks::SolverOptions& options) {
  const auto start = Clock::now();
  const double t0 = options.t_start, t_end = options.t_end, h = options.output_interval;
  const mechflow::blocks::OutputGrid grid(t0, h, t_end);
  ReferenceData data{osc.c() / osc.m, osc.d() / osc.m};
  Run run;
  run.rows.reserve(3 * (static_cast<std::size_t>(std::lround((t_end - t0) / h)) + 2));

  ReferenceSolver s;
  Check(SUNContext_Create(nullptr, &s.ctx), "SUNContext_Create");
  s.y = CheckPointer(N_VNew_Serial(2, s.ctx), "N_VNew_Serial");
  double* y = N_VGetArrayPointer(s.y);
  y[0] = osc.x0;
  y[1] = osc.v0;
  s.a = CheckPointer(SUNDenseMatrix(2, 2, s.ctx), "SUNDenseMatrix");
  s.ls = CheckPointer(SUNLinSol_Dense(s.y, s.a, s.ctx), "SUNLinSol_Dense");
  s.cvode = CheckPointer(CVodeCreate(CV_BDF, s.ctx), "CVodeCreate");
  Check(CVodeInit(s.cvode, ReferenceRhs, t0, s.y), "CVodeInit");
  Check(CVodeSetUserData(s.cvode, &data), "CVodeSetUserData");
  Check(CVodeSStolerances(s.cvode, options.rtol, options.atol), "CVodeSStolerances");
  Check(CVodeSetLinearSolver(s.cvode, s.ls, s.a), "CVodeSetLinearSolver");
  Check(CVodeSetMaxNumSteps(s.cvode, options.max_steps), "CVodeSetMaxNumSteps");
  if (options.max_step > 0.0) Check(CVodeSetMaxStep(s.cvode, options.max_step), "CVodeSetMaxStep");
  if (options.initial_step > 0.0) Check(CVodeSetInitStep(s.cvode, options.initial_step), "CVodeSetInitStep");
  // like the simulator: never step past the end
  Check(CVodeSetStopTime(s.cvode, t_end), "CVodeSetStopTime");

  run.rows.insert(run.rows.end(), {t0, y[0], y[1]});
  // output times from an integer index, the simulator's formula
  double t = t0;
  for (long k = 1; t < t_end; ++k) {
    // the output times mechflow's rows take (decimals: 0.47, not 47 * 0.01)
    const double t_out = grid.Time(k);
    Check(CVode(s.cvode, t_out, s.y, &t, CV_NORMAL), "CVode");
    run.rows.insert(run.rows.end(), {t, y[0], y[1]});
  }

  Check(CVodeGetNumSteps(s.cvode, &run.counters.steps), "CVodeGetNumSteps");
  Check(CVodeGetNumRhsEvals(s.cvode, &run.counters.rhs_evals), "CVodeGetNumRhsEvals");
  Check(CVodeGetNumLinRhsEvals(s.cvode, &run.counters.jac_rhs_evals), "CVodeGetNumLinRhsEvals");
  Check(CVodeGetNumJacEvals(s.cvode, &run.counters.jac_evals), "CVodeGetNumJacEvals");
  run.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return run;
}

// ---------------------------------------------------------------------------
// mechflow: the loaded diagram through blocks::Simulator

Run RunMechflow(const mechflow::diagrams::LoadedDiagram& loaded, int x_column, int v_column) {
  const auto start = Clock::now();
  mechflow::blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const mechflow::blocks::RunOutcome outcome = sim.Run();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (!outcome.ok)
    throw std::runtime_error("mechflow run failed at t = " + std::to_string(outcome.t_reached) + ": " +
                             outcome.failure);
  Run run;
  run.seconds = seconds;
  const mechflow::blocks::Results& r = sim.results();
  for (int i = 0; i < r.num_rows(); ++i) run.rows.insert(run.rows.end(), {r.at(i, 0), r.at(i, x_column), r.at(i, v_column)});
  const mechflow::blocks::SolverStats& st = sim.stats();
  run.counters = {st.steps, st.rhs_evals, st.jac_rhs_evals, st.jac_evals};
  return run;
}

// ---------------------------------------------------------------------------

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double MaxErrorVsClosedForm(const Run& run, const Oscillator& osc) {
  double e = 0.0;
  for (int i = 0; i < run.num_rows(); ++i)
    e = std::max(e, std::abs(run.rows[3 * i + 1] - osc.ExactX(run.rows[3 * i])));
  return e;
}

int Usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s [diagram.xml] [--repeat N]   (N >= 1, default 7)\n", argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/damped_oscillator_blocks.xml";
  int repeat = 7;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeat") {
      if (i + 1 >= argc) return Usage(argv[0]);
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || n < 1 || n > 100000) return Usage(argv[0]);
      repeat = static_cast<int>(n);
    } else if (arg == "-h" || arg == "--help") {
      Usage(argv[0]);
      return 0;
    } else if (!arg.empty() && arg[0] == '-') {
      return Usage(argv[0]);
    } else {
      path = arg;
    }
  }

  try {
    // load once, outside the timing
    const mechflow::diagrams::LoadedDiagram loaded = mechflow::diagrams::LoadDiagram(path);
    mechflow::blocks::SolverOptions options = loaded.solver;
    if (options.output_interval == 0.0) options.output_interval = (options.t_end - options.t_start) / 1000.0;
    Oscillator osc;
    const auto& ids = *loaded.identifiers;
    if (ids.Has("m")) osc.m = ids.Value("m");
    if (ids.Has("f")) osc.f = ids.Value("f");
    if (ids.Has("beta")) osc.beta = ids.Value("beta");
    if (ids.Has("x0")) osc.x0 = ids.Value("x0");
    if (!(osc.beta < 1.0)) throw std::runtime_error("the closed form needs beta < 1");

    // the logged columns to compare: "x" and "v" (column 0 is time)
    int x_column = -1, v_column = -1;
    for (int i = 0, column = 1; i < static_cast<int>(loaded.logged.size()); column += loaded.logged[i++].width) {
      if (loaded.logged[i].width != 1) continue;
      if (loaded.logged[i].name == "x") x_column = column;
      if (loaded.logged[i].name == "v") v_column = column;
    }
    if (x_column < 0 || v_column < 0)
      throw std::runtime_error(path + ": the diagram must log signals labelled \"x\" and \"v\"");

    // one untimed warm-up each (page faults, lazy binding), then alternating timed runs
    RunMechflow(loaded, x_column, v_column);
    RunReference(osc, options);
    std::vector<double> t_mechflow, t_reference;
    Run mechflow_run, reference_run;
    for (int r = 0; r < repeat; ++r) {
      if (r % 2 == 0) {
        mechflow_run = RunMechflow(loaded, x_column, v_column);
        reference_run = RunReference(osc, options);
      } else {
        reference_run = RunReference(osc, options);
        mechflow_run = RunMechflow(loaded, x_column, v_column);
      }
      t_mechflow.push_back(mechflow_run.seconds);
      t_reference.push_back(reference_run.seconds);
    }

    // agreement: same output times, x compared row by row
    if (mechflow_run.num_rows() != reference_run.num_rows())
      throw std::runtime_error("output grids differ: " + std::to_string(mechflow_run.num_rows()) + " vs " +
                               std::to_string(reference_run.num_rows()) + " rows");
    double dx = 0.0, dt = 0.0;
    for (int i = 0; i < mechflow_run.num_rows(); ++i) {
      dt = std::max(dt, std::abs(mechflow_run.rows[3 * i] - reference_run.rows[3 * i]));
      dx = std::max(dx, std::abs(mechflow_run.rows[3 * i + 1] - reference_run.rows[3 * i + 1]));
    }
    if (dt != 0.0) throw std::runtime_error("output times differ by up to " + std::to_string(dt) + " s");

    const double med_m = Median(t_mechflow), med_r = Median(t_reference);
    const Counters& cm = mechflow_run.counters;
    const Counters& cr = reference_run.counters;
    auto ratio = [](double a, double b) { return b > 0 ? a / b : 0.0; };

    std::printf("damped oscillator: %s\n", path.c_str());
    std::printf("BDF + Newton + dense, rtol %g, atol %g, t = %g..%g s, %d output times, median of %d runs\n\n",
                options.rtol, options.atol, options.t_start, options.t_end, mechflow_run.num_rows(), repeat);
    std::printf("%-26s %12s %12s %8s\n", "", "mechflow", "reference", "ratio");
    std::printf("%-26s %12.3f %12.3f %8.2f\n", "wall time, median [ms]", 1e3 * med_m, 1e3 * med_r, ratio(med_m, med_r));
    std::printf("%-26s %12.3f %12.3f\n", "wall time, fastest [ms]",
                1e3 * *std::min_element(t_mechflow.begin(), t_mechflow.end()),
                1e3 * *std::min_element(t_reference.begin(), t_reference.end()));
    std::printf("%-26s %12ld %12ld %8.2f\n", "steps", cm.steps, cr.steps, ratio(cm.steps, cr.steps));
    std::printf("%-26s %12ld %12ld %8.2f\n", "RHS evals (integrator)", cm.rhs_evals, cr.rhs_evals,
                ratio(cm.rhs_evals, cr.rhs_evals));
    std::printf("%-26s %12ld %12ld\n", "RHS evals (DQ Jacobian)", cm.jac_rhs_evals, cr.jac_rhs_evals);
    std::printf("%-26s %12ld %12ld\n", "Jacobian evals", cm.jac_evals, cr.jac_evals);
    std::printf("%-26s %12.2e %12.2e\n", "max |x - closed form| [m]", MaxErrorVsClosedForm(mechflow_run, osc),
                MaxErrorVsClosedForm(reference_run, osc));
    std::printf("%-26s %12.2e\n", "max |x_mf - x_ref| [m]", dx);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_damped_oscillator: %s\n", e.what());
    return 1;
  }
  return 0;
}
