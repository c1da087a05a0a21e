#include "mech/constraint_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/QR>

#include "mech/errors.h"

namespace mechflow::mech {
namespace {

// Pivots below kNoise * (largest) are round-off: the direction is redundant.
constexpr double kNoise = 1e-13;
// Damping of the pivots relative to the largest (singular-value ratio 1e-5).
constexpr double kDamping = 1e-10;
// Position residuals below this are in Newton's quadratic regime.
constexpr double kQuadraticRegime = 1e-8;
// Pivots above kRank * (largest) count towards the numerical rank.
constexpr double kRank = 1e-8;

// Factors ws->G and solves G x = b (b in ws->rhs, x written there) with the
// damped pivots, damped by at least `min_damping` (pivot units); records the
// rank and the weakest counted pivot's row.
void DampedGramSolve(ConstraintWorkspace* ws, double min_damping = 0.0) {
  const int m = static_cast<int>(ws->G.rows());
  ws->G_ldlt.compute(ws->G);
  const auto d = ws->G_ldlt.vectorD();
  const double largest = m > 0 ? d.cwiseAbs().maxCoeff() : 0.0;
  const int generic = std::min(ws->generic_rank, m);
  ws->pivoted.noalias() = ws->G_ldlt.transpositionsP() * ws->rhs;
  ws->G_ldlt.matrixL().solveInPlace(ws->pivoted);
  const double mu = std::max(kDamping * largest, min_damping);
  ws->rank = 0;
  for (int i = 0; i < m; ++i) {
    const double di = d(i);
    if (!(std::abs(di) > kNoise * largest)) {
      ws->pivoted(i) = 0.0;
      continue;
    }
    ws->pivoted(i) *= di / (di * di + mu * mu);
    if (std::abs(di) > kRank * largest) ++ws->rank;
  }
  // the pivots come largest first (symmetric pivoting): within the generic
  // rank, the last one is the weakest
  const int weakest = generic - 1;
  ws->G_ldlt.matrixU().solveInPlace(ws->pivoted);
  ws->rhs.noalias() = ws->G_ldlt.transpositionsP().transpose() * ws->pivoted;
  ws->weakest_row = -1;
  if (weakest >= 0) {
    // pivot i is row order[i]: the transpositions applied to 0 .. m-1
    const auto& P = ws->G_ldlt.transpositionsP();
    for (int i = 0; i < m; ++i) ws->order[i] = i;
    for (int k = 0; k < m; ++k) std::swap(ws->order[k], ws->order[P.coeff(k)]);
    ws->weakest_row = ws->rows[ws->order[weakest]];
  }
}

// Copies the rows of J that are not exactly zero into ws->Jc (a planar
// loop's out-of-plane rows are), and sizes the solves for them; they
// allocate only when that set of rows changes.
void CompactRows(ConstraintWorkspace* ws) {
  const int m = static_cast<int>(ws->J.rows()), n = static_cast<int>(ws->J.cols());
  // (with no freedom at all, as two welds of one body, every row is zero; and
  // a row view of a matrix of no columns is not to be taken)
  auto nonzero = [&](int i) { return n > 0 && (ws->J.row(i).array() != 0.0).any(); };
  int count = 0;
  bool same = true;
  for (int i = 0; i < m; ++i) {
    if (!nonzero(i)) continue;
    same = same && count < static_cast<int>(ws->rows.size()) && ws->rows[count] == i;
    ++count;
  }
  // Jc's width too: with no row left from the start the sizes would stay
  // those of an empty matrix
  if (!same || count != static_cast<int>(ws->rows.size()) || ws->Jc.cols() != n) {
    ws->rows.clear();
    for (int i = 0; i < m; ++i)
      if (nonzero(i)) ws->rows.push_back(i);
    ws->Jc.resize(count, n);
    ws->X.resize(n, count);
    ws->G.resize(count, count);
    ws->rhs.resize(count);
    ws->pivoted.resize(count);
    ws->order.assign(count, 0);
    // sized by a factorisation: a constructed LDLT leaves its status
    // uninitialised, and UBSan reports the copy
    ws->G_ldlt.compute(Eigen::MatrixXd::Identity(count, count));
  }
  for (int k = 0; k < count; ++k) ws->Jc.row(k) = ws->J.row(ws->rows[k]);
}

// Least-norm dv with J dv = e (ws->J given), through G = J J^T, its pivots
// damped by at least `min_damping`.
void LeastNormStep(const Eigen::VectorXd& e, ConstraintWorkspace* ws, double min_damping = 0.0) {
  CompactRows(ws);
  if (ws->rows.empty()) {  // loops that move nothing: no step (and no products over empty matrices)
    ws->rank = 0;
    ws->weakest_row = -1;
    ws->weakest_pivot = 0.0;
    ws->step.setZero();
    return;
  }
  ws->G.setZero();
  ws->G.selfadjointView<Eigen::Lower>().rankUpdate(ws->Jc);  // the solve reads the lower half
  for (std::size_t k = 0; k < ws->rows.size(); ++k) ws->rhs(k) = e(ws->rows[k]);
  DampedGramSolve(ws, min_damping);
  const int weakest = std::min(ws->generic_rank, static_cast<int>(ws->rows.size())) - 1;
  ws->weakest_pivot = weakest >= 0 ? std::abs(ws->G_ldlt.vectorD()(weakest)) : 0.0;
  ws->step.noalias() = ws->Jc.transpose() * ws->rhs;
}

// q += dv, with quaternion blocks advanced by the rotation vector in body axes.
void AddVelocityStep(const Model& model, std::span<double> q, const Eigen::VectorXd& dv) {
  for (const Dof& dof : model.dofs()) q[dof.q_index] += dv(dof.v_index);
  for (const Segment& seg : model.segments()) {
    if (seg.motion != SegmentMotion::kFree) continue;
    const int iq = seg.q_index, iv = seg.v_index;
    Eigen::Quaterniond quat(q[iq + 3], q[iq + 4], q[iq + 5], q[iq + 6]);
    const Vec3 dtheta = dv.segment<3>(iv);
    const Vec3 dp = quat.normalized().toRotationMatrix() * dv.segment<3>(iv + 3);
    const double angle = dtheta.norm();
    if (angle > 0.0) quat = quat * Eigen::Quaterniond(Eigen::AngleAxisd(angle, dtheta / angle));
    quat.normalize();
    for (int c = 0; c < 3; ++c) q[iq + c] += dp(c);
    q[iq + 3] = quat.w();
    q[iq + 4] = quat.x();
    q[iq + 5] = quat.y();
    q[iq + 6] = quat.z();
  }
}

// The damping (pivot units, sigma^2) below which a projection's change is
// round-off that the tolerance cannot absorb. The position residual is known
// to about one ulp of the largest coordinate, eps L; along a direction of
// singular value sigma that moves q by eps L / sigma, which turns the
// velocity constraint's rows (|dJ/dq| ~ |J|) and so moves v by
// eps L |J| |v| / sigma^2. Pivots sigma^2 below eps L |J| |v| / tol_v are
// therefore damped: their directions are left to the dynamics (which keep
// J v' = -bias exactly) until the mechanism leaves the singular position.
double ToleranceDamping(const Model& model, const Kinematics& kin, std::span<const double> v,
                        double velocity_tolerance, const ConstraintWorkspace& ws) {
  if (!(velocity_tolerance > 0.0) || ws.J.size() == 0) return 0.0;
  double length = 1.0, speed = 0.0;
  for (const Pose& pose : kin.pose) length = std::max(length, pose.p.lpNorm<Eigen::Infinity>());
  for (int i = 0; i < model.nv(); ++i) speed = std::max(speed, std::abs(v[i]));
  const double slope = ws.J.cwiseAbs().maxCoeff();
  return std::numeric_limits<double>::epsilon() * length * slope * speed / velocity_tolerance;
}

}  // namespace

ConstraintWorkspace::ConstraintWorkspace(const Model& model, const Constraints& constraints) {
  const int m = constraints.size(), n = model.nv();
  if (m > 0) {  // dense, and needed only to solve with constraints
    M.setZero(n, n);
    // sized now (no allocation in the solves); computed rather than
    // constructed empty, which would leave their status uninitialised
    M_llt.compute(Eigen::MatrixXd::Identity(n, n));
  }
  J.setZero(m, n);
  phi.setZero(m);
  psi.setZero(m);
  bias.setZero(m);
  lambda.setZero(m);
  step.setZero(n);
  vfree.setZero(n);
  scratch.assign(model.segments().size(), Vec6::Zero());
  loads.assign(model.segments().size(), Vec6::Zero());
  h.assign(n, 0.0);
  zero.assign(n, 0.0);
}

void SolveConstrainedAccelerations(std::span<const double> f, std::span<double> vdot, ConstraintWorkspace* ws) {
  const int n = static_cast<int>(ws->M.rows());
  // The ghost segments of cut joints carry no mass, so M alone is singular;
  // the constraints fix those directions. With M~ = M + alpha J^T J (regular
  // when they do), M v' = f + J^T lambda, J v' = -bias is the same system as
  //   M~ v' = f + J^T lambda~,  lambda = lambda~ + alpha bias,
  // solved by its Schur complement: (J M~^-1 J^T) lambda~ = -(J M~^-1 f + bias).
  // With M~ = L L^T and X = L^-1 J^T: G = X^T X, J M~^-1 f = X^T y with
  // y = L^-1 f, and v' = L^-T (y + X lambda~). Lower halves only.
  CompactRows(ws);
  const double jj = ws->rows.empty() ? 0.0 : ws->Jc.colwise().squaredNorm().maxCoeff();
  const double alpha = jj > 0.0 ? ws->M.diagonal().maxCoeff() / jj : 0.0;
  if (alpha > 0.0) ws->M.selfadjointView<Eigen::Lower>().rankUpdate(ws->Jc.transpose(), alpha);
  ws->M_llt.compute(ws->M);
  if (ws->M_llt.info() != Eigen::Success)
    throw SimulationError("the mass matrix is singular in a direction the loop constraints leave free");
  const auto L = ws->M_llt.matrixL();
  for (int i = 0; i < n; ++i) ws->vfree(i) = f[i];
  L.solveInPlace(ws->vfree);  // y
  // (loops that move nothing leave no row: no products over empty matrices)
  if (!ws->rows.empty()) {
    ws->X = ws->Jc.transpose();
    L.solveInPlace(ws->X);
    ws->G.setZero();
    ws->G.selfadjointView<Eigen::Lower>().rankUpdate(ws->X.transpose());
    ws->rhs.noalias() = ws->X.transpose() * ws->vfree;
    for (std::size_t k = 0; k < ws->rows.size(); ++k) ws->rhs(k) = -ws->rhs(k) - ws->bias(ws->rows[k]);
    DampedGramSolve(ws);
    ws->vfree.noalias() += ws->X * ws->rhs;
  } else {
    ws->rank = 0;
    ws->weakest_row = -1;
  }
  ws->M_llt.matrixU().solveInPlace(ws->vfree);
  ws->lambda = alpha * ws->bias;
  for (std::size_t k = 0; k < ws->rows.size(); ++k) ws->lambda(ws->rows[k]) += ws->rhs(k);
  for (int i = 0; i < n; ++i) vdot[i] = ws->vfree(i);
  if (!ws->vfree.allFinite()) throw SimulationError("the constrained accelerations are not finite");
}

double ProjectPositions(const Model& model, const Constraints& constraints, double t, std::span<double> q,
                        std::span<const double> v, double tolerance, int max_iterations, Kinematics* kin,
                        ConstraintWorkspace* ws, double velocity_tolerance) {
  double norm = 0.0, previous = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it) {
    UpdateKinematics(model, t, q, v, kin);
    constraints.Residual(model, *kin, &ws->phi);
    norm = ws->phi.size() ? ws->phi.lpNorm<Eigen::Infinity>() : 0.0;
    // stop at the tolerance, or where round-off stops the progress: from a
    // residual that small Newton converges quadratically, so a step that
    // gains less than a factor 4 only stirs the round-off
    const bool stalled = previous < kQuadraticRegime && norm > 0.25 * previous;
    if (norm <= tolerance || it >= max_iterations || !std::isfinite(norm) || stalled) break;
    previous = norm;
    constraints.Jacobian(model, *kin, &ws->J);
    LeastNormStep(ws->phi, ws, ToleranceDamping(model, *kin, v, velocity_tolerance, *ws));
    ws->step = -ws->step;
    AddVelocityStep(model, q, ws->step);
  }
  return norm;
}

