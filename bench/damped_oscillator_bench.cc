// Benchmark: the damped-oscillator diagram against the same equations written
// directly against CVODE.
//
//   x' = v,  v' = -(c x + d v) / m,   m = 1000 kg, f = 1 Hz, beta = 0.1,
//   c = 4 pi^2 f^2 m, d = 2 beta sqrt(m c), x(0) = 0.5 m, v(0) = 0.
//
// Both use CVODE BDF with Newton and a dense linear solver, the tolerances and
// the output grid of the diagram, and store both states at every output time.
// Printed: median wall time of each (of --repeat runs, alternating), their
// ratio, solver counters, and the largest difference in x between the two and
// against the closed form.
//
// usage: bench_damped_oscillator [DIAGRAM] [--repeat N]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include "blocks/simulator.h"
#include "diagrams/loader.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kM = 1000.0, kF = 1.0, kBeta = 0.1, kX0 = 0.5;
const double kC = 4 * kPi * kPi * kF * kF * kM;
const double kD = 2 * kBeta * std::sqrt(kM * kC);

struct Measured {
  double seconds = 0;
  long steps = 0, rhs = 0, jac = 0;
  std::vector<double> x;  // at every output time
};

int Rhs(double, N_Vector y, N_Vector ydot, void*) {
  const double* s = N_VGetArrayPointer(y);
  double* ds = N_VGetArrayPointer(ydot);
  ds[0] = s[1];
  ds[1] = -(kC * s[0] + kD * s[1]) / kM;
  return 0;
}

// The hand-written reference program.
Measured RunReference(const mechflow::blocks::SolverOptions& o) {
  Measured m;
  const auto start = std::chrono::steady_clock::now();
  SUNContext ctx;
  SUNContext_Create(nullptr, &ctx);
  N_Vector y = N_VNew_Serial(2, ctx);
  N_VGetArrayPointer(y)[0] = kX0;
  N_VGetArrayPointer(y)[1] = 0.0;
  SUNMatrix a = SUNDenseMatrix(2, 2, ctx);
  SUNLinearSolver ls = SUNLinSol_Dense(y, a, ctx);
  void* mem = CVodeCreate(CV_BDF, ctx);
  CVodeInit(mem, Rhs, o.t_start, y);
  CVodeSStolerances(mem, o.rtol, o.atol);
  CVodeSetLinearSolver(mem, ls, a);
  CVodeSetMaxNumSteps(mem, o.max_steps);
  const long n_out = std::lround((o.t_end - o.t_start) / o.output_interval);
  std::vector<double> rows;
  rows.reserve(3 * (n_out + 1));
  auto record = [&](double t) {
    rows.push_back(t);
    rows.push_back(N_VGetArrayPointer(y)[0]);
    rows.push_back(N_VGetArrayPointer(y)[1]);
  };
  record(o.t_start);
  for (long k = 1; k <= n_out; ++k) {
    double t = 0;
    if (CVode(mem, std::min(o.t_start + k * o.output_interval, o.t_end), y, &t, CV_NORMAL) < 0) break;
    record(t);
  }
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CVodeGetNumSteps(mem, &m.steps);
  long lin_rhs = 0;
  CVodeGetNumRhsEvals(mem, &m.rhs);
  CVodeGetNumLinRhsEvals(mem, &lin_rhs);
  m.rhs += lin_rhs;
  CVodeGetNumJacEvals(mem, &m.jac);
  for (size_t i = 1; i < rows.size(); i += 3) m.x.push_back(rows[i]);
  CVodeFree(&mem);
  SUNLinSolFree(ls);
  SUNMatDestroy(a);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  return m;
}

Measured RunDiagram(const mechflow::diagrams::LoadedDiagram& loaded) {
  Measured m;
  const auto start = std::chrono::steady_clock::now();
  mechflow::blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const auto outcome = sim.Run();
  m.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!outcome.ok) std::fprintf(stderr, "diagram run failed: %s\n", outcome.failure.c_str());
  m.steps = sim.stats().steps;
  m.rhs = sim.stats().rhs_evals + sim.stats().jac_rhs_evals;
  m.jac = sim.stats().jac_evals;
  m.x = sim.results().Column(sim.results().FindColumn("x"));
  return m;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/damped_oscillator_blocks.xml";
  int repeat = 7;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeat" && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else {
      path = arg;
    }
  }
  const auto loaded = mechflow::diagrams::LoadDiagram(path);
  const auto& o = loaded.solver;
  std::vector<double> t_diagram, t_reference;
  Measured diagram, reference;
  for (int r = 0; r < repeat; ++r) {
    diagram = RunDiagram(loaded);
    reference = RunReference(o);
    t_diagram.push_back(diagram.seconds);
    t_reference.push_back(reference.seconds);
  }
  const double zeta = kD / (2 * std::sqrt(kM * kC)), w = std::sqrt(kC / kM), wd = w * std::sqrt(1 - zeta * zeta);
  double diff = 0, err_diagram = 0, err_reference = 0;
  const size_t n = std::min(diagram.x.size(), reference.x.size());
  for (size_t i = 0; i < n; ++i) {
    const double t = o.t_start + i * o.output_interval;
    const double exact = std::exp(-zeta * w * t) * (kX0 * std::cos(wd * t) + zeta * w * kX0 / wd * std::sin(wd * t));
    diff = std::max(diff, std::abs(diagram.x[i] - reference.x[i]));
    err_diagram = std::max(err_diagram, std::abs(diagram.x[i] - exact));
    err_reference = std::max(err_reference, std::abs(reference.x[i] - exact));
  }
  const double md = Median(t_diagram), mr = Median(t_reference);
  std::printf("damped oscillator, t = %g..%g s, rtol %g, atol %g, %zu output rows, median of %d runs\n", o.t_start,
              o.t_end, o.rtol, o.atol, n, repeat);
  std::printf("%-22s %12s %8s %10s %10s %14s\n", "", "wall [ms]", "steps", "RHS evals", "Jacobians", "max |x - exact|");
  std::printf("%-22s %12.3f %8ld %10ld %10ld %14.3g\n", "mechflow diagram", 1e3 * md, diagram.steps, diagram.rhs,
              diagram.jac, err_diagram);
  std::printf("%-22s %12.3f %8ld %10ld %10ld %14.3g\n", "hand-written CVODE", 1e3 * mr, reference.steps,
              reference.rhs, reference.jac, err_reference);
  std::printf("ratio mechflow / reference: wall time %.2f, RHS evaluations %.2f\n", md / mr,
              static_cast<double>(diagram.rhs) / reference.rhs);
  std::printf("max |x_mechflow - x_reference| = %.3g m\n", diff);
  return 0;
}
