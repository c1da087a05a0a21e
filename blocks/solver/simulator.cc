#include "blocks/solver/simulator.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>

#include <cvode/cvode_ls.h>
#include <cvode/cvode_proj.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "blocks/solver/analytic_jacobian.h"
#include "blocks/solver/coloured_jacobian.h"
#include "blocks/solver/crossing_search.h"
#include "blocks/framework/evaluation.h"
#include "blocks/solver/flush_denormals.h"
#include "blocks/solver/second_order_solver.h"
#include "blocks/solver/sparsity.h"
#include "blocks/solver/sundials.h"
#include "mech/errors.h"

namespace mechflow::blocks {

using sundials::Check;

std::string SolverOptions::Problem() const {
  if (!std::isfinite(t_start)) return "t_start must be a finite number";
  if (!(t_end > t_start) || !std::isfinite(t_end))
    return "t_end must be a finite number greater than t_start (" + std::to_string(t_start) + ")";
  if (!(rtol >= 1e-15) || !(rtol < 1.0))
    return "rtol must be at least 1e-15 (double precision cannot follow a tighter one) and < 1";
  if (!(atol > 0.0) || !std::isfinite(atol)) return "atol must be a finite number > 0";
  if (!(max_step >= 0.0) || !std::isfinite(max_step)) return "max_step must be >= 0 (0 means no limit)";
  if (!(initial_step >= 0.0) || !std::isfinite(initial_step))
    return "initial_step must be >= 0 (0 means automatic)";
  if (max_steps < 1) return "max_steps must be >= 1";
  if (!(output_interval >= 0.0) || !std::isfinite(output_interval)) return "output interval must be >= 0";
  return "";
}

// The SUNDIALS objects of one run; y is the solver's state vector. One of
// sparse, second-order (dense, with rate pairs) and dense is made.
struct Simulator::Solver {
  Solver(sunindextype n, const ColouredJacobian* jacobian, const std::vector<std::pair<int, int>>& rate_pairs,
         bool krylov_solver)
      : n(n), y(n, ctx), weights(n, ctx), watch(n, ctx), check(n, ctx), search(n, ctx), cvode(ctx) {
    for (int k = 0; k <= kMaxOrder; ++k) taylor.push_back(std::make_unique<sundials::Vector>(n, ctx));
    if (krylov_solver) {
      krylov = std::make_unique<sundials::KrylovSolver>(y, kKrylovDimension, ctx);
    } else if (jacobian) {
      sparse = std::make_unique<sundials::SparseSolver>(y, jacobian->pattern(), ctx);
    } else if (!rate_pairs.empty()) {
      second_order = std::make_unique<SecondOrderSolver>(y, rate_pairs, [this] {
        double gamma = 0.0;  // called by CVODE: no exception may pass
        return CVodeGetCurrentGamma(cvode.get(), &gamma) < 0 ? std::nan("") : gamma;
      }, ctx);
    } else {
      dense = std::make_unique<sundials::DenseSolver>(y, ctx);
    }
  }
  SUNMatrix matrix() const {
    return krylov ? nullptr : sparse ? sparse->matrix() : second_order ? second_order->matrix() : dense->matrix();
  }
  SUNLinearSolver linear_solver() const {
    return krylov         ? krylov->solver()
           : sparse       ? sparse->solver()
           : second_order ? second_order->solver()
                          : dense->solver();
  }
  // GMRES iterations per linear solve, without restarts (CVODE's default):
  // CVODE takes a solve that has not converged by then as a failure and
  // retries with a smaller step
  static constexpr int kKrylovDimension = 5;
  static constexpr int kMaxOrder = 5;  // BDF's
  const sunindextype n;  // states
  sundials::Context ctx;
  sundials::Vector y;
  sundials::Vector weights;  // sparse: CVODE's error weights, for the increments
  // Interpolated states: on a step the reports watch, at a check inside a
  // step, at a probe or trial of the crossing search; and the Taylor
  // coefficients of a step with several rows (Simulator::InterpolateInStep)
  sundials::Vector watch, check, search;
  std::vector<std::unique_ptr<sundials::Vector>> taylor;
  std::unique_ptr<sundials::DenseSolver> dense;
  std::unique_ptr<sundials::SparseSolver> sparse;
  std::unique_ptr<SecondOrderSolver> second_order;
  std::unique_ptr<sundials::KrylovSolver> krylov;
  sundials::Cvode cvode;  // last: freed first, before the solvers it uses
};

namespace {

// Right-hand-side failures (exceptions) tolerated in one run before it stops.
constexpr int kMaxCallbackFailures = 30;

// A value that is not finite as a user reads it ("nan", not "-nan").
std::string NotFiniteText(double v) { return std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"; }

// v * 0 is 0 for a finite v and NaN otherwise; four sums in turn, which the
// compiler vectorises (a test per element cost 2 % of P1's instructions).
bool AllFinite(const std::vector<double>& values) {
  const double* v = values.data();
  const std::size_t n = values.size(), whole = n - n % 4;
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  for (std::size_t i = 0; i < whole; i += 4) {
    s0 += v[i] * 0.0;
    s1 += v[i + 1] * 0.0;
    s2 += v[i + 2] * 0.0;
    s3 += v[i + 3] * 0.0;
  }
  for (std::size_t i = whole; i < n; ++i) s0 += v[i] * 0.0;
  return s0 + s1 + s2 + s3 == 0.0;
}

// An output (or sample) time t0 + k * interval as the decimal it stands for: the
// product rounds (47 * 0.01 = 0.47000000000000003), and a row taken there
// would read so in the results. The double nearest the time's 15 significant
// digits, when it is within a few units in the last place of it (rounding,
// not a grid of its own such as k / 3), so the row is taken at 0.47 and the
// results, in the shortest form that reads back, show 0.47.
double DecimalGridTime(double t) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, t, std::chars_format::general, 15).ptr;
  double decimal = t;
  std::from_chars(text, end, decimal);
  const double ulp = std::nextafter(std::abs(t), std::numeric_limits<double>::infinity()) - std::abs(t);
  return std::abs(decimal - t) <= 4.0 * ulp ? decimal : t;
}

// The most nonzeros in one row of the pattern.
int FullestRow(const SparsityPattern& pattern) {
  std::vector<int> count(pattern.n, 0);
  for (const int row : pattern.rows) ++count[row];
  return count.empty() ? 0 : *std::max_element(count.begin(), count.end());
}

std::vector<std::string> ColumnNames(const std::vector<SignalRef>& logged) {
  std::vector<std::string> names;
  for (const auto& s : logged) {
    if (s.width == 1) {
      names.push_back(s.name);
    } else {
      for (int i = 0; i < s.width; ++i) names.push_back(s.name + "[" + std::to_string(i) + "]");
    }
  }
  return names;
}

}  // namespace

