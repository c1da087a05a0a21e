#include "analysis/linearization.h"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>

#include "blocks/framework/evaluation.h"
#include "blocks/library/friction_from_normal_force.h"
#include "blocks/library/mechanism_block.h"
#include "mech/errors.h"
#include "mech/mechanism.h"

namespace mechflow::analysis {

using namespace blocks;  // linearisation works on the dataflow framework's diagrams and contexts
namespace {

// Index of the largest |f_i| (0 when f is empty).
int LargestEntry(const std::vector<double>& f, int n) {
  int largest = 0;
  for (int i = 1; i < n; ++i)
    if (std::abs(f[i]) > std::abs(f[largest])) largest = i;
  return largest;
}

// Index of the first non-finite f_i, or -1.
int FirstNonFinite(const std::vector<double>& f, int n) {
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(f[i])) return i;
  return -1;
}

double Norm2(const std::vector<double>& f, int n) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += f[i] * f[i];
  return std::sqrt(sum);
}

// Evaluates the outputs at x and leaves the context pointing at x itself, with
// no derivative buffer: the probes' buffers do not outlive the caller.
void EvaluateAt(const Diagram& diagram, Context* ctx, const std::vector<double>& x) {
  ctx->x = const_cast<double*>(x.data());  // blocks only read states while evaluating outputs
  ctx->xdot = nullptr;
  ++ctx->evaluation;
  EvaluateOutputs(diagram, ctx);
}

std::string StateName(const Diagram& diagram, int i) {
  const std::vector<std::string> names = StateNames(diagram);
  return i >= 0 && i < static_cast<int>(names.size()) ? names[i] : "?";
}

}  // namespace

void PrepareContext(const Diagram& diagram, double t, Context* ctx, std::vector<double>* x) {
  ctx->time = t;
  ctx->signals.assign(diagram.num_signals(), 0.0);
  ctx->discrete.assign(diagram.num_discrete_states(), 0.0);
  x->assign(std::max(1, diagram.num_states()), 0.0);
  ctx->x = x->data();
  InitializeStates(diagram, ctx);
  SettleModes(diagram, ctx);
}

void StateDerivative(const Diagram& diagram, Context* ctx, std::vector<double>* x, std::vector<double>* xdot) {
  xdot->assign(x->size(), 0.0);
  ctx->x = x->data();
  ctx->xdot = xdot->data();
  ++ctx->evaluation;
  EvaluateOutputs(diagram, ctx);
  EvaluateDerivatives(diagram, ctx);
}

Eigen::MatrixXd StateJacobian(const Diagram& diagram, Context* ctx, const std::vector<double>& x) {
  const int n = diagram.num_states();
  Eigen::MatrixXd A(n, n);
  std::vector<double> probe(x), plus, minus;
  const double root_eps = std::cbrt(std::numeric_limits<double>::epsilon());
  for (int j = 0; j < n; ++j) {
    const double h = root_eps * std::max(1.0, std::abs(x[j]));
    probe[j] = x[j] + h;
    const double x_plus = probe[j];
    StateDerivative(diagram, ctx, &probe, &plus);
    probe[j] = x[j] - h;
    const double x_minus = probe[j];
    StateDerivative(diagram, ctx, &probe, &minus);
    probe[j] = x[j];
    const int bad = std::max(FirstNonFinite(plus, n), FirstNonFinite(minus, n));
    if (bad >= 0) {
      std::ostringstream out;
      out << "linearisation: the rate of state '" << StateName(diagram, bad) << "' is not finite when state '"
          << StateName(diagram, j) << "' is moved by " << h << " from " << x[j];
      throw SimulationError(out.str());
    }
    for (int i = 0; i < n; ++i) A(i, j) = (plus[i] - minus[i]) / (x_plus - x_minus);
  }
  EvaluateAt(diagram, ctx, x);
  return A;
}

namespace {

// The Newton step: s with A s = f, taken in the range of A. Where A is
// singular the part of x that x' cannot change (an invariant, such as a stick
// spring's deflection less its coordinate's travel) stays as it is, as a
// damped transient keeps it; where range and null space overlap (a free,
// undamped coordinate) the least-norm choice leaves that direction alone.
Eigen::VectorXd NewtonStep(const Eigen::MatrixXd& A, const std::vector<double>& f) {
  const Eigen::Map<const Eigen::VectorXd> rates(f.data(), A.rows());
  const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
  if (cod.rank() == A.cols()) return cod.solve(rates);
  if (cod.rank() == 0) return Eigen::VectorXd::Zero(A.cols());  // x' depends on no state: nothing to step
  const Eigen::MatrixXd range = Eigen::MatrixXd(cod.householderQ()).leftCols(cod.rank());
  return range * Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A * range).solve(rates);
}

