// Benchmark P4 of ../shared/BENCH.md: planar chain of N uniform rods (1 kg,
// 1 m) on revolute joints, the first hinged to the ground, gravity 9.81,
// released horizontal at rest, t_end = 5 s, N = 2, 10, 50.
//
// Two programs of the same mechanics in one process, at rtol 1e-6, atol 1e-8:
//   mechflow   a diagram with one mechanism (generated as XML text, loaded
//              outside the timing), relative joint angles, articulated-body
//              dynamics, run by blocks::Simulator;
//   reference  the chain's equations of motion written directly against CVODE
//              in absolute angles theta_i (from the horizontal):
//                sum_j b_ij cos(th_i - th_j) th_j'' + I th_i''
//                  = -sum_j b_ij sin(th_i - th_j) th_j'^2 - g c_i cos(th_i)
//              with b_ij = l^2 (N - 1 - max(i,j)) + l^2/2 (i != j) or + l^2/4
//              (i = j), c_i = l (N - 1 - i) + l/2, I = m l^2 / 12, solved by a
//              Cholesky factorisation per evaluation (preallocated).
// Both use BDF + Newton + dense LU with CVODE's difference-quotient Jacobian.
// Runs alternate; wall times are medians. Printed per N: wall time, steps,
// RHS evaluations (integrator + Jacobian), their ratios, the cost per RHS
// evaluation, the energy drift of each, and the growth exponent of the cost
// per RHS evaluation with N (least squares on log-log).
//
// Usage: bench_pendulum_chain [--repeat K] [--sizes 2,10,50]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "blocks/simulator.h"
#include "diagrams/loader.h"
#include "diagrams/xml_reader.h"

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kG = 9.81, kL = 1.0, kM = 1.0, kRtol = 1e-6, kAtol = 1e-8, kTEnd = 5.0;

struct Outcome {
  double seconds = 0.0;
  long steps = 0, rhs = 0, jac_rhs = 0;
  std::vector<double> theta, omega;  // absolute angles and rates at t_end
};

// ---------------------------------------------------------------------------
// reference: the chain in absolute angles, written directly

struct Chain {
  int n;
  Eigen::MatrixXd b, M;
  Eigen::VectorXd c, rhs;
  Eigen::LLT<Eigen::MatrixXd> llt;
  explicit Chain(int size) : n(size), b(size, size), M(size, size), c(size), rhs(size), llt(size) {
    for (int i = 0; i < n; ++i) {
      c(i) = kM * kL * (n - 1 - i) + kM * kL / 2;
      for (int j = 0; j < n; ++j)
        b(i, j) = kM * kL * kL * (n - 1 - std::max(i, j)) + kM * kL * kL * (i == j ? 0.25 : 0.5);
    }
  }
  double Energy(const double* th, const double* w) const {
    double kinetic = 0, potential = 0;
    for (int i = 0; i < n; ++i) {
      potential += kG * c(i) * std::sin(th[i]);
      kinetic += 0.5 * kM * kL * kL / 12 * w[i] * w[i];
      for (int j = 0; j < n; ++j) kinetic += 0.5 * b(i, j) * std::cos(th[i] - th[j]) * w[i] * w[j];
    }
    return kinetic + potential;
  }
};

int ChainRhs(double, N_Vector y, N_Vector ydot, void* user) {
  Chain& ch = *static_cast<Chain*>(user);
  const double* th = N_VGetArrayPointer(y);
  const double* w = th + ch.n;
  double* d = N_VGetArrayPointer(ydot);
  for (int i = 0; i < ch.n; ++i) {
    double r = -kG * ch.c(i) * std::cos(th[i]);
    for (int j = 0; j < ch.n; ++j) {
      ch.M(i, j) = ch.b(i, j) * std::cos(th[i] - th[j]) + (i == j ? kM * kL * kL / 12 : 0.0);
      r -= ch.b(i, j) * std::sin(th[i] - th[j]) * w[j] * w[j];
    }
    ch.rhs(i) = r;
    d[i] = w[i];
  }
  ch.llt.compute(ch.M);
  ch.llt.solveInPlace(ch.rhs);
  for (int i = 0; i < ch.n; ++i) d[ch.n + i] = ch.rhs(i);
  return 0;
}