Simulator::Simulator(const Diagram& diagram, SolverOptions options, std::vector<SignalRef> logged)
    : diagram_(diagram),
      options_(options),
      logged_(std::move(logged)),
      results_(ColumnNames(logged_)) {
  const std::string problem = options_.Problem();
  if (!problem.empty()) throw InputError("solver settings: " + problem);
  if (options_.output_interval == 0.0) options_.output_interval = (options_.t_end - options_.t_start) / 1000.0;
  for (const int b : diagram_.periodic_blocks()) {
    const std::string period = SamplePeriodProblem(diagram_.block(b).sample_time().period, options_.t_start,
                                                   options_.t_end);
    if (!period.empty())
      throw InputError(diagram_.origin(b) + ": block '" + diagram_.block(b).name() + "': sample period: " + period);
  }
  ctx_.signals.assign(diagram_.num_signals(), 0.0);
  ctx_.discrete.assign(diagram_.num_discrete_states(), 0.0);
  row_.resize(results_.num_columns());
  for (const SignalRef& s : logged_)
    for (int i = 0; i < s.width; ++i) {
      row_signals_.push_back(s.offset + i);
      row_factors_.push_back(s.column_factor);
    }
  frozen_y_.assign(diagram_.num_states(), 0.0);
  frozen_slope_.assign(diagram_.num_states(), 0.0);
  frozen_before_.assign(diagram_.num_states(), 0.0);
  for (const int b : diagram_.crossing_blocks())
    for (int i = 0; i < diagram_.layout(b).num_crossings; ++i) crossing_owner_.push_back(b);
  roots_found_.assign(diagram_.num_zero_crossings(), 0);
  last_fired_.assign(diagram_.num_zero_crossings(), 0.0);
  fired_in_a_row_.assign(diagram_.num_zero_crossings(), 0);
  next_hit_.assign(diagram_.periodic_blocks().size(), 0);
  std::vector<int> directions;
  for (const int b : diagram_.crossing_blocks())
    for (int i = 0; i < diagram_.block(b).num_zero_crossings(); ++i) {
      const CrossingDirection dir = diagram_.block(b).crossing_direction(i);
      directions.push_back(dir == CrossingDirection::kRising ? 1 : dir == CrossingDirection::kFalling ? -1 : 0);
    }
  crossings_ = std::make_unique<CrossingSearch>(std::move(directions));
  crossing_values_.assign(diagram_.num_zero_crossings(), 0.0);
  // the Jacobian's structure is the diagram's: found and coloured once
  const int n = std::max(1, diagram_.num_states());
  const LinearSolverKind kind = options_.linear_solver;
  if (kind == LinearSolverKind::kSparse || (kind == LinearSolverKind::kAuto && n >= kSparseMinStates)) {
    SparsityPattern pattern = DiagramSparsity(diagram_);
    // Columns that share a row take different colours, so the fullest row
    // bounds the colours from below: a pattern that cannot qualify is not
    // coloured (a serial chain of 1000 bodies spent 2.8 s colouring its
    // dense pattern, of 2000 bodies 26 s)
    if (kind == LinearSolverKind::kSparse || 4 * FullestRow(pattern) <= n) {
      auto jacobian = std::make_unique<ColouredJacobian>(std::move(pattern));
      if (kind == LinearSolverKind::kSparse || 4 * jacobian->num_colours() <= n) {
        jacobian_ = std::move(jacobian);
        increments_.assign(n, 0.0);
      }
    }
  }
  if (!jacobian_) rate_pairs_ = DiagramRatePairs(diagram_);
  // large mechanisms whose Jacobian is dense: matrix-free (see the header)
  // (not for closed loops: on the slider-crank its inexact solves cost
  // accuracy, 5e-6 against 3e-7 at rtol 1e-8, tests/blocks/solver/second_order_solver_test.cc)
  bool projects = false;
  for (int b = 0; b < diagram_.num_blocks(); ++b) projects = projects || diagram_.block(b).has_projection();
  krylov_ = kind == LinearSolverKind::kKrylov ||
            (kind == LinearSolverKind::kAuto && !jacobian_ && !projects && n >= kKrylovMinStates &&
             4 * static_cast<int>(rate_pairs_.size()) >= n);
  if (!krylov_ && !options_.second_order) rate_pairs_.clear();
  if (options_.jacobian != JacobianKind::kDifferenceQuotient) {
    std::string why = "the krylov linear solver uses no Jacobian";
    const int block = krylov_ ? -1 : AnalyticJacobian::FindBlock(diagram_, &why);
    if (block >= 0) analytic_ = std::make_unique<AnalyticJacobian>(diagram_, block);
    else if (options_.jacobian == JacobianKind::kAnalytic)
      throw InputError(AnalyticJacobian::Refusal(why));
  }
  if (analytic_ && jacobian_) analytic_values_.assign(jacobian_->pattern().nonzeros(), 0.0);
}

Simulator::~Simulator() = default;

void Simulator::SetReports(std::vector<ReportRequest> reports) {
  for (const ReportRequest& r : reports)
    if (r.index < 0 || r.index >= r.signal.width)
      throw InputError("report '" + r.label + "': signal '" + r.signal.name + "' has width " +
                       std::to_string(r.signal.width) + "; element " + std::to_string(r.index) + " does not exist");
  reports_ = std::move(reports);
  trackers_.assign(reports_.size(), ExtremumTracker());
  accumulators_.clear();
  for (const ReportRequest& r : reports_) accumulators_.emplace_back(r.level);
}

std::vector<ReportFigure> Simulator::figures() const {
  std::vector<ReportFigure> out;
  for (std::size_t i = 0; i < reports_.size(); ++i) {
    const ReportRequest& r = reports_[i];
    ReportFigure f{r.label, r.unit, r.signal.name, r.kind, trackers_[i].found()};
    const SignalAccumulator& a = accumulators_[i];
    if (IsExtremum(r.kind) && f.found) {
      // the tracker maximised -f for a minimum
      f.value = r.kind == ReportKind::kMin ? -trackers_[i].value() : trackers_[i].value();
      f.time = trackers_[i].time();
    } else if (!IsExtremum(r.kind)) {
      f.found = r.kind == ReportKind::kCrossing ? a.crossed()
                : r.kind == ReportKind::kPeriod ? a.has_period()
                                                : a.started();
      if (f.found) {
        switch (r.kind) {
          case ReportKind::kMean: f.value = a.mean(), f.time = a.end(); break;
          case ReportKind::kRms: f.value = a.rms(), f.time = a.end(); break;
          case ReportKind::kIntegral: f.value = a.integral(), f.time = a.end(); break;
          case ReportKind::kFinal: f.value = a.final_value(), f.time = a.end(); break;
          case ReportKind::kCrossing: f.value = f.time = a.first_crossing(); break;
          case ReportKind::kPeriod: f.value = a.period(), f.time = a.last_upward(); break;
          default: break;
        }
      }
    }
    f.value *= r.signal.column_factor;  // in the report's unit (SignalRef::column_factor)
    out.push_back(std::move(f));
  }
  return out;
}