// Damped Newton on x'(x) = 0 in the current modes (see FindEquilibrium);
// adds its steps to *steps. `context` ends the failure messages.
double SolveInModes(const Diagram& diagram, Context* ctx, std::vector<double>* x, double tolerance,
                    int max_iterations, int* steps, const std::string& context) {
  const int n = diagram.num_states();
  constexpr int kMaxHalvings = 10;
  std::vector<double> f, trial, f_trial;
  StateDerivative(diagram, ctx, x, &f);
  if (const int bad = FirstNonFinite(f, n); bad >= 0) {
    EvaluateAt(diagram, ctx, *x);
    throw SimulationError("no static equilibrium found: the rate of state '" + StateName(diagram, bad) +
                          "' is not finite at the " + (context.empty() ? "initial state" : "state reached") +
                          context);
  }
  auto failure = [&](const std::string& what, int taken) {
    const int worst = LargestEntry(f, n);
    std::ostringstream out;
    out << "no static equilibrium found: " << what << " after " << taken << " Newton step"
        << (taken == 1 ? "" : "s") << "; the largest rate is " << f[worst] << " (state '"
        << StateName(diagram, worst) << "'). Is the diagram driven, or free to drift at a constant rate?" << context;
    return SimulationError(out.str());
  };
  for (int it = 0;; ++it) {
    const Eigen::MatrixXd A = StateJacobian(diagram, ctx, *x);
    // converged: every rate is zero relative to the terms that balance in it
    bool converged = true;
    for (int i = 0; i < n && converged; ++i) {
      double terms = 1.0;
      for (int j = 0; j < n; ++j) terms += std::abs(A(i, j)) * std::abs((*x)[j]);
      converged = std::abs(f[i]) <= tolerance * terms;
    }
    if (converged) {
      *steps += it;
      return std::abs(f[LargestEntry(f, n)]);
    }
    if (it == max_iterations) throw failure("not converged", it);  // the context is at x

    const Eigen::VectorXd step = NewtonStep(A, f);
    // damping: halve the step until |f| decreases enough
    const double norm = Norm2(f, n);
    double alpha = 1.0;
    for (int halvings = 0;; ++halvings) {
      trial = *x;
      for (int i = 0; i < n; ++i) trial[i] -= alpha * step(i);
      StateDerivative(diagram, ctx, &trial, &f_trial);
      if (FirstNonFinite(f_trial, n) < 0 && Norm2(f_trial, n) < (1 - 1e-4 * alpha) * norm) break;
      if (halvings == kMaxHalvings) {
        EvaluateAt(diagram, ctx, *x);
        throw failure("Newton stalled (no step along the Newton direction reduces the rates)", it);
      }
      alpha /= 2;
    }
    std::swap(*x, trial);
    std::swap(f, f_trial);
    ctx->x = x->data();
  }
}

// "block.element" for a mechanism element's mode, the block's name for any
// other discrete state; what its modes are taken as, when it says.
struct SwitchingElement {
  std::string name;
  std::string taken_as;
};
SwitchingElement OwnerOfDiscrete(const Diagram& diagram, const Context& ctx, int index) {
  for (int b = 0; b < diagram.num_blocks(); ++b) {
    const BlockLayout& layout = diagram.layout(b);
    if (index < layout.first_discrete || index >= layout.first_discrete + layout.num_discrete) continue;
    const auto* block = dynamic_cast<const MechanismBlock*>(&diagram.block(b));
    if (!block) return {diagram.block(b).name(), ""};
    const mech::Mechanism& m = block->mechanism();
    for (int e = 0; e < m.num_elements(); ++e) {
      const int first = layout.first_discrete + m.mode_offset(e), count = m.element(e).num_modes();
      if (index < first || index >= first + count) continue;
      const std::span<const double> modes(ctx.discrete.data() + first, count);
      return {block->name() + "." + m.element(e).name(), m.element(e).LinearisedAs(modes)};
    }
    return {block->name(), ""};
  }
  return {"?", ""};
}

