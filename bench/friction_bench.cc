// Benchmarks P1, P2, P3 of bench/README.md: friction with stick/slip
// events, a mechflow diagram against the same equations written directly
// against CVODE (bench/friction_direct.h, tested on its own by
// tests/mech/friction_reference_test.cc), in one process, at the same
// tolerances, with the same events located by CVODE's root finding.
//
//   P1  seed diagrams/examples/elast_friction.xml, variants Standard + Free,
//       t_end 2 s: box m 10 at 1.5 m/s stopped by a Frictional element;
//       expected stop at 1.5 s after 1.125 m. Reports the stop and the creep
//       after it (x - x_s at t_end); then both again without the output grid
//       (one row at t_end), to show what recording the rows costs.
//   P2  stick-slip: body m 1 on a translational joint with a Frictional
//       element (mu_d m g, ratio mu_s/mu_d = 1.5), pulled by a spring c 100
//       from a leader with prescribed motion 0.1 t; t_end 20 s. Reports the
//       period against the closed-form Coulomb period (CoulombStickSlip).
//   P3  chain-N, N = 10, 100, 1000, 10000 (--sizes), t_end 1 s. Reports the growth
//       exponent of the wall time with N.
// P2's and P3's diagrams are generated (bench/friction_diagram.h) from the
// same description the direct program integrates, loaded outside the timing.
//
// Contenders: mechflow (blocks::Simulator with the diagram's solver, linear
// solver auto: dense LU with difference-quotient Jacobian below 100 states,
// else coloured sparse Jacobian and KLU when the pattern is sparse);
// direct-dense (dense LU, difference-quotient Jacobian, as the simulator's
// dense path, so counts compare); for P3 also mechflow-dense (the simulator
// forced dense), direct-band (banded LU with the analytic Jacobian) and
// direct-band-ftz (the same with flush-to-zero, the subnormal trap of bench/README.md). The
// -ops contenders are the direct programs with mechflow's compiled vector
// operations (blocks/solver/compiled_ops.h) in place of Debian's unoptimised ones:
// the comparison with equal vector kernels. Dense
// contenders are skipped above --dense-max (default 100: at N = 1000 a run
// would take an hour or more), mechflow above --mechflow-max (10000).
// Final states are compared with a tight run of the direct program (rtol
// 1e-10, atol 1e-12, untimed). One untimed warm-up of each contender, then
// --repeat timed runs, the starting contender rotating.
//
// Usage: bench_friction [--problems 1,2,3] [--repeat K] [--sizes 10,100,1000,10000] [--dense-max N] [--mechflow-max N]
//                       [--only mechflow,direct-dense]   (the contenders to run, e.g. to profile one)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/friction_diagram.h"
#include "bench/friction_direct.h"
#include "blocks/solver/compiled_ops.h"
#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"

