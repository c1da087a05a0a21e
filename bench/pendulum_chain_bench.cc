// Benchmark P4 of bench/README.md: planar chain of N uniform rods (1 kg,
// 1 m, I = 1/12 kg m^2 about the centre) on revolute joints, the first hinged
// to the ground, gravity 9.81, released horizontal at rest, t_end = 5 s,
// N = 2, 10, 50, 200, rtol 1e-6, atol 1e-8, 1000 output times.
//
// Contenders, each run in the same process on the same problem:
//   reference  the chain's equations written directly against CVODE
//              (bench/pendulum_chain_direct.h: absolute angles, mass matrix in
//              closed form, Cholesky per evaluation; tested on its own by
//              tests/mech/pendulum_chain_reference_test.cc);
//   reference-ops  the same with mechflow's compiled vector operations
//              (blocks/solver/compiled_ops.h) in place of Debian's unoptimised ones;
//   mechflow   a diagram with one mechanism (generated as XML text and loaded
//              outside the timing), relative joint angles, articulated-body
//              dynamics, run by blocks::Simulator with its dense solver
//              (joint coordinates eliminated from the Newton systems);
//   mf-krylov  the same with the Krylov solver (GMRES, matrix-free);
//   simbody-rkm, simbody-bdf  Simbody (when built with it) with its own
//              Runge-Kutta-Merson and CPODES integrators at accuracy rtol,
//              each run in a process of its own that times itself
//              (bench/pendulum_chain_simbody_main.cc says why).
// reference and mechflow use BDF + Newton + CVODE's difference-quotient
// Jacobian; they run up to --dense-max bodies.
// A contender is a name and a set-up function that returns its timed run (see
// Contenders() at the bottom); adding one is one entry there.
//
// Per N: one untimed warm-up of each contender, then --repeat timed runs of
// each, the starting contender rotating from run to run so a slow phase of the
// machine hits all. Printed: median and fastest wall time, steps, RHS
// evaluations (integrator and difference-quotient Jacobian), Jacobian
// evaluations, the cost per RHS evaluation (median wall time / all RHS
// evaluations), the energy drift at t_end, the largest difference of the final
// absolute angles from the reference's, ratios to the reference, and at the
// end the growth exponent of the cost per RHS evaluation with N (least-squares
// slope on log-log axes).
//
// Usage: bench_pendulum_chain [--repeat K] [--sizes 2,10,50,200] [--dense-max N]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "bench/pendulum_chain_direct.h"
#include "blocks/solver/compiled_ops.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"