void Simulator::WatchStep(double ta, double tb) {
  void* mem = solver_->cvode.get();
  for (std::size_t i = 0; i < reports_.size(); ++i) {
    const ReportRequest& r = reports_[i];
    const int offset = r.signal.offset + r.index;
    const auto value = [&](double t) {
      Check(CVodeGetDky(mem, t, 0, solver_->watch.get()), "CVodeGetDky");
      EvaluateAt(t, solver_->watch.data());
      return ctx_.signals[offset];
    };
    if (!IsExtremum(r.kind)) {
      accumulators_[i].WatchStep(ta, tb, value);
      continue;
    }
    const double sign = r.kind == ReportKind::kMin ? -1.0 : 1.0;
    const bool magnitude = r.kind == ReportKind::kPeakAbs;
    trackers_[i].WatchStep(ta, tb, [&](double t) {
      const double v = value(t);
      return magnitude ? std::abs(v) : sign * v;
    });
  }
}

void Simulator::WatchTo(double t) {
  if (reports_.empty() || !(t > watched_to_)) return;
  WatchStep(watched_to_, t);
  watched_to_ = t;
}

void Simulator::InterpolateInStep(double t, double* out) {
  const auto n = static_cast<std::size_t>(solver_->n);
  const auto& taylor = solver_->taylor;
  if (taylor_order_ < 0) {
    // the step's polynomial about its end tn: y(t) = sum_k y^(k)(tn) (t - tn)^k / k!
    void* mem = solver_->cvode.get();
    Check(CVodeGetLastOrder(mem, &taylor_order_), "CVodeGetLastOrder");
    Check(CVodeGetCurrentTime(mem, &taylor_tn_), "CVodeGetCurrentTime");
    double factorial = 1.0;
    for (int k = 0; k <= taylor_order_; ++k) {
      Check(CVodeGetDky(mem, taylor_tn_, k, taylor[k]->get()), "CVodeGetDky");
      factorial *= std::max(k, 1);
      double* a = taylor[k]->data();
      for (std::size_t i = 0; k > 1 && i < n; ++i) a[i] /= factorial;
    }
  }
  const double dt = t - taylor_tn_;
  const double* a = taylor[taylor_order_]->data();
  std::copy(a, a + n, out);
  for (int k = taylor_order_ - 1; k >= 0; --k) {
    a = taylor[k]->data();
    for (std::size_t i = 0; i < n; ++i) out[i] = out[i] * dt + a[i];
  }
}

void Simulator::EvaluateAt(double t, double* x, bool dynamics_only) {
  ctx_.time = t;
  ctx_.x = x;
  ++ctx_.evaluation;
  EvaluateOutputs(diagram_, dynamics_only ? diagram_.dynamics_schedule() : diagram_.schedule(), &ctx_);
}

void Simulator::EvaluateCrossingsAt(double t, double* x, bool row) {
  EvaluateAt(t, x, !row);
  ctx_.crossings = crossing_values_.data();
  EvaluateZeroCrossings(diagram_, &ctx_);
  ++stats_.root_evals;
}

void Simulator::StartCrossings(double t, double* x) {
  if (crossings_->size() == 0) return;
  EvaluateCrossingsAt(t, x, false);
  crossings_->Start(t, crossing_values_);
  probe_pending_ = crossings_->AnyInactive();
}

bool Simulator::CheckCrossings(double t, double* x, bool row, double* t_root, double* x_root) {
  void* mem = solver_->cvode.get();
  // the probe and the search interpolate into their own buffer: x stays
  N_Vector search = solver_->search.get();
  double* trial = solver_->search.data();
  if (probe_pending_) {
    // CVODE's look just after the start, for functions exactly zero there:
    // a tenth of the first step on (inside it, on its interpolant)
    probe_pending_ = false;
    const double t_probe = crossings_->lower_time() + 0.1 * (t - crossings_->lower_time());
    Check(CVodeGetDky(mem, t_probe, 0, search), "CVodeGetDky");
    EvaluateCrossingsAt(t_probe, trial, false);
    crossings_->Probe(crossing_values_);
  }
  EvaluateCrossingsAt(t, x, row);
  if (!crossings_->Crosses(crossing_values_)) {
    crossings_->Accept(t, crossing_values_);
    return false;
  }
  double tn = t, h = 0.0;
  CVodeGetCurrentTime(mem, &tn);
  CVodeGetLastStep(mem, &h);
  // CVODE's tolerance on the crossing time: a hundred units of round-off
  const double ttol = 100.0 * std::numeric_limits<double>::epsilon() * (std::abs(tn) + std::abs(h));
  *t_root = crossings_->Locate(t, crossing_values_, ttol, [&](double tm, std::span<double> g) {
    Check(CVodeGetDky(mem, tm, 0, search), "CVodeGetDky");
    EvaluateCrossingsAt(tm, trial, false);
    std::copy(crossing_values_.begin(), crossing_values_.end(), g.begin());
  });
  std::copy(crossings_->directions_found().begin(), crossings_->directions_found().end(), roots_found_.begin());
  const auto n = static_cast<std::size_t>(solver_->n);
  if (*t_root == t) {
    std::copy(x, x + n, x_root);
  } else {
    Check(CVodeGetDky(mem, *t_root, 0, search), "CVodeGetDky");
    std::copy(trial, trial + n, x_root);
  }
  return true;
}

void Simulator::Record(double t, double* x, bool evaluated) {
  if (!evaluated) EvaluateAt(t, x);
  if (!AllFinite(ctx_.signals)) [[unlikely]]
    RefuseNonFiniteOutputs(t);
  row_[0] = t;
  const double* signals = ctx_.signals.data();
  // times 1 is exact: columns in SI keep the signal's bits
  for (std::size_t c = 0; c < row_signals_.size(); ++c) row_[c + 1] = signals[row_signals_[c]] * row_factors_[c];
  results_.AddRow(row_.data());
  if (observer_) observer_->OnRow(t, x, ctx_);
}