// The elements whose discrete states differ between `before` and the context's.
std::vector<SwitchingElement> Switched(const Diagram& diagram, const Context& ctx, const std::vector<double>& before) {
  std::vector<SwitchingElement> elements;
  for (int i = 0; i < static_cast<int>(before.size()); ++i) {
    if (before[i] == ctx.discrete[i]) continue;
    SwitchingElement e = OwnerOfDiscrete(diagram, ctx, i);
    if (elements.empty() || elements.back().name != e.name) elements.push_back(std::move(e));
  }
  return elements;
}

std::string Describe(const std::vector<SwitchingElement>& elements) {
  std::string text;
  for (const SwitchingElement& e : elements)
    text += (text.empty() ? "'" : ", '") + e.name + "'" + (e.taken_as.empty() ? "" : " (now " + e.taken_as + ")");
  return text;
}

// Makes the modes agree with the candidate x as a state at rest has them:
// one at-rest pass (Block::UpdateModesAtRest), then the modes settled as
// after an event. Leaves the context evaluated at x.
void SelectModesAtRest(const Diagram& diagram, Context* ctx, std::vector<double>* x) {
  ctx->x = x->data();
  ctx->xdot = nullptr;
  ++ctx->evaluation;
  EvaluateOutputs(diagram, ctx);
  for (int b = 0; b < diagram.num_blocks(); ++b)
    diagram.block(b).UpdateModesAtRest(BlockContext(ctx, &diagram.layout(b)));
  SettleModes(diagram, ctx);
  EvaluateAt(diagram, ctx, *x);
}

}  // namespace

EquilibriumResult FindEquilibrium(const Diagram& diagram, Context* ctx, std::vector<double>* x, double tolerance,
                                  int max_iterations) {
  constexpr int kMaxRounds = 20;
  const std::vector<double> initial_modes = ctx->discrete;
  EquilibriumResult result;
  std::string context;  // what the failure messages add after a switch
  for (result.rounds = 1;; ++result.rounds) {
    result.residual = SolveInModes(diagram, ctx, x, tolerance, max_iterations, &result.iterations, context);
    const std::vector<double> modes = ctx->discrete, candidate = *x;
    SelectModesAtRest(diagram, ctx, x);
    if (ctx->discrete == modes && *x == candidate) break;
    const std::vector<SwitchingElement> switched = Switched(diagram, *ctx, modes);
    if (result.rounds == kMaxRounds) {
      EvaluateAt(diagram, ctx, *x);
      std::ostringstream out;
      out << "no static equilibrium found: the modes of " << (switched.empty() ? "a block's state" : Describe(switched))
          << " do not settle: after " << kMaxRounds
          << " rounds each rest state found in its modes still puts it in others. Run the diagram (mechflow run) "
             "to see where it goes, or start it nearer its rest state";
      throw SimulationError(out.str());
    }
    context = "; the search had switched " + Describe(switched) + " at the rest state found in the modes before";
  }
  for (const SwitchingElement& e : Switched(diagram, *ctx, initial_modes)) result.switched.push_back(e.name);
  return result;
}

