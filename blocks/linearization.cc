#include "blocks/linearization.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

#include "blocks/evaluation.h"
#include "mech/errors.h"

namespace mechflow::blocks {

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
  const double root_eps = std::cbrt(std::numeric_limits<double>::epsilon());  // central differences
  for (int j = 0; j < n; ++j) {
    const double h = root_eps * std::max(1.0, std::abs(x[j]));
    probe[j] = x[j] + h;
    StateDerivative(diagram, ctx, &probe, &plus);
    probe[j] = x[j] - h;
    StateDerivative(diagram, ctx, &probe, &minus);
    probe[j] = x[j];
    for (int i = 0; i < n; ++i) A(i, j) = (plus[i] - minus[i]) / (2 * h);
  }
  return A;
}

void FindEquilibrium(const Diagram& diagram, Context* ctx, std::vector<double>* x, double tolerance,
                     int max_iterations) {
  std::vector<double> f;
  const int n = diagram.num_states();
  double residual = 0.0;
  for (int it = 0; it <= max_iterations; ++it) {
    StateDerivative(diagram, ctx, x, &f);
    residual = 0.0;
    for (int i = 0; i < n; ++i) residual = std::max(residual, std::abs(f[i]));
    if (residual <= tolerance) return;
    if (it == max_iterations) break;
    const Eigen::MatrixXd A = StateJacobian(diagram, ctx, *x);
    const Eigen::VectorXd step =
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(A).solve(Eigen::Map<Eigen::VectorXd>(f.data(), n));
    for (int i = 0; i < n; ++i) (*x)[i] -= step(i);
  }
  std::ostringstream out;
  out << "no static equilibrium found: largest |x'| is " << residual << " after " << max_iterations
      << " Newton steps (is the diagram free to drift, or driven?)";
  throw SimulationError(out.str());
}

std::vector<Mode> ModalAnalysis(const Eigen::MatrixXd& A, const std::vector<bool>& normalise_on) {
  std::vector<Mode> modes;
  if (A.rows() == 0) return modes;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(A);
  const auto values = solver.eigenvalues();
  const auto vectors = solver.eigenvectors();
  const double scale = std::max(1.0, A.cwiseAbs().maxCoeff());
  for (int k = 0; k < values.size(); ++k) {
    const std::complex<double> lambda = values(k);
    if (lambda.imag() < -1e-12 * scale) continue;  // keep one of each conjugate pair
    Mode m;
    m.eigenvalue = lambda;
    const double magnitude = std::abs(lambda);
    m.frequency_hz = std::abs(lambda.imag()) / (2 * M_PI);
    m.natural_frequency_hz = magnitude / (2 * M_PI);
    m.damping_ratio = magnitude > 0 ? -lambda.real() / magnitude : 0.0;
    if (std::abs(m.damping_ratio) < 1e-9) m.damping_ratio = 0.0;  // undamped, up to differencing noise
    // Shape: phase so that the largest component is real and 1.
    Eigen::VectorXcd v = vectors.col(k);
    Eigen::Index largest = 0;
    double best = -1.0;
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if ((normalise_on.empty() || normalise_on[i]) && std::abs(v(i)) > best) best = std::abs(v(i)), largest = i;
    if (std::abs(v(largest)) > 0) v /= v(largest);
    for (int i = 0; i < v.size(); ++i) m.shape.push_back(v(i).real());
    modes.push_back(std::move(m));
  }
  std::sort(modes.begin(), modes.end(),
            [](const Mode& a, const Mode& b) { return a.natural_frequency_hz < b.natural_frequency_hz; });
  return modes;
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

}  // namespace mechflow::blocks