namespace {

std::vector<int> GhostColumns(const Model& model) {
  std::vector<int> columns;
  for (const Segment& seg : model.segments())
    if (seg.ghost && seg.drive == SegmentDrive::kDof) columns.push_back(seg.v_index);
  return columns;
}

// Least-squares change of the ghost columns that removes `residual` (J given).
Eigen::VectorXd GhostStep(const Eigen::MatrixXd& J, const std::vector<int>& columns, const Eigen::VectorXd& residual) {
  Eigen::MatrixXd Jg(J.rows(), columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c) Jg.col(c) = J.col(columns[c]);
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(Jg).solve(residual);
}

}  // namespace

double AssembleCutCoordinates(const Model& model, const Constraints& constraints, std::span<double> q,
                              std::span<const double> v, Kinematics* kin, ConstraintWorkspace* ws) {
  const std::vector<int> ghost_columns = GhostColumns(model);
  double norm = 0.0;
  for (int it = 0;; ++it) {
    UpdateKinematics(model, 0.0, q, v, kin);
    constraints.Residual(model, *kin, &ws->phi);
    norm = ws->phi.size() ? ws->phi.lpNorm<Eigen::Infinity>() : 0.0;
    if (norm <= 1e-12 || it >= 30 || ghost_columns.empty() || !std::isfinite(norm)) break;
    constraints.Jacobian(model, *kin, &ws->J);
    const Eigen::VectorXd step = GhostStep(ws->J, ghost_columns, ws->phi);
    for (std::size_t c = 0; c < ghost_columns.size(); ++c) {
      for (const Dof& dof : model.dofs())
        if (dof.v_index == ghost_columns[c]) q[dof.q_index] -= step(c);
    }
  }
  return norm;
}