std::vector<Mode> ModalAnalysis(const Eigen::MatrixXd& A, const std::vector<bool>& normalise_on) {
  std::vector<Mode> modes;
  if (A.rows() == 0) return modes;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(A);
  const Eigen::VectorXcd values = solver.eigenvalues();
  const Eigen::MatrixXcd vectors = solver.eigenvectors();
  const double scale = std::max(1.0, A.cwiseAbs().maxCoeff());
  const double fastest = std::max(1.0, values.cwiseAbs().maxCoeff());
  for (int k = 0; k < values.size(); ++k) {
    const std::complex<double> lambda = values(k);
    if (lambda.imag() < -1e-12 * scale) continue;  // keep one of each conjugate pair
    Mode m;
    m.eigenvalue = lambda;
    const double magnitude = std::abs(lambda);
    const bool real = std::abs(lambda.imag()) <= 1e-12 * scale;
    m.frequency_hz = real ? 0.0 : std::abs(lambda.imag()) / (2.0 * std::numbers::pi);
    m.natural_frequency_hz = magnitude / (2.0 * std::numbers::pi);
    m.decay_rate = -lambda.real();
    if (magnitude <= 1e-9 * fastest) {
      m.kind = ModeKind::kRigidBody;
      m.damping_ratio = 0.0;
    } else {
      m.kind = !real ? ModeKind::kOscillating : lambda.real() < 0 ? ModeKind::kDecaying : ModeKind::kGrowing;
      m.damping_ratio = -lambda.real() / magnitude;
      if (std::abs(m.damping_ratio) < 1e-9) m.damping_ratio = 0.0;  // undamped, up to differencing noise
    }
    // shape: divide by the largest normalising component (makes it exactly 1)
    Eigen::VectorXcd v = vectors.col(k);
    Eigen::Index largest = -1;
    double best = -1.0;
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if ((normalise_on.empty() || normalise_on[i]) && std::abs(v(i)) > best) best = std::abs(v(i)), largest = i;
    if (largest < 0 || best == 0.0) {  // no normalising state takes part: use them all
      for (Eigen::Index i = 0; i < v.size(); ++i)
        if (std::abs(v(i)) > best) best = std::abs(v(i)), largest = i;
    }
    if (best > 0) v /= v(largest);
    m.shape.resize(v.size());
    for (Eigen::Index i = 0; i < v.size(); ++i) m.shape[i] = v(i).real();
    modes.push_back(std::move(m));
  }
  std::stable_sort(modes.begin(), modes.end(),
                   [](const Mode& a, const Mode& b) { return a.natural_frequency_hz < b.natural_frequency_hz; });
  return modes;
}

StateRoles FindStateRoles(const Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows();
  StateRoles roles{std::vector<bool>(n, false), std::vector<bool>(n, false)};
  constexpr double kTolerance = 1e-9;
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index unit = -1;
    bool other = false;
    for (Eigen::Index j = 0; j < n && !other; ++j) {
      if (std::abs(A(i, j)) <= kTolerance) continue;
      if (j != i && unit < 0 && std::abs(A(i, j) - 1.0) <= kTolerance) {
        unit = j;
      } else {
        other = true;
      }
    }
    if (unit >= 0 && !other) {
      roles.coordinate[i] = true;
      roles.rate[unit] = true;
    }
  }
  return roles;
}

std::vector<std::string> StateNames(const Diagram& diagram) {
  std::vector<std::string> names(diagram.num_states());
  for (int b = 0; b < diagram.num_blocks(); ++b) {
    const Block& block = diagram.block(b);
    for (int i = 0; i < block.num_states(); ++i)
      names[diagram.layout(b).first_state + i] = block.name() + "." + block.state_name(i);
  }
  return names;
}

std::vector<std::string> DescribeLinearisedModes(const Diagram& diagram, const Context& ctx) {
  std::vector<std::string> lines;
  for (int b = 0; b < diagram.num_blocks(); ++b) {
    const BlockLayout& layout = diagram.layout(b);
    if (const auto* block = dynamic_cast<const MechanismBlock*>(&diagram.block(b))) {
      const mech::Mechanism& m = block->mechanism();
      for (int e = 0; e < m.num_elements(); ++e) {
        const int n = m.element(e).num_modes();
        if (n == 0) continue;
        const std::span<const double> modes(ctx.discrete.data() + layout.first_discrete + m.mode_offset(e), n);
        lines.push_back(block->name() + "." + m.element(e).name() + ": " + m.element(e).LinearisedAs(modes));
      }
    } else if (const auto* friction = dynamic_cast<const FrictionFromNormalForceBlock*>(&diagram.block(b))) {
      const mech::FrictionLawParams& law = friction->law();
      const double normal = ctx.signals[layout.input_offset[friction->FindInput("N")]];
      const double v = ctx.signals[layout.input_offset[friction->FindInput("v")]];
      std::ostringstream line;
      if (std::abs(v) > 3 * law.regularisation_velocity) {
        line << friction->name() << ": sliding (v = " << v
             << "): the force follows v only through the Stribeck fall and the viscous term";
        lines.push_back(line.str());
        continue;
      }
      line << friction->name() << ": regularised near rest (v = " << v << ", v_reg = " << law.regularisation_velocity
           << "): a viscous damper of slope mu_s N / v_reg + c_visc = "
           << law.mu_static * friction->PressingForce(normal) / law.regularisation_velocity + law.viscous
           << " per unit of v, where Coulomb friction would stick";
      lines.push_back(line.str());
    }
  }
  return lines;
}

}  // namespace mechflow::analysis