void Simulator::RefuseNonFiniteOutputs(double t) const {
  const std::vector<double>& signals = ctx_.signals;
  // the first in evaluation order: the cause, not what it fed
  int bad = -1;
  for (const OutputNode& node : diagram_.schedule()) {
    if (node.loop >= 0) continue;
    const BlockLayout& layout = diagram_.layout(node.block);
    const int first = layout.output_offset[node.port];
    for (int i = first; bad < 0 && i < first + layout.output_width[node.port]; ++i)
      if (!std::isfinite(signals[i])) bad = i;
    if (bad >= 0) break;
  }
  for (std::size_t i = 0; bad < 0 && i < signals.size(); ++i)  // in a loop's unknowns
    if (!std::isfinite(signals[i])) bad = static_cast<int>(i);
  if (bad < 0) throw std::logic_error("RefuseNonFiniteOutputs: every signal is finite");
  std::ostringstream out;
  out << DescribeSignal(bad) << " is not finite (" << NotFiniteText(signals[bad]) << ") at t = " << t
      << "; the rows before are kept (a value out of the range of double precision, or undefined: check what the "
         "block computes from its inputs and parameters there)";
  throw SimulationError(out.str());
}

std::string Simulator::DescribeSignal(int signal) const {
  for (int b = 0; b < diagram_.num_blocks(); ++b) {
    const BlockLayout& layout = diagram_.layout(b);
    for (int p = 0; p < static_cast<int>(layout.output_offset.size()); ++p) {
      const int first = layout.output_offset[p], width = layout.output_width[p];
      if (signal < first || signal >= first + width) continue;
      const std::string& origin = diagram_.origin(b);
      std::string port = diagram_.block(b).output_port(p).name;
      if (width > 1) port += "[" + std::to_string(signal - first) + "]";
      return "block '" + diagram_.block(b).name() + "'" + (origin.empty() ? "" : " (" + origin + ")") + " output '" +
             port + "'";
    }
  }
  return "signal " + std::to_string(signal);
}

void Simulator::RefuseFrozenState() {
  if (frozen_y_.empty()) return;  // no states, nothing can freeze
  void* mem = solver_->cvode.get();
  double tn = 0.0;
  N_Vector yn = nullptr;
  Check(CVodeGetCurrentTime(mem, &tn), "CVodeGetCurrentTime");
  Check(CVodeGetCurrentState(mem, &yn), "CVodeGetCurrentState");
  const double* y = N_VGetArrayPointer(yn);
  const std::size_t n = frozen_y_.size();
  const bool advanced = frozen_valid_ && tn > frozen_tn_;
  const double tn_before = frozen_tn_;
  std::copy(frozen_y_.begin(), frozen_y_.end(), frozen_before_.begin());
  frozen_valid_ = true;
  frozen_tn_ = tn;
  std::copy(y, y + n, frozen_y_.begin());
  if (!advanced || !std::equal(y, y + n, frozen_before_.begin())) return;
  // the solver's own derivative there
  N_Vector slope = sundials::WrapArray(static_cast<sunindextype>(n), frozen_slope_.data(), solver_->ctx);
  const int flag = CVodeGetDky(mem, tn, 1, slope);
  N_VDestroy(slope);
  Check(flag, "CVodeGetDky");
  const int i = FrozenState(frozen_before_, frozen_y_, frozen_slope_, tn - tn_before, options_.rtol, options_.atol);
  if (i < 0) return;
  std::ostringstream out;
  out << "the integrator's state stopped changing from t = " << tn_before << " to " << tn
      << " s while its derivative is not zero (state " << i << ": x' = " << frozen_slope_[i]
      << "): refusing to write rows of frozen motion";
  throw SimulationError(out.str());
}

int FrozenState(std::span<const double> before, std::span<const double> after, std::span<const double> slope,
                double dt, double rtol, double atol) {
  if (!std::equal(before.begin(), before.end(), after.begin(), after.end())) return -1;
  for (std::size_t i = 0; i < after.size(); ++i)
    if (std::abs(slope[i]) * dt > 1e-3 * (rtol * std::abs(after[i]) + atol)) return static_cast<int>(i);
  return -1;
}

int Simulator::Rhs(double t, N_Vector y, N_Vector ydot, void* user) {
  return static_cast<Simulator*>(user)->EvaluateRhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
}

int Simulator::EvaluateRhs(double t, double* x, double* xdot) {
  const Diagram& d = diagram_;
  try {
    Context& ctx = ctx_;
    ctx.time = t;
    ctx.x = x;
    ctx.xdot = xdot;
    ++ctx.evaluation;
    ctx.derivatives_follow = true;
    EvaluateOutputs(d, d.dynamics_schedule(), &ctx);
    EvaluateDerivatives(d, &ctx);
    ctx.derivatives_follow = false;
    if (analytic_) {  // where an analytic Jacobian may follow without evaluating again
      rhs_t_ = t;
      std::copy(x, x + rhs_x_.size(), rhs_x_.begin());
      rhs_at_ = ctx.evaluation;
    }
  } catch (const std::exception& e) {
    // recoverable at first: CVODE retries with smaller steps, so a failing
    // run stops close to the failing instant; then final, so that a model
    // that cannot go on does not creep towards it with ever smaller steps
    callback_failure_ = e.what();
    callback_no_solution_ = dynamic_cast<const NoSolutionError*>(&e) != nullptr;
    return ++callback_failures_ > kMaxCallbackFailures ? -1 : 1;
  }
  if (d.num_states() == 0) xdot[0] = 0.0;  // the placeholder state of a stateless diagram
  for (int i = 0; i < d.num_states(); ++i) {
    if (!std::isfinite(xdot[i])) {
      // recoverable: CVODE retries with a smaller step, and fails if it persists
      callback_failure_ = "the derivative of " + DescribeState(i) + " is not finite (" + NotFiniteText(xdot[i]) +
                          ") at t = " + std::to_string(t);
      return 1;
    }
  }
  return 0;
}

std::string Simulator::DescribeState(int state) const {
  for (const int b : diagram_.stateful_blocks()) {
    const BlockLayout& layout = diagram_.layout(b);
    if (state < layout.first_state || state >= layout.first_state + layout.num_states) continue;
    const std::string& origin = diagram_.origin(b);
    return "block '" + diagram_.block(b).name() + "'" + (origin.empty() ? "" : " (" + origin + ")") + " state '" +
           diagram_.block(b).state_name(state - layout.first_state) + "'";
  }
  return "continuous state " + std::to_string(state);
}