void AssembleCutVelocities(const Model& model, const Constraints& constraints, std::span<const double> q,
                           std::span<double> v, Kinematics* kin, ConstraintWorkspace* ws) {
  const std::vector<int> ghost_columns = GhostColumns(model);
  if (ghost_columns.empty()) return;
  UpdateKinematics(model, 0.0, q, v, kin);
  constraints.VelocityResidual(model, *kin, &ws->psi);
  constraints.Jacobian(model, *kin, &ws->J);
  const Eigen::VectorXd step = GhostStep(ws->J, ghost_columns, ws->psi);
  for (std::size_t c = 0; c < ghost_columns.size(); ++c) v[ghost_columns[c]] -= step(c);
}

void ProjectVelocities(const Model& model, const Constraints& constraints, double t, std::span<const double> q,
                       std::span<double> v, Kinematics* kin, ConstraintWorkspace* ws, double velocity_tolerance) {
  UpdateKinematics(model, t, q, v, kin);
  constraints.VelocityResidual(model, *kin, &ws->psi);
  constraints.Jacobian(model, *kin, &ws->J);
  LeastNormStep(ws->psi, ws, ToleranceDamping(model, *kin, v, velocity_tolerance, *ws));
  for (int i = 0; i < model.nv(); ++i) v[i] -= ws->step(i);
}