void Check(int flag, const char* what) {
  if (flag < 0) throw std::runtime_error(std::string(what) + " failed with flag " + std::to_string(flag));
}

Outcome RunReference(int n) {
  const auto start = Clock::now();
  Chain chain(n);
  SUNContext ctx = nullptr;
  Check(SUNContext_Create(nullptr, &ctx), "SUNContext_Create");
  N_Vector y = N_VNew_Serial(2 * n, ctx);
  N_VConst(0.0, y);
  SUNMatrix a = SUNDenseMatrix(2 * n, 2 * n, ctx);
  SUNLinearSolver ls = SUNLinSol_Dense(y, a, ctx);
  void* mem = CVodeCreate(CV_BDF, ctx);
  Check(CVodeInit(mem, ChainRhs, 0.0, y), "CVodeInit");
  Check(CVodeSetUserData(mem, &chain), "CVodeSetUserData");
  Check(CVodeSStolerances(mem, kRtol, kAtol), "CVodeSStolerances");
  Check(CVodeSetLinearSolver(mem, ls, a), "CVodeSetLinearSolver");
  Check(CVodeSetMaxNumSteps(mem, 500000), "CVodeSetMaxNumSteps");
  Check(CVodeSetStopTime(mem, kTEnd), "CVodeSetStopTime");
  double t = 0;
  for (int k = 1; k <= 1000; ++k) Check(CVode(mem, kTEnd * k / 1000, y, &t, CV_NORMAL), "CVode");
  Outcome out;
  Check(CVodeGetNumSteps(mem, &out.steps), "CVodeGetNumSteps");
  Check(CVodeGetNumRhsEvals(mem, &out.rhs), "CVodeGetNumRhsEvals");
  Check(CVodeGetNumLinRhsEvals(mem, &out.jac_rhs), "CVodeGetNumLinRhsEvals");
  const double* s = N_VGetArrayPointer(y);
  out.theta.assign(s, s + n);
  out.omega.assign(s + n, s + 2 * n);
  CVodeFree(&mem);
  SUNLinSolFree(ls);
  SUNMatDestroy(a);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  out.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

// ---------------------------------------------------------------------------
// mechflow: the same chain as a diagram

std::string ChainDiagram(int n) {
  std::ostringstream x;
  x << "<diagram name=\"chain\">\n<mechanism name=\"c\">\n";
  for (int i = 1; i <= n; ++i)
    x << "<body name=\"R" << i << "\" mass=\"1\" com=\"0 0.5 0\" inertia=\"1/12 1e-6 1/12\"/>\n";
  for (int i = 1; i <= n; ++i)
    x << "<joint name=\"j" << i << "\" type=\"rotational\" body1=\"" << (i == 1 ? "Base0" : "R" + std::to_string(i - 1))
      << "\" body2=\"R" << i << "\"" << (i == 1 ? "" : " point1=\"0 1 0\"") << " axis=\"1 0 0\"/>\n";
  for (int i = 1; i <= n; ++i) {
    x << "<sensor name=\"q" << i << "\" kind=\"coordinate\" dof=\"j" << i << "\"/>\n";
    x << "<sensor name=\"w" << i << "\" kind=\"velocity\" dof=\"j" << i << "\"/>\n";
  }
  x << "</mechanism>\n<solver t_end=\"" << kTEnd << "\" rtol=\"" << kRtol << "\" atol=\"" << kAtol
    << "\"/>\n<output interval=\"" << kTEnd / 1000 << "\">\n";
  for (int i = 1; i <= n; ++i) x << "<log signal=\"c.q" << i << "\"/><log signal=\"c.w" << i << "\"/>\n";
  x << "</output>\n</diagram>\n";
  return x.str();
}

Outcome RunMechflow(const mechflow::diagrams::LoadedDiagram& loaded, int n) {
  const auto start = Clock::now();
  mechflow::blocks::Simulator sim(*loaded.diagram, loaded.solver, loaded.logged);
  const auto outcome = sim.Run();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (!outcome.ok) throw std::runtime_error("mechflow run failed: " + outcome.failure);
  Outcome out;
  out.seconds = seconds;
  out.steps = sim.stats().steps;
  out.rhs = sim.stats().rhs_evals;
  out.jac_rhs = sim.stats().jac_rhs_evals;
  const auto& r = sim.results();
  const int last = r.num_rows() - 1;
  double th = 0, w = 0;
  for (int i = 0; i < n; ++i) {  // relative -> absolute
    th += r.at(last, 1 + 2 * i);
    w += r.at(last, 2 + 2 * i);
    out.theta.push_back(th);
    out.omega.push_back(w);
  }
  return out;
}

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += std::log(x[i]) / x.size(), my += std::log(y[i]) / y.size();
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    sxx += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return sxy / sxx;
}

}  // namespace