namespace {

using Clock = std::chrono::steady_clock;
namespace mb = mechflow::bench;

constexpr double kRtol = 1e-6, kAtol = 1e-8;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// One timed run of a contender.
struct Outcome {
  double seconds = 0.0;
  long steps = 0, rhs = 0, jac_rhs = 0, jac_evals = 0, events = 0;
  std::vector<double> x, v;          // at t_end
  std::vector<double> stops, breaks;  // mass 1: SLIP+ -> STICK and STICK -> SLIP+ times
  double creep = kNaN;               // P1: x - x_s at t_end
};

struct Contender {
  std::string name;
  std::function<Outcome()> run;  // empty: not measured
};

// --only: the contenders to run (all when empty), e.g. to profile one alone
std::vector<std::string> only_contenders;

bool Selected(const std::string& name) {
  return only_contenders.empty() ||
         std::find(only_contenders.begin(), only_contenders.end(), name) != only_contenders.end();
}

// ---------------------------------------------------------------------------
// the two kinds of runs

Outcome Direct(const mb::FrictionLine& line, const std::vector<double>& x0, const std::vector<double>& v0,
               mb::FrictionRunOptions options) {
  const mb::FrictionRunResult r = mb::RunFrictionLine(line, x0, v0, options);
  Outcome o{r.seconds, r.steps, r.rhs_evals, r.jac_rhs_evals, r.jac_evals, static_cast<long>(r.events.size()),
            r.x, r.v, {}, {}, r.x[0] - r.anchors[0]};
  for (const mb::FrictionEvent& e : r.events) {
    if (e.mass != 0) continue;
    if (e.crossing == 0) o.stops.push_back(e.time);
    if (e.crossing == 2) o.breaks.push_back(e.time);
  }
  return o;
}

// A loaded diagram whose mechanism "m" logs m.x<i>, m.v<i> (or m.x, m.v for
// one mass); the first mechanism crossings are mass 1's Frictional element
// (stop forward = 0, break forward = 2). creep_force: with the logged friction
// force F_s, x - x_s = -(F_s + d v)/c while stuck.
std::function<Outcome()> Mechflow(std::shared_ptr<const mechflow::diagrams::LoadedDiagram> loaded, int n,
                                  const mb::FrictionLaw* creep_law = nullptr, bool force_dense = false) {
  mechflow::blocks::SolverOptions solver = loaded->solver;
  if (force_dense) solver.linear_solver = mechflow::blocks::LinearSolverKind::kDense;
  const mechflow::blocks::Results columns(
      [&] {
        std::vector<std::string> names;
        for (const auto& s : loaded->logged) names.push_back(s.name);
        return names;
      }());
  std::vector<int> xc(n), vc(n);
  for (int i = 0; i < n; ++i) {
    const std::string suffix = n == 1 && columns.FindColumn("m.x") >= 0 ? "" : std::to_string(i + 1);
    xc[i] = columns.FindColumn("m.x" + suffix);
    vc[i] = columns.FindColumn("m.v" + suffix);
    if (xc[i] < 0 || vc[i] < 0) throw std::runtime_error("diagram does not log m.x" + suffix + " and m.v" + suffix);
  }
  const int fc = creep_law ? columns.FindColumn("m.force") : -1;
  if (creep_law && fc < 0) throw std::runtime_error("diagram does not log m.force");
  const mb::FrictionLaw law = creep_law ? *creep_law : mb::FrictionLaw{};
  return [loaded, solver, n, xc, vc, fc, law] {
    const auto start = Clock::now();
    mechflow::blocks::Simulator sim(*loaded->diagram, solver, loaded->logged);
    const auto outcome = sim.Run();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    if (!outcome.ok) throw std::runtime_error("mechflow run failed: " + outcome.failure);
    const auto& st = sim.stats();
    const auto& r = sim.results();
    const int last = r.num_rows() - 1;
    Outcome o;
    o.seconds = seconds;
    o.steps = st.steps, o.rhs = st.rhs_evals, o.jac_rhs = st.jac_rhs_evals, o.jac_evals = st.jac_evals;
    o.events = st.events;
    for (int i = 0; i < n; ++i) o.x.push_back(r.at(last, xc[i])), o.v.push_back(r.at(last, vc[i]));
    for (const auto& e : sim.events()) {
      if (e.crossing == 0) o.stops.push_back(e.time);
      if (e.crossing == 2) o.breaks.push_back(e.time);
    }
    if (fc >= 0) o.creep = 0.0 - (r.at(last, fc) + law.damping * r.at(last, vc[0])) / law.stiffness;  // no -0
    return o;
  };
}

std::shared_ptr<const mechflow::diagrams::LoadedDiagram> LoadText(const std::string& xml) {
  return std::make_shared<const mechflow::diagrams::LoadedDiagram>(
      mechflow::diagrams::LoadDiagramDescription(mechflow::diagrams::ReadDiagramText(xml, "generated.xml")));
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

double MaxDiff(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

// Warm-up, timed runs (starting contender rotating), table. Returns the last
// outcome and the median wall time of each contender (NaN: not measured).
struct Measured {
  std::vector<Outcome> last;
  std::vector<double> median;
};

Measured Measure(const std::vector<Contender>& contenders, int repeat, const Outcome& tight, const char* label) {
  const std::size_t nc = contenders.size();
  Measured m{std::vector<Outcome>(nc), std::vector<double>(nc, kNaN)};
  std::vector<std::vector<double>> seconds(nc);
  std::vector<bool> runs(nc);
  for (std::size_t c = 0; c < nc; ++c) runs[c] = contenders[c].run && Selected(contenders[c].name);
  for (std::size_t c = 0; c < nc; ++c)
    if (runs[c]) contenders[c].run();
  for (int k = 0; k < repeat; ++k)
    for (std::size_t i = 0; i < nc; ++i) {
      const std::size_t c = (i + k) % nc;
      if (!runs[c]) continue;
      m.last[c] = contenders[c].run();
      seconds[c].push_back(m.last[c].seconds);
    }
  for (std::size_t c = 0; c < nc; ++c) {
    if (!runs[c]) {
      std::printf("%6s  %-16s not measured\n", label, contenders[c].name.c_str());
      continue;
    }
    const Outcome& o = m.last[c];
    m.median[c] = Median(seconds[c]);
    std::printf("%6s  %-16s %10.2f %10.2f %7ld %8ld %8ld %5ld %7ld %10.1e %10.1e\n", label, contenders[c].name.c_str(),
                1e3 * m.median[c], 1e3 * *std::min_element(seconds[c].begin(), seconds[c].end()), o.steps, o.rhs,
                o.jac_rhs, o.jac_evals, o.events, MaxDiff(o.x, tight.x), MaxDiff(o.v, tight.v));
  }
  // ratios of mechflow (first) to each direct contender
  for (std::size_t c = 1; c < nc; ++c)
    if (runs[0] && runs[c])
      std::printf("        %s / %s: wall time %.2f, steps %.2f, RHS evaluations (all) %.2f\n",
                  contenders[0].name.c_str(), contenders[c].name.c_str(), m.median[0] / m.median[c],
                  double(m.last[0].steps) / m.last[c].steps,
                  double(m.last[0].rhs + m.last[0].jac_rhs) / (m.last[c].rhs + m.last[c].jac_rhs));
  return m;
}

void Header() {
  std::printf("%6s  %-16s %10s %10s %7s %8s %8s %5s %7s %10s %10s\n", "", "contender", "wall [ms]", "fast [ms]",
              "steps", "RHS int", "RHS jac", "Jac", "events", "|dx| tight", "|dv| tight");
}

// The direct programs keep the rows the diagram logs (x_i, v_i for P2 and P3)
// unless told otherwise, as a program writing the same results would.
mb::FrictionRunOptions Options(double t_end, int outputs, double rtol, double atol, mb::LinearSolver solver,
                               bool ftz, bool compiled_ops = false,
                               mb::FrictionRunOptions::Rows rows = mb::FrictionRunOptions::Rows::kStates) {
  mb::FrictionRunOptions o;
  o.rows = rows;
  o.t_end = t_end, o.num_outputs = outputs, o.rtol = rtol, o.atol = atol, o.solver = solver;
  o.flush_subnormals = ftz;
  if (compiled_ops) o.vector_ops = mechflow::blocks::sundials::UseCompiledVectorOps;
  return o;
}

// ---------------------------------------------------------------------------

void RunP1(int repeat) {
  const double t_end = 2.0, v0 = 1.5;
  mechflow::diagrams::LoadOptions load;
  load.variants = {"Standard", "Free"};
  load.t_end = t_end;
  auto loaded = std::make_shared<mechflow::diagrams::LoadedDiagram>(
      mechflow::diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/elast_friction.xml", load));
  loaded->solver.rtol = kRtol, loaded->solver.atol = kAtol;
  const int outputs = static_cast<int>(std::lround(t_end / loaded->solver.output_interval));
  const mb::FrictionLine line = mb::FreeSlideLine();
  const std::vector<double> x0{0.0}, v0s{v0};
  const Outcome tight = Direct(line, x0, v0s, Options(t_end, outputs, 1e-10, 1e-12, mb::LinearSolver::kDenseDifferenceQuotient, false));
  const mb::SlideStop exact = mb::FreeSlideStop(line.masses[0], v0, line.friction.friction);

  std::printf("P1 free slide (seed ElastFriction, variants Standard + Free): m 10, v0 1.5 m/s, F 10 N, "
              "t = 0..%g s, rtol %g, atol %g, %d output times, median of %d runs\n",
              t_end, kRtol, kAtol, outputs, repeat);
  Header();
  // The seed logs x, v, the friction force and mode, and four columns that
  // are zero in this variant (the switched-off elastic element, the resting
  // base), which the direct program does not model.
  const auto rows = mb::FrictionRunOptions::Rows::kStatesAndFriction;
  const auto dense = mb::LinearSolver::kDenseDifferenceQuotient;
  const std::vector<Contender> contenders = {
      {"mechflow", Mechflow(loaded, 1, &line.friction)},
      {"direct-dense", [&] { return Direct(line, x0, v0s, Options(t_end, outputs, kRtol, kAtol, dense, false, false, rows)); }},
      {"direct-dense-ops", [&] { return Direct(line, x0, v0s, Options(t_end, outputs, kRtol, kAtol, dense, false, true, rows)); }},
      {"direct-no-rows", [&] { return Direct(line, x0, v0s, Options(t_end, outputs, kRtol, kAtol, dense, false, false, mb::FrictionRunOptions::Rows::kNone)); }}};
  const Measured m = Measure(contenders, repeat, tight, "P1");
  // the same with no output grid (rows at 0 and t_end only): what the 2001 rows cost
  auto bare = std::make_shared<mechflow::diagrams::LoadedDiagram>(
      mechflow::diagrams::LoadDiagram(std::string(MECHFLOW_SOURCE_DIR) + "/diagrams/examples/elast_friction.xml", load));
  bare->solver.rtol = kRtol, bare->solver.atol = kAtol, bare->solver.output_interval = t_end;
  Measure({{"mechflow-1-row", Mechflow(bare, 1, &line.friction)},
           {"direct-1-row", [&] { return Direct(line, x0, v0s, Options(t_end, 1, kRtol, kAtol, mb::LinearSolver::kDenseDifferenceQuotient, false)); }}},
          repeat, tight, "P1");
  std::printf("        closed form: stop at t = %.6f s after %.6f m\n", exact.time, exact.distance);
  for (std::size_t c = 0; c < contenders.size(); ++c) {
    const Outcome& o = m.last[c];
    if (std::isnan(m.median[c])) continue;
    const double stop = o.stops.empty() ? kNaN : o.stops.front();
    std::printf("        %-16s stop at t = %.9f s (%zu stop events), x_s = %.9f m, creep x - x_s at t_end = %.2e m\n",
                contenders[c].name.c_str(), stop, o.stops.size(), o.x[0] - o.creep, o.creep);
  }
  std::printf("\n");
}

void RunP2(int repeat) {
  const double t_end = 20.0;
  const int outputs = 20000;  // every 1 ms
  const mb::FrictionLine line = mb::StickSlipLine();
  const std::vector<double> zero{0.0};
  mb::DiagramSettings settings;
  settings.t_end = t_end, settings.num_outputs = outputs, settings.rtol = kRtol, settings.atol = kAtol;
  const auto loaded = LoadText(mb::FrictionLineDiagram(line, zero, zero, settings));
  const Outcome tight = Direct(line, zero, zero, Options(t_end, outputs, 1e-10, 1e-12, mb::LinearSolver::kDenseDifferenceQuotient, false));
  const mb::StickSlipCycle exact = mb::CoulombStickSlip(1.0, 100.0, 0.1, 0.6, 0.4, 9.81);

  std::printf("P2 stick-slip: m 1, spring 100 N/m from a leader at 0.1 m/s, mu_s 0.6, mu_d 0.4 (Frictional: F = mu_d m g, "
              "ratio 1.5, stick at 50 Hz, damping ratio 0.1), t = 0..%g s, rtol %g, atol %g, median of %d runs\n",
              t_end, kRtol, kAtol, repeat);
  Header();
  const std::vector<Contender> contenders = {
      {"mechflow", Mechflow(loaded, 1)},
      {"direct-dense", [&] { return Direct(line, zero, zero, Options(t_end, outputs, kRtol, kAtol, mb::LinearSolver::kDenseDifferenceQuotient, false)); }},
      {"direct-dense-ops", [&] { return Direct(line, zero, zero, Options(t_end, outputs, kRtol, kAtol, mb::LinearSolver::kDenseDifferenceQuotient, false, true)); }}};
  const Measured m = Measure(contenders, repeat, tight, "P2");
  std::printf("        closed-form Coulomb period (rigid stick): stick %.6f + slip %.6f = %.6f s\n", exact.stick,
              exact.slip, exact.period());
  auto report = [&](const char* name, const Outcome& o) {
    if (o.breaks.size() < 2) {
      std::printf("        %-16s fewer than two break-aways\n", name);
      return;
    }
    double lo = 1e300, hi = -1e300;
    for (std::size_t i = 1; i < o.breaks.size(); ++i) {
      const double p = o.breaks[i] - o.breaks[i - 1];
      lo = std::min(lo, p), hi = std::max(hi, p);
    }
    const double mean = (o.breaks.back() - o.breaks.front()) / (o.breaks.size() - 1);
    std::printf("        %-16s %zu cycles, period mean %.6f s (min %.6f, max %.6f), vs closed form %+.2e relative; "
                "first break-away at %.6f s\n",
                name, o.breaks.size() - 1, mean, lo, hi, mean / exact.period() - 1.0, o.breaks.front());
  };
  for (std::size_t c = 0; c < contenders.size(); ++c)
    if (!std::isnan(m.median[c])) report(contenders[c].name.c_str(), m.last[c]);
  report("tight direct", tight);
  std::printf("        closed form: first break-away at mu_s m g/(c V) = %.6f s\n\n", 0.6 * 9.81 / (100.0 * 0.1));
}

void RunP3(int repeat, const std::vector<int>& sizes, int dense_max, int mechflow_max) {
  const double t_end = 1.0;
  const int outputs = 1000;
  std::printf("P3 chain-N: masses 1 kg, spring-dampers 1e4 N/m + 10 N s/m, friction 0.3*9.81 N (ratio 1.2, stick at 50 Hz, "
              "damping ratio 0.1), 50 sin(2 pi 5 t) N on the last mass, t = 0..%g s, rtol %g, atol %g, median of %d runs\n",
              t_end, kRtol, kAtol, repeat);
  Header();
  const std::vector<std::string> names = {"mechflow", "mechflow-dense", "direct-dense", "direct-band",
                                          "direct-band-ftz", "direct-band-ops"};
  std::vector<std::vector<double>> ns(names.size()), cost(names.size());
  for (const int n : sizes) {
    const mb::FrictionLine line = mb::ChainLine(n);
    const std::vector<double> zero(n, 0.0);
    const Outcome tight = Direct(line, zero, zero, Options(t_end, outputs, 1e-10, 1e-12, mb::LinearSolver::kBandAnalytic, true));
    std::shared_ptr<const mechflow::diagrams::LoadedDiagram> loaded;
    mb::DiagramSettings settings;
    settings.t_end = t_end, settings.num_outputs = outputs, settings.rtol = kRtol, settings.atol = kAtol;
    if (n <= mechflow_max) loaded = LoadText(mb::FrictionLineDiagram(line, zero, zero, settings));
    auto direct = [line, zero, t_end](mb::LinearSolver solver, bool ftz, bool ops = false) {
      return std::function<Outcome()>([=] { return Direct(line, zero, zero, Options(t_end, outputs, kRtol, kAtol, solver, ftz, ops)); });
    };
    const std::vector<Contender> contenders = {
        {names[0], loaded ? Mechflow(loaded, n) : std::function<Outcome()>()},
        {names[1], loaded && n <= dense_max ? Mechflow(loaded, n, nullptr, true) : std::function<Outcome()>()},
        {names[2], n <= dense_max ? direct(mb::LinearSolver::kDenseDifferenceQuotient, false) : std::function<Outcome()>()},
        {names[3], direct(mb::LinearSolver::kBandAnalytic, false)},
        {names[4], direct(mb::LinearSolver::kBandAnalytic, true)},
        {names[5], direct(mb::LinearSolver::kBandAnalytic, true, true)}};
    const Measured m = Measure(contenders, repeat, tight, ("N=" + std::to_string(n)).c_str());
    for (std::size_t c = 0; c < names.size(); ++c)
      if (!std::isnan(m.median[c])) ns[c].push_back(n), cost[c].push_back(m.median[c]);
  }
  std::printf("\ngrowth of wall time with N (log-log least-squares slope over the sizes measured):");
  for (std::size_t c = 0; c < names.size(); ++c)
    if (ns[c].size() >= 2) std::printf(" %s %.2f (N %g..%g);", names[c].c_str(), Slope(ns[c], cost[c]), ns[c].front(), ns[c].back());
  std::printf("\n");
}

std::vector<int> List(const char* text) {
  std::vector<int> out;
  std::stringstream list(text);
  for (std::string item; std::getline(list, item, ',');) out.push_back(std::atoi(item.c_str()));
  return out;
}

int Usage(const char* argv0) {
  std::fprintf(stderr, "usage: %s [--problems 1,2,3] [--repeat K] [--sizes 10,100,1000,10000] [--dense-max N] [--mechflow-max N] [--only NAME,...]\n",
               argv0);
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5, dense_max = 100, mechflow_max = 10000;
  std::vector<int> problems = {1, 2, 3}, sizes = {10, 100, 1000, 10000};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return Usage(argv[0]);
    if (arg == "--repeat") {
      repeat = std::atoi(argv[++i]);
    } else if (arg == "--dense-max") {
      dense_max = std::atoi(argv[++i]);
    } else if (arg == "--mechflow-max") {
      mechflow_max = std::atoi(argv[++i]);
    } else if (arg == "--problems") {
      problems = List(argv[++i]);
    } else if (arg == "--sizes") {
      sizes = List(argv[++i]);
    } else if (arg == "--only") {
      std::stringstream names(argv[++i]);
      for (std::string name; std::getline(names, name, ',');) only_contenders.push_back(name);
    } else {
      return Usage(argv[0]);
    }
  }
  if (repeat < 1 || sizes.empty() || *std::min_element(sizes.begin(), sizes.end()) < 1) return Usage(argv[0]);
  try {
    for (const int p : problems) {
      if (p == 1) RunP1(repeat);
      else if (p == 2) RunP2(repeat);
      else if (p == 3) RunP3(repeat, sizes, dense_max, mechflow_max);
      else return Usage(argv[0]);
      std::fflush(stdout);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_friction: %s\n", e.what());
    return 1;
  }
  return 0;
}