void RecordGenericRank(const Model& model, const Constraints& constraints, const Kinematics& kin,
                       ConstraintWorkspace* ws) {
  constraints.Jacobian(model, kin, &ws->J);
  ws->generic_rank = -1;
  LeastNormStep(ws->phi, ws);
  ws->generic_rank = ws->rank;
  ws->reference_pivot = ws->generic_rank > 0 ? std::abs(ws->G_ldlt.vectorD()(ws->generic_rank - 1)) : 0.0;
}

std::string SingularPositionNote(const Model& model, const Constraints& constraints,
                                 const ConstraintWorkspace& ws) {
  if (ws.generic_rank <= 0 || ws.weakest_row < 0) return {};
  const bool lost_rank = ws.rank < ws.generic_rank;
  // sigma ratio: the pivots are squares of singular values
  const double weakness = std::sqrt(ws.weakest_pivot / ws.reference_pivot);
  if (!lost_rank && !(weakness < 0.2)) return {};
  std::string joint;
  for (int k = 0; k < static_cast<int>(constraints.cut_joints().size()); ++k)
    if (ws.weakest_row >= constraints.row(k) && ws.weakest_row < constraints.row(k) + constraints.rows(k))
      joint = model.joints()[constraints.cut_joints()[k]].name;
  std::ostringstream out;
  out.precision(2);
  out << (lost_rank ? "the loops are at a singular position" : "the loops are close to a singular position")
      << ": the constraint of joint '" << joint << "' became " << (lost_rank ? "" : "nearly ")
      << "dependent on the others (rank " << ws.rank << " of " << ws.generic_rank << ", weakest direction "
      << weakness << " of its strength at the start; links aligned, a dead centre, where the mechanism has "
         "momentarily more degrees of freedom)";
  return out.str();
}

}  // namespace mechflow::mech