int Simulator::EvaluateAnalyticJacobian(double t, double* x) {
  try {
    const bool current = rhs_at_ != 0 && rhs_at_ == ctx_.evaluation && t == rhs_t_ &&
                         std::memcmp(x, rhs_x_.data(), rhs_x_.size() * sizeof(double)) == 0;
    if (!current) {
      EvaluateAt(t, x, /*dynamics_only=*/true);
      ++stats_.jac_rhs_evals;
    }
    ctx_.time = t;
    ctx_.x = x;
    analytic_->Evaluate(&ctx_);
  } catch (const std::logic_error& e) {  // a block's Jacobian outside its own pattern: a bug, never retried
    callback_failure_ = e.what();
    return -1;
  } catch (const std::exception& e) {  // as a right-hand side's failure
    callback_failure_ = e.what();
    return ++callback_failures_ > kMaxCallbackFailures ? -1 : 1;
  }
  return 0;
}

int Simulator::DenseJacobian(double t, N_Vector y, N_Vector, SUNMatrix j, void* user, N_Vector, N_Vector,
                             N_Vector) {
  auto* self = static_cast<Simulator*>(user);
  if (const int flag = self->EvaluateAnalyticJacobian(t, N_VGetArrayPointer(y)); flag != 0) return flag;
  self->analytic_->ToDense(static_cast<int>(SM_COLUMNS_D(j)), SM_DATA_D(j));
  return 0;
}

int Simulator::LinearSystem(double t, N_Vector y, N_Vector fy, SUNMatrix a, sunbooleantype jok,
                            sunbooleantype* jcur, double gamma, void* user, N_Vector, N_Vector, N_Vector) {
  auto* self = static_cast<Simulator*>(user);
  ColouredJacobian& jacobian = *self->jacobian_;
  const SparsityPattern& pattern = jacobian.pattern();
  if (!jok && self->analytic_) {
    if (const int flag = self->EvaluateAnalyticJacobian(t, N_VGetArrayPointer(y)); flag != 0) return flag;
    try {
      self->analytic_->ToPattern(pattern, self->analytic_values_.data());
    } catch (const std::logic_error& e) {
      self->callback_failure_ = e.what();
      return -1;
    }
    *jcur = SUNTRUE;
  } else if (!jok) {
    // a fresh J at (t, y), with the increments CVODE's dense quotient would take
    void* mem = self->solver_->cvode.get();
    double step = 0.0;
    CVodeGetCurrentStep(mem, &step);
    CVodeGetErrWeights(mem, self->solver_->weights.get());
    double* x = N_VGetArrayPointer(y);
    DifferenceIncrements(pattern.n, x, N_VGetArrayPointer(fy), self->solver_->weights.data(), step,
                         self->increments_.data());
    const int flag = jacobian.Fill(x, N_VGetArrayPointer(fy), self->increments_.data(),
                                   [&](double* xp, double* fp) { return self->EvaluateRhs(t, xp, fp); });
    self->ctx_.x = x;  // the callers' state again, for anything that reads the context next
    // CVODE counts the Jacobian evaluations; the right-hand sides are ours
    self->stats_.jac_rhs_evals += jacobian.num_colours();
    if (flag != 0) return flag;
    *jcur = SUNTRUE;
  } else {
    *jcur = SUNFALSE;
  }
  // A = I - gamma J on the fixed pattern (rewritten each time: a matrix
  // zeroed by anyone else would lose it)
  sunindextype* start = SUNSparseMatrix_IndexPointers(a);
  sunindextype* rows = SUNSparseMatrix_IndexValues(a);
  double* values = SUNSparseMatrix_Data(a);
  const std::vector<double>& j = self->analytic_ ? self->analytic_values_ : jacobian.values();
  for (int c = 0; c <= pattern.n; ++c) start[c] = pattern.column_start[c];
  for (int c = 0; c < pattern.n; ++c) {
    for (int k = pattern.column_start[c]; k < pattern.column_start[c + 1]; ++k) {
      rows[k] = pattern.rows[k];
      values[k] = (pattern.rows[k] == c ? 1.0 : 0.0) - gamma * j[k];
    }
  }
  return 0;
}

int Simulator::PreconditionRatePairs(double, N_Vector, N_Vector, N_Vector r, N_Vector z, double gamma, double,
                                     int, void* user) {
  // P = I - gamma [rows q' = v]: exact for the pairs, the identity elsewhere
  const auto* self = static_cast<Simulator*>(user);
  const double* in = N_VGetArrayPointer(r);
  double* out = N_VGetArrayPointer(z);
  const sunindextype n = N_VGetLength(r);
  for (sunindextype i = 0; i < n; ++i) out[i] = in[i];
  for (const auto& [position, rate] : self->rate_pairs_) out[position] = in[position] + gamma * in[rate];
  return 0;
}

int Simulator::Project(double t, N_Vector y, N_Vector correction, double, N_Vector error, void* user) {
  auto* self = static_cast<Simulator*>(user);
  const Diagram& d = self->diagram_;
  double* corr = N_VGetArrayPointer(correction);
  double* err = error ? N_VGetArrayPointer(error) : nullptr;
  for (int i = 0; i < d.num_states(); ++i) corr[i] = 0.0;
  // the weights of the step being completed (CVODE sets them at its start)
  void* mem = self->solver_->cvode.get();
  const double* weights = CVodeGetErrWeights(mem, self->solver_->weights.get()) == CV_SUCCESS
                              ? self->solver_->weights.data()
                              : nullptr;
  try {
    Context& ctx = self->ctx_;
    ctx.time = t;
    ctx.x = N_VGetArrayPointer(y);
    ++ctx.evaluation;
    for (int b = 0; b < d.num_blocks(); ++b) {
      if (!d.block(b).has_projection()) continue;
      const BlockLayout& layout = d.layout(b);
      const auto n = static_cast<std::size_t>(layout.num_states);
      d.block(b).Project(BlockContext(&ctx, &layout), std::span<double>(corr + layout.first_state, n),
                         err ? std::span<double>(err + layout.first_state, n) : std::span<double>(),
                         weights ? std::span<const double>(weights + layout.first_state, n)
                                 : std::span<const double>());
    }
  } catch (const std::exception& e) {
    self->callback_failure_ = e.what();
    return ++self->callback_failures_ > kMaxCallbackFailures ? -1 : 1;
  }
  return 0;
}

void Simulator::ErrorHandler(int, const char*, const char* function, char* msg, void* user) {
  auto* self = static_cast<Simulator*>(user);
  self->solver_message_ = std::string(function) + ": " + msg;
}