int main(int argc, char** argv) {
  int repeat = 5;
  std::vector<int> sizes = {2, 10, 50};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--repeat" && i + 1 < argc) {
      repeat = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--sizes" && i + 1 < argc) {
      sizes.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');) sizes.push_back(std::max(1, std::atoi(item.c_str())));
    } else {
      std::fprintf(stderr, "usage: %s [--repeat K] [--sizes 2,10,50]\n", argv[0]);
      return 2;
    }
  }
  try {
    std::printf("P4 pendulum chain: rtol %g, atol %g, t_end %g s, median of %d runs\n\n", kRtol, kAtol, kTEnd, repeat);
    std::printf("%4s %11s %11s %6s %7s %7s %6s %8s %8s %6s %10s %10s %9s\n", "N", "mf [ms]", "ref [ms]", "ratio",
                "mf stp", "ref stp", "ratio", "mf RHS", "ref RHS", "ratio", "mf us/RHS", "ref us/RHS", "|dtheta|");
    std::vector<double> ns, cost_mf, cost_ref;
    for (int n : sizes) {
      const auto loaded = mechflow::diagrams::LoadDiagramDescription(
          mechflow::diagrams::ReadDiagramText(ChainDiagram(n), "chain.xml"));
      RunMechflow(loaded, n);  // warm-up
      RunReference(n);
      std::vector<double> tm, tr;
      Outcome m, r;
      for (int k = 0; k < repeat; ++k) {
        if (k % 2 == 0) {
          m = RunMechflow(loaded, n);
          r = RunReference(n);
        } else {
          r = RunReference(n);
          m = RunMechflow(loaded, n);
        }
        tm.push_back(m.seconds);
        tr.push_back(r.seconds);
      }
      double dtheta = 0;
      for (int i = 0; i < n; ++i) dtheta = std::max(dtheta, std::abs(m.theta[i] - r.theta[i]));
      const double wm = Median(tm), wr = Median(tr);
      const long em = m.rhs + m.jac_rhs, er = r.rhs + r.jac_rhs;
      ns.push_back(n);
      cost_mf.push_back(wm / em);
      cost_ref.push_back(wr / er);
      std::printf("%4d %11.2f %11.2f %6.2f %7ld %7ld %6.2f %8ld %8ld %6.2f %10.2f %10.2f %9.1e\n", n, 1e3 * wm,
                  1e3 * wr, wm / wr, m.steps, r.steps, double(m.steps) / r.steps, em, er, double(em) / er,
                  1e6 * wm / em, 1e6 * wr / er, dtheta);
      const Chain chain(n);
      const std::vector<double> zero(n, 0.0);
      const double e0 = chain.Energy(zero.data(), zero.data());
      std::printf("     energy drift at t_end: mechflow %.2e J, reference %.2e J (scale m g L N^2/2 = %.3g J)\n",
                  chain.Energy(m.theta.data(), m.omega.data()) - e0, chain.Energy(r.theta.data(), r.omega.data()) - e0,
                  kM * kG * kL * n * n / 2.0);
    }
    if (ns.size() >= 2)
      std::printf("\ngrowth of cost per RHS evaluation with N (log-log slope): mechflow %.2f, reference %.2f\n",
                  Slope(ns, cost_mf), Slope(ns, cost_ref));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pendulum_chain: %s\n", e.what());
    return 1;
  }
  return 0;
}