namespace {

using Clock = std::chrono::steady_clock;
using mechflow::bench::PendulumChain;

constexpr double kMass = 1.0, kLength = 1.0, kG = 9.81;
constexpr double kRtol = 1e-6, kAtol = 1e-8, kTEnd = 5.0;
constexpr int kOutputs = 1000;

// One timed run of a contender.
struct Outcome {
  double seconds = 0.0;
  long steps = 0, rhs = 0, jac_rhs = 0, jac_evals = 0;
  Eigen::VectorXd theta, omega;  // absolute angles [rad] and rates [rad/s] at t_end
  long linear_iters = 0;         // Krylov iterations
  long all_rhs() const { return rhs + jac_rhs; }
};

// A contender: its name and its set-up for a chain of n rods (untimed), which
// returns the timed run; an empty run means "not measured" and is printed so.
struct Contender {
  std::string name;
  std::function<std::function<Outcome()>(int n)> prepare;
};

// ---------------------------------------------------------------------------
// reference: the direct program

std::function<Outcome()> PrepareReference(int n, bool compiled_ops) {
  auto chain = std::make_shared<const PendulumChain>(n, kMass, kLength, kG);
  return [chain, compiled_ops] {
    mechflow::bench::DirectRunOptions options;
    if (compiled_ops) options.vector_ops = mechflow::blocks::sundials::UseCompiledVectorOps;
    options.rtol = kRtol;
    options.atol = kAtol;
    options.t_end = kTEnd;
    options.num_outputs = kOutputs;
    const mechflow::bench::DirectRunResult r = RunDirect(*chain, options);
    return Outcome{r.seconds, r.steps, r.rhs_evals, r.jac_rhs_evals, r.jac_evals, r.theta, r.omega};
  };
}

// ---------------------------------------------------------------------------
// mechflow: the chain as a diagram with one mechanism

std::string ChainDiagram(int n) {
  std::ostringstream x;
  x << "<diagram name=\"chain\">\n<mechanism name=\"c\">\n";
  for (int i = 1; i <= n; ++i)
    x << "<body name=\"R" << i << "\" mass=\"" << kMass << "\" com=\"0 " << kLength / 2
      << " 0\" inertia=\"1/12 1e-6 1/12\"/>\n";
  for (int i = 1; i <= n; ++i)
    x << "<joint name=\"j" << i << "\" type=\"rotational\" body1=\"" << (i == 1 ? "Base0" : "R" + std::to_string(i - 1))
      << "\" body2=\"R" << i << "\"" << (i == 1 ? "" : " point1=\"0 1 0\"") << " axis=\"1 0 0\"/>\n";
  for (int i = 1; i <= n; ++i) {
    x << "<sensor name=\"q" << i << "\" kind=\"coordinate\" dof=\"j" << i << "\"/>\n";
    x << "<sensor name=\"w" << i << "\" kind=\"velocity\" dof=\"j" << i << "\"/>\n";
  }
  x << "</mechanism>\n<solver t_end=\"" << kTEnd << "\" rtol=\"" << kRtol << "\" atol=\"" << kAtol
    << "\"/>\n<output interval=\"" << kTEnd / kOutputs << "\">\n";
  for (int i = 1; i <= n; ++i) x << "<log signal=\"c.q" << i << "\"/><log signal=\"c.w" << i << "\"/>\n";
  x << "</output>\n</diagram>\n";
  return x.str();
}

std::function<Outcome()> PrepareMechflow(int n, mechflow::blocks::LinearSolverKind kind) {
  auto loaded = std::make_shared<mechflow::diagrams::LoadedDiagram>(
      mechflow::diagrams::LoadDiagramDescription(mechflow::diagrams::ReadDiagramText(ChainDiagram(n), "chain.xml")));
  loaded->solver.linear_solver = kind;
  return [loaded, n] {
    const auto start = Clock::now();
    mechflow::blocks::Simulator sim(*loaded->diagram, loaded->solver, loaded->logged);
    const auto outcome = sim.Run();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (!outcome.ok) throw std::runtime_error("mechflow run failed: " + outcome.failure);
    const auto& st = sim.stats();
    const auto& r = sim.results();
    const int last = r.num_rows() - 1;
    Eigen::VectorXd q(n), w(n);  // logged as q1, w1, q2, w2, ... after time
    for (int i = 0; i < n; ++i) q(i) = r.at(last, 1 + 2 * i), w(i) = r.at(last, 2 + 2 * i);
    return Outcome{seconds,        st.steps, st.rhs_evals, st.jac_rhs_evals, st.jac_evals,
                   mechflow::bench::RelativeToAbsolute(q), mechflow::bench::RelativeToAbsolute(w), st.linear_iters};
  };
}

// ---------------------------------------------------------------------------
// Simbody with its own integrators (only when built with it)

// bench_pendulum_chain_simbody, beside this program (see its source for why
// a process of its own); it times its own run.
std::string simbody_program;

std::function<Outcome()> PrepareSimbody(int n, const std::string& integrator) {
  if (kMass != 1.0 || kLength != 1.0 || kG != 9.81) throw std::logic_error("the Simbody program builds unit rods");
  const std::string command = simbody_program + " " + std::to_string(n) + " " + integrator + " " +
                              std::to_string(kRtol) + " " + std::to_string(kTEnd) + " " + std::to_string(kOutputs);
  return [command, n] {
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) throw std::runtime_error("cannot run " + command);
    Outcome o;
    o.theta.resize(n);
    o.omega.resize(n);
    bool ok = std::fscanf(pipe, "%lf %ld %ld", &o.seconds, &o.steps, &o.rhs) == 3;
    for (int i = 0; ok && i < n; ++i) ok = std::fscanf(pipe, "%lf", &o.theta(i)) == 1;
    for (int i = 0; ok && i < n; ++i) ok = std::fscanf(pipe, "%lf", &o.omega(i)) == 1;
    if (pclose(pipe) != 0 || !ok) throw std::runtime_error("failed: " + command);
    return o;
  };
}

// Dense contenders (their Jacobians cost N^2, their LU N^3) run up to this N.
int dense_max = 200;

// The contenders; the first is the reference the others are compared with.
std::vector<Contender> Contenders() {
  using mechflow::blocks::LinearSolverKind;
  const auto dense_only = [](auto prepare) {
    return [prepare](int n) { return n <= dense_max ? prepare(n) : std::function<Outcome()>(); };
  };
  std::vector<Contender> contenders = {
      {"reference", dense_only([](int n) { return PrepareReference(n, false); })},
      {"reference-ops", dense_only([](int n) { return PrepareReference(n, true); })},
      {"mechflow", dense_only([](int n) { return PrepareMechflow(n, LinearSolverKind::kDense); })},
      {"mf-krylov", [](int n) { return PrepareMechflow(n, LinearSolverKind::kKrylov); }}};
#ifdef MECHFLOW_HAVE_SIMBODY
  contenders.push_back({"simbody-rkm", [](int n) { return PrepareSimbody(n, "rkm"); }});
  contenders.push_back({"simbody-bdf", [](int n) { return PrepareSimbody(n, "bdf"); }});
#else
  contenders.push_back({"simbody", [](int) { return std::function<Outcome()>(); }});  // built without Simbody
#endif
  return contenders;
}

// ---------------------------------------------------------------------------

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

// least-squares slope of log y against log x
double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double k = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]) / k, my += std::log(y[i]) / k;
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxy / sxx;
}

int Usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s [--repeat K] [--sizes 2,10,50,200] [--dense-max N]   (K >= 1, default 5; N default 200)\n",
               argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::vector<int> sizes = {2, 10, 50, 200};
  {
    const std::string self = argv[0];
    const std::size_t slash = self.rfind('/');
    simbody_program = (slash == std::string::npos ? std::string(".") : self.substr(0, slash)) +
                      "/bench_pendulum_chain_simbody";
  }
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeat" && i + 1 < argc) {
      repeat = std::atoi(argv[++i]);
      if (repeat < 1) return Usage(argv[0]);
    } else if (arg == "--dense-max" && i + 1 < argc) {
      dense_max = std::atoi(argv[++i]);
    } else if (arg == "--sizes" && i + 1 < argc) {
      sizes.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::atoi(item.c_str()));
      if (sizes.empty() || *std::min_element(sizes.begin(), sizes.end()) < 1) return Usage(argv[0]);
    } else {
      return Usage(argv[0]);
    }
  }

  try {
    const std::vector<Contender> contenders = Contenders();
    const std::size_t nc = contenders.size();
    std::printf("P4 pendulum chain: BDF + Newton + dense, difference-quotient Jacobian, rtol %g, atol %g, "
                "t = 0..%g s, %d output times, median of %d runs\n",
                kRtol, kAtol, kTEnd, kOutputs, repeat);
    std::printf("us/RHS = median wall time / (integrator + Jacobian RHS evaluations); energy drift E(t_end) - E(0); "
                "|dtheta| = max |theta_i - theta_i,reference| at t_end\n\n");
    std::printf("%5s  %-13s %9s %9s %7s %8s %8s %5s %7s %8s %11s %9s\n", "N", "contender", "wall [ms]", "fast [ms]",
                "steps", "RHS int", "RHS jac", "Jac", "lin it", "us/RHS", "drift [J]", "|dtheta|");

    std::vector<std::vector<double>> cost(nc), wall(nc), sizes_of(nc);  // per contender, per N measured

    for (const int n : sizes) {
      const PendulumChain chain(n, kMass, kLength, kG);
      // set up (untimed) and warm up each contender
      std::vector<std::function<Outcome()>> runs(nc);
      for (std::size_t c = 0; c < nc; ++c) {
        runs[c] = contenders[c].prepare(n);
        if (runs[c]) runs[c]();
      }
      // timed runs, the starting contender rotating
      std::vector<std::vector<double>> seconds(nc);
      std::vector<Outcome> last(nc);
      for (int k = 0; k < repeat; ++k)
        for (std::size_t i = 0; i < nc; ++i) {
          const std::size_t c = (i + k) % nc;
          if (!runs[c]) continue;
          last[c] = runs[c]();
          seconds[c].push_back(last[c].seconds);
        }

      std::vector<double> median(nc, 0.0);
      for (std::size_t c = 0; c < nc; ++c) {
        if (!runs[c]) {
          std::printf("%5d  %-13s not measured\n", n, contenders[c].name.c_str());
          continue;
        }
        const Outcome& o = last[c];
        median[c] = Median(seconds[c]);
        cost[c].push_back(median[c] / o.all_rhs());
        wall[c].push_back(median[c]);
        sizes_of[c].push_back(n);
        const double drift = chain.Energy(o.theta, o.omega);  // E(0) = 0: horizontal, at rest
        std::printf("%5d  %-13s %9.2f %9.2f %7ld %8ld %8ld %5ld %7ld %8.2f %11.2e", n, contenders[c].name.c_str(),
                    1e3 * median[c], 1e3 * *std::min_element(seconds[c].begin(), seconds[c].end()), o.steps, o.rhs,
                    o.jac_rhs, o.jac_evals, o.linear_iters, 1e6 * cost[c].back(), drift);
        if (c > 0 && runs[0])
          std::printf(" %9.1e", (o.theta - last[0].theta).cwiseAbs().maxCoeff());
        std::printf("\n");
      }
      for (std::size_t c = 1; c < nc; ++c)
        if (runs[c] && runs[0])
          std::printf("      %s / %s: wall time %.2f, steps %.2f, RHS evaluations %.2f, us/RHS %.2f\n",
                      contenders[c].name.c_str(), contenders[0].name.c_str(), median[c] / median[0],
                      double(last[c].steps) / last[0].steps, double(last[c].all_rhs()) / last[0].all_rhs(),
                      (median[c] / last[c].all_rhs()) / (median[0] / last[0].all_rhs()));
      std::printf("      energy scale (released from horizontal to hanging) m g L N^2/2 = %.3g J\n",
                  chain.EnergyScale());
    }

    // growth exponents over the sizes each contender ran (log-log least-squares slopes)
    for (const auto& [what, values] : {std::pair{"cost per RHS evaluation", &cost}, std::pair{"wall time", &wall}}) {
      std::printf("\ngrowth of %s with N:", what);
      for (std::size_t c = 0; c < nc; ++c)
        if (sizes_of[c].size() >= 2)
          std::printf(" %s %.2f (N %g..%g)%s", contenders[c].name.c_str(), Slope(sizes_of[c], (*values)[c]),
                      sizes_of[c].front(), sizes_of[c].back(), c + 1 < nc ? "," : "");
      std::printf("\n");
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pendulum_chain: %s\n", e.what());
    return 1;
  }
  return 0;
}