double Simulator::NextSampleHit() const {
  double next = std::numeric_limits<double>::infinity();
  const auto& periodic = diagram_.periodic_blocks();
  for (size_t i = 0; i < periodic.size(); ++i) {
    const SampleTime& st = diagram_.block(periodic[i]).sample_time();
    next = std::min(next, DecimalGridTime(st.offset + next_hit_[i] * st.period));  // as the rows' times
  }
  return next;
}

void Simulator::HandleSampleHits(double t) {
  const auto& periodic = diagram_.periodic_blocks();
  EvaluateAt(t, ctx_.x);
  for (size_t i = 0; i < periodic.size(); ++i) {
    const SampleTime& st = diagram_.block(periodic[i]).sample_time();
    // the same formula that produced the stop time, so equality is exact --
    // except at t_end, which a hit may pass by a rounding (3 * 0.1 > 0.3)
    if (!SameInstant(DecimalGridTime(st.offset + next_hit_[i] * st.period), t)) continue;
    diagram_.block(periodic[i]).OnSampleHit(BlockContext(&ctx_, &diagram_.layout(periodic[i])));
    ++next_hit_[i];
    ++stats_.sample_hits;
  }
}

void Simulator::HandleCrossings(double t) {
  // roots_found_: the crossings CheckCrossings located at t
  EvaluateAt(t, ctx_.x);
  const double instant = kInstant * std::max(1.0, std::abs(t));
  for (int i = 0; i < diagram_.num_zero_crossings(); ++i) {
    if (roots_found_[i] == 0) continue;
    fired_in_a_row_[i] = t - last_fired_[i] <= instant ? fired_in_a_row_[i] + 1 : 1;
    last_fired_[i] = t;
    if (fired_in_a_row_[i] <= kMaxEventsPerInstant) continue;
    const int b = crossing_owner_[i];
    throw SimulationError("block '" + diagram_.block(b).name() + "' crossing " +
                          std::to_string(i - diagram_.layout(b).first_crossing) + " keeps firing at t = " +
                          std::to_string(t) + " (" + std::to_string(kMaxEventsPerInstant) +
                          " times at one instant: does its event handler leave it where it fires again?)");
  }
  for (int i = 0; i < diagram_.num_zero_crossings(); ++i) {
    if (roots_found_[i] == 0) continue;
    const int b = crossing_owner_[i];
    const int local = i - diagram_.layout(b).first_crossing;
    diagram_.block(b).OnZeroCrossing(local, roots_found_[i], BlockContext(&ctx_, &diagram_.layout(b)));
    events_.push_back({t, b, local, roots_found_[i]});
    ++stats_.events;
  }
}

void Simulator::AccumulateStats() {
  void* mem = solver_->cvode.get();
  long v = 0;
  auto add = [&](int flag, long* total) {
    if (flag >= 0) *total += v;
  };
  add(CVodeGetNumSteps(mem, &v), &stats_.steps);
  add(CVodeGetNumRhsEvals(mem, &v), &stats_.rhs_evals);
  if (linear_solver_attached_) {  // otherwise CVLS would complain on stderr
    add(CVodeGetNumLinRhsEvals(mem, &v), &stats_.jac_rhs_evals);
    add(CVodeGetNumJacEvals(mem, &v), &stats_.jac_evals);
    add(CVodeGetNumLinIters(mem, &v), &stats_.linear_iters);
  }
  add(CVodeGetNumNonlinSolvIters(mem, &v), &stats_.newton_iters);
  add(CVodeGetNumNonlinSolvConvFails(mem, &v), &stats_.newton_failures);
  add(CVodeGetNumErrTestFails(mem, &v), &stats_.error_test_failures);
  add(CVodeGetNumGEvals(mem, &v), &stats_.root_evals);
  if (projection_attached_) {  // likewise for the projection's counters
    add(CVodeGetNumProjEvals(mem, &v), &stats_.projections);
    add(CVodeGetNumProjFails(mem, &v), &stats_.projection_failures);
  }
}

void Simulator::Reinitialize(double t) {
  // what the solver found beyond t (a watched stretch) is void now
  watched_to_ = t;
  if (!SettleModes(diagram_, &ctx_))
    throw SimulationError("modes did not settle at t = " + std::to_string(t) +
                          " (blocks keep switching each other's modes)");
  AccumulateStats();
  Check(CVodeReInit(solver_->cvode.get(), t, solver_->y.get()), "CVodeReInit");
  frozen_valid_ = false;  // a new start: the history compared against is gone
  ++stats_.reinits;
  StartCrossings(t, solver_->y.data());
}

class Simulator::Point final : public ControlPoint {
 public:
  explicit Point(Simulator& sim) : sim_(sim) {}
  double time() const override { return sim_.ctx_.time; }
  double end_time() const override { return sim_.options_.t_end; }
  std::span<const double> signals() const override { return sim_.ctx_.signals; }
  std::span<double> discrete() override { return sim_.ctx_.discrete; }
  void Changed() override {
    sim_.control_changed_ = true;
    sim_.EvaluateAt(sim_.ctx_.time, sim_.ctx_.x);
  }
  void Stop(std::string reason) override {
    sim_.stop_requested_ = true;
    sim_.stop_reason_ = std::move(reason);
  }

 private:
  Simulator& sim_;
};

bool Simulator::CallControl(double t, double* x, void (RunControl::*call)(ControlPoint&), bool evaluated) {
  if (!evaluated) EvaluateAt(t, x);
  control_changed_ = false;
  Point point(*this);
  (control_->*call)(point);
  if (control_changed_ && !SettleModes(diagram_, &ctx_))
    throw SimulationError("modes did not settle at t = " + std::to_string(t) + " after the control script's changes");
  return control_changed_;
}

double Simulator::NextStop() const {
  const double timer = control_ ? control_->NextTimer() : std::numeric_limits<double>::infinity();
  return std::min({NextSampleHit(), timer, options_.t_end});
}

RunOutcome Simulator::Run(const std::function<void(double)>& progress) {
  const double t0 = options_.t_start, t_end = options_.t_end;
  const sunindextype n = std::max(1, diagram_.num_states());
  const FlushDenormals flush_denormals;  // for the whole run (see the header)
  solver_ = std::make_unique<Solver>(n, jacobian_.get(), krylov_ ? std::vector<std::pair<int, int>>() : rate_pairs_,
                                     krylov_);
  double* y = solver_->y.data();
  std::fill(y, y + n, 0.0);
  void* mem = solver_->cvode.get();
  results_.Clear();  // a run again starts afresh (streaming, if set, stays)
  events_.clear();
  stats_ = SolverStats();
  for (const AlgebraicLoop& loop : diagram_.loops()) loop.ResetStats();
  if (jacobian_) {
    stats_.sparse = true;
    stats_.colours = jacobian_->num_colours();
    stats_.nonzeros = jacobian_->pattern().nonzeros();
  }
  stats_.krylov = krylov_;
  stats_.analytic_jacobian = analytic_ != nullptr;
  rhs_x_.assign(analytic_ ? n : 0, 0.0);
  rhs_at_ = 0;
  stats_.newton_size = solver_->second_order ? solver_->second_order->reduced_size() : static_cast<int>(n);
  callback_failures_ = 0;
  callback_failure_.clear();
  callback_no_solution_ = false;
  stop_requested_ = false;
  stop_reason_.clear();
  std::fill(last_fired_.begin(), last_fired_.end(), -std::numeric_limits<double>::infinity());
  std::fill(fired_in_a_row_.begin(), fired_in_a_row_.end(), 0);
  linear_solver_attached_ = false;
  projection_attached_ = false;
  for (auto& tracker : trackers_) tracker.Reset();
  for (auto& accumulator : accumulators_) accumulator.Reset();
  watched_to_ = t0;
  probe_pending_ = false;
  const long expected_rows = std::lround((t_end - t0) / options_.output_interval) + 2;
  results_.Reserve(static_cast<int>(std::min(expected_rows, 10'000'000L)));

  // initial state, modes, the control's start and the sample hits due at t_start
  ctx_.time = t0;
  ctx_.x = y;
  const auto& periodic = diagram_.periodic_blocks();
  for (size_t i = 0; i < periodic.size(); ++i) {
    const SampleTime& st = diagram_.block(periodic[i]).sample_time();
    next_hit_[i] = static_cast<long>(std::max(0.0, std::ceil((t0 - st.offset) / st.period)));
  }
  RunOutcome outcome;
  try {
    InitializeStates(diagram_, &ctx_);
    if (!SettleModes(diagram_, &ctx_)) throw SimulationError("modes did not settle at t_start");
    if (control_) CallControl(t0, y, &RunControl::Start);
    if (NextSampleHit() == t0) HandleSampleHits(t0);
    if (control_ && control_->NextTimer() == t0) CallControl(t0, y, &RunControl::Timer);
    SettleModes(diagram_, &ctx_);

    Check(CVodeInit(mem, &Simulator::Rhs, t0, solver_->y.get()), "CVodeInit");
    Check(CVodeSetUserData(mem, this), "CVodeSetUserData");
    Check(CVodeSetErrHandlerFn(mem, &Simulator::ErrorHandler, this), "CVodeSetErrHandlerFn");
    Check(CVodeSStolerances(mem, options_.rtol, options_.atol), "CVodeSStolerances");
    Check(CVodeSetLinearSolver(mem, solver_->linear_solver(), solver_->matrix()), "CVodeSetLinearSolver");
    if (jacobian_) Check(CVodeSetLinSysFn(mem, &Simulator::LinearSystem), "CVodeSetLinSysFn");
    else if (analytic_) Check(CVodeSetJacFn(mem, &Simulator::DenseJacobian), "CVodeSetJacFn");
    if (krylov_)
      Check(CVodeSetPreconditioner(mem, nullptr, &Simulator::PreconditionRatePairs), "CVodeSetPreconditioner");
    linear_solver_attached_ = true;
    Check(CVodeSetMaxNumSteps(mem, options_.max_steps), "CVodeSetMaxNumSteps");
    if (options_.max_step > 0.0) Check(CVodeSetMaxStep(mem, options_.max_step), "CVodeSetMaxStep");
    if (options_.initial_step > 0.0) Check(CVodeSetInitStep(mem, options_.initial_step), "CVodeSetInitStep");
    // Below this step t + h == t (or nearly): steps would not advance time,
    // and CVODE, merely warning, would go on writing rows of a frozen state.
    Check(CVodeSetMinStep(mem, MinimumStep(t0, t_end)), "CVodeSetMinStep");
    // projection needs the linear solver attached first (CVODE's rule)
    for (int b = 0; b < diagram_.num_blocks(); ++b) {
      if (!diagram_.block(b).has_projection()) continue;
      Check(CVodeSetProjFn(mem, &Simulator::Project), "CVodeSetProjFn");
      projection_attached_ = true;
      break;
    }

    Record(t0, y);
    if (progress) progress(t0);
    StartCrossings(t0, y);
    std::vector<double> interpolated(n), at_root(n);
    N_Vector yout = sundials::WrapArray(n, interpolated.data(), solver_->ctx);
    struct Release {
      N_Vector v;
      ~Release() { N_VDestroy(v); }
    } release{yout};

    long next_output = 1;
    double t = t0;        // the last row, event or stop: the run's results reach here
    long steps = 0;       // since then (options_.max_steps)
    // output times are computed from an integer index: no drift over long runs
    auto output_time = [&](long k) { return std::min(DecimalGridTime(t0 + k * options_.output_interval), t_end); };
    while (t < t_end && !stop_requested_ && !Interrupted()) {
      const double stop = NextStop();
      double t_out = std::min(output_time(next_output), stop);
      // an output time that rounding puts a hair before a sample hit is taken
      // at the hit, so the row shows the values after it (right-continuous)
      if (SameInstant(stop, t_out)) t_out = stop;
      if (t_out <= t) {  // an output time that coincides with the last event
        if (control_ && CallControl(t, y, &RunControl::Output)) Reinitialize(t);
        Record(t, y);
        ++next_output;
        continue;
      }
      Check(CVodeSetStopTime(mem, stop), "CVodeSetStopTime");
      // One step at a time: its rows come from its interpolant. t_out only
      // sizes the first step after a start, as it would in CV_NORMAL mode.
      double t_ret = t;
      int flag = CV_TOO_MUCH_WORK;
      if (steps < options_.max_steps) {
        flag = CVode(mem, t_out, yout, &t_ret, CV_ONE_STEP);
        ++steps;
      } else {
        double tn = t;
        CVodeGetCurrentTime(mem, &tn);
        solver_message_ = "at t = " + std::to_string(tn) + ", " + std::to_string(options_.max_steps) +
                          " steps taken before reaching the output time";
      }
      if (flag == CV_ERR_FAILURE || flag == CV_CONV_FAILURE) {
        // Repeated error-test or convergence failures at one step: restart
        // the method from the last accepted point (order 1, a fresh history)
        // when it took kRestartSteps steps since it last started. A
        // regularised friction law's near-kinks pollute the multistep history
        // now and then (stick_slip_blocks failed at t = 50.2 s, mid-stick,
        // after 2061 error-test failures); error control stays as it was.
        double t_last = t;
        CVodeGetCurrentTime(mem, &t_last);
        long since_start = 0;  // steps since CVODE last started (CVodeReInit resets the count)
        CVodeGetNumSteps(mem, &since_start);
        if (callback_failure_.empty() && since_start >= kRestartSteps &&
            CVodeGetDky(mem, t_last, 0, yout) == CV_SUCCESS) {
          std::copy(interpolated.begin(), interpolated.end(), y);
          ctx_.x = y;
          t = std::max(t, t_last);
          steps = 0;
          Reinitialize(t_last);
          ++stats_.restarts;
          continue;
        }
      }
      if (flag < 0) {
        // keep what was reached: the state at the last successful step
        double t_last = t;
        CVodeGetCurrentTime(mem, &t_last);
        if (t_last > t && CVodeGetDky(mem, t_last, 0, yout) == CV_SUCCESS) {
          try {
            Record(t_last, interpolated.data());
            t = t_last;
          } catch (const std::exception&) {
            // the outputs fail there too: the rows up to the last output time stand
          }
        }
        outcome.ok = false;
        outcome.t_reached = t;
        outcome.failure = sundials::CvodeFlagName(flag);
        if (!callback_failure_.empty()) outcome.failure += ": " + callback_failure_;
        else if (!solver_message_.empty()) outcome.failure += ": " + solver_message_;
        double h = 0.0;
        if (!(callback_no_solution_ && !callback_failure_.empty()) && CVodeGetCurrentStep(mem, &h) == CV_SUCCESS &&
            std::abs(h) <= 2.0 * MinimumStep(t0, t_end))
          outcome.failure += " (the step size fell to the resolution of time: the solver cannot meet the tolerances "
                             "here; a singular position, a discontinuity without an event, or rtol below what the "
                             "model's round-off allows)";
        for (int b = 0; b < diagram_.num_blocks(); ++b) {
          const std::string note = diagram_.block(b).FailureNote();
          if (!note.empty()) outcome.failure += "; block '" + diagram_.block(b).name() + "': " + note;
        }
        break;
      }
      // The step reached t_ret (its end, or the stop time). Its output times
      // and then its end are checked for crossings in order, as CVODE checks
      // them in CV_NORMAL mode; each output time gets its row, all outputs
      // evaluated once for both.
      const bool at_stop = flag == CV_TSTOP_RETURN || t_ret >= stop;
      taylor_order_ = -1;  // a new step: its polynomial is not known yet
      bool restarted = false;  // an event, or a control's change at a row: the rest of the step is void
      bool frozen_checked = false;
      for (;;) {
        double t_check = std::min(output_time(next_output), stop);
        if (SameInstant(stop, t_check)) t_check = stop;
        // a row at the stop time comes after its sample hits (below)
        const bool row = t_check <= t_ret && !(at_stop && t_check >= t_ret);
        if (!row) {
          t_check = t_ret;  // the step's end
          if (t_check <= crossings_->lower_time() || crossings_->size() == 0) {
            WatchTo(t_ret);
            break;
          }
        }
        double* x = solver_->check.data();
        if (t_check == t_ret) {
          std::copy(interpolated.begin(), interpolated.end(), x);
        } else if (taylor_order_ >= 0 || output_time(next_output + 1) <= t_ret) {
          InterpolateInStep(t_check, x);  // several rows in this step: its polynomial, once
        } else {
          Check(CVodeGetDky(mem, t_check, 0, solver_->check.get()), "CVodeGetDky");
        }
        double t_root = 0.0;
        if (crossings_->size() > 0 && CheckCrossings(t_check, x, row, &t_root, at_root.data())) {
          // an event: continue from the located instant with the new modes
          WatchTo(t_root);
          std::copy(at_root.begin(), at_root.end(), y);
          t = t_root;
          ctx_.x = y;
          steps = 0;
          HandleCrossings(t);
          Reinitialize(t);
          restarted = true;
          break;
        }
        WatchTo(t_check);
        if (!row) break;
        if (crossings_->size() == 0 || !reports_.empty()) EvaluateAt(t_check, x);  // else the check did
        if (!frozen_checked) RefuseFrozenState();
        frozen_checked = true;
        bool changed = false;
        if (control_) changed = CallControl(t_check, x, &RunControl::Output, true);
        if (changed) {
          // the control changed the model here: the solver must not go on
          // from a point beyond it, computed with the old values
          std::copy(x, x + n, y);
          ctx_.x = y;
          Reinitialize(t_check);
          x = y;
        }
        Record(t_check, x, !changed);
        if (progress) progress(t_check);
        ++next_output;
        t = t_check;
        steps = 0;
        if (changed || stop_requested_ || Interrupted()) {
          restarted = true;
          break;
        }
      }
      if (restarted || !at_stop) continue;
      // a sample hit or control timer (also one at t_end): update before
      // the row is taken
      std::copy(interpolated.begin(), interpolated.end(), y);
      ctx_.x = y;
      t = t_ret;
      steps = 0;
      HandleSampleHits(t_ret);
      if (control_ && SameInstant(control_->NextTimer(), t_ret)) CallControl(t_ret, y, &RunControl::Timer);
      if (t_ret < t_end) Reinitialize(t_ret);
      double t_row = std::min(output_time(next_output), stop);
      if (SameInstant(stop, t_row)) t_row = stop;
      if (t_row <= t_ret) {
        if (control_ && CallControl(t_ret, y, &RunControl::Output)) Reinitialize(t_ret);
        RefuseFrozenState();
        Record(t_ret, y);
        if (progress) progress(t_ret);
        ++next_output;
      }
      if (t >= t_end) break;
    }
    if (outcome.ok && Interrupted()) {
      outcome.ok = false;
      outcome.interrupted = *interrupt_;
      outcome.t_reached = t;
      outcome.failure = std::string("interrupted by SIG") + sigabbrev_np(*interrupt_);  // SIGINT, SIGTERM, SIGHUP
    } else if (outcome.ok && stop_requested_) {
      // the row at the instant the control stopped the run, unless it was one
      if (results_.num_rows() == 0 || results_.last_time() != ctx_.time) Record(ctx_.time, ctx_.x);
      outcome.stopped = true;
      outcome.stop_reason = stop_reason_;
      outcome.t_reached = ctx_.time;
    } else if (outcome.ok) {
      outcome.t_reached = t_end;
    }
    if (outcome.ok && control_) CallControl(ctx_.time, ctx_.x, &RunControl::Finish);
  } catch (const std::exception& e) {
    outcome.ok = false;
    outcome.t_reached = ctx_.time;
    outcome.failure = e.what();
  }
  AccumulateStats();
  results_.SetFigures(figures());
  return outcome;
}

}  // namespace mechflow::blocks
