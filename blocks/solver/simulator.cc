#include "blocks/solver/simulator.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "blocks/framework/algebraic_loop.h"
#include "blocks/framework/evaluation.h"
#include "blocks/outputs/column_names.h"
#include "blocks/solver/cvode_run.h"
#include "blocks/solver/evaluate_at.h"
#include "blocks/solver/flush_denormals.h"
#include "blocks/solver/run_failure.h"
#include "mech/errors.h"

namespace mechflow::blocks {

using sundials::Check;

SolverOptions Simulator::Checked(const Diagram& diagram, SolverOptions options) {
  const std::string problem = options.Problem();
  if (!problem.empty()) throw InputError("solver settings: " + problem);
  if (options.output_interval == 0.0) options.output_interval = (options.t_end - options.t_start) / 1000.0;
  for (const int b : diagram.periodic_blocks()) {
    const std::string period = SamplePeriodProblem(diagram.block(b).sample_time().period, options.t_start,
                                                   options.t_end);
    if (!period.empty())
      throw InputError(diagram.origin(b) + ": block '" + diagram.block(b).name() + "': sample period: " + period);
  }
  return options;
}

Simulator::Simulator(const Diagram& diagram, SolverOptions options, std::vector<SignalRef> logged)
    : diagram_(diagram),
      options_(Checked(diagram, options)),
      logged_(std::move(logged)),
      results_(LoggedColumnNames(logged_)),
      grid_(options_.t_start, options_.output_interval, options_.t_end, options_.output_times),
      solver_choice_(ChooseLinearSolver(diagram, options_)),
      rows_(diagram, &ctx_, logged_, &results_),
      frozen_(diagram.num_states(), options_.rtol, options_.atol),
      reports_(ctx_.signals),
      crossings_(diagram, &ctx_, &stats_),
      sample_hits_(diagram, &ctx_, &stats_),
      control_(diagram, &ctx_, options_.t_end),
      at_root_(std::max(1, diagram.num_states()), 0.0) {
  ctx_.signals.assign(diagram_.num_signals(), 0.0);
  ctx_.discrete.assign(diagram_.num_discrete_states(), 0.0);
  // sixteen looks a period, at least, whatever steps the integrator takes
  double fastest = INFINITY;
  for (int b = 0; b < diagram_.num_blocks(); ++b) fastest = std::min(fastest, diagram_.block(b).OwnTimeScale());
  reports_.SetLongestPiece(fastest / 16.0);
}

Simulator::~Simulator() = default;

RunOutcome Simulator::Run(const std::function<void(double)>& progress) {
  const FlushDenormals flush_denormals;  // for the whole run (see the header)
  Start(progress);
  AdvanceTo(options_.t_end);
  return Finish();
}

void Simulator::Start(const std::function<void(double)>& progress) {
  const FlushDenormals flush_denormals;
  BeginRun(progress);
  try {
    StartAt(options_.t_start);
  } catch (const std::exception& e) {
    outcome_.ok = false;
    outcome_.t_reached = ctx_.time;
    outcome_.failure = e.what();
  }
}

bool Simulator::AdvanceTo(double limit) {
  const FlushDenormals flush_denormals;
  if (!outcome_.ok) return false;
  try {
    while (at_.t < limit && !control_.stop_requested() && !Interrupted()) {
      if (!step_.open) {
        const double stop = NextStop();
        const double t_out = NextRowTime(stop);
        if (t_out <= at_.t) {
          RowAtLastInstant();
          continue;
        }
        double t_ret = at_.t;
        const int flag = TakeStep(stop, t_out, &t_ret);
        if (flag < 0) {
          if (Restart(flag)) continue;
          Fail(flag, &outcome_);
          return false;
        }
        cvode_->polynomial.Forget();  // a new step: its polynomial is not known yet
        step_.open = true;
        step_.t_ret = t_ret;
        step_.stop = stop;
        step_.at_stop = flag == CV_TSTOP_RETURN || t_ret >= stop;
        step_.frozen_checked = false;
      }
      const Scan scan = ScanStep(step_.t_ret, step_.stop, step_.at_stop, limit);
      if (scan == Scan::kPaused) return true;
      step_.open = false;
      if (scan == Scan::kCut || !step_.at_stop) continue;
      ArriveAtStop(step_.t_ret);
      if (at_.t >= options_.t_end) break;
    }
  } catch (const std::exception& e) {
    step_.open = false;
    outcome_.ok = false;
    outcome_.t_reached = ctx_.time;
    outcome_.failure = e.what();
    return false;
  }
  return at_.t >= limit;
}

RunOutcome Simulator::Finish() {
  const FlushDenormals flush_denormals;
  step_.open = false;
  try {
    EndRun(&outcome_);
  } catch (const std::exception& e) {
    outcome_.ok = false;
    outcome_.t_reached = ctx_.time;
    outcome_.failure = e.what();
  }
  cvode_->AccumulateStats();
  results_.SetFigures(figures());
  progress_ = nullptr;
  return outcome_;
}

void Simulator::RestartHere() {
  const FlushDenormals flush_denormals;
  if (!outcome_.ok) return;
  double* y = cvode_->y();
  if (step_.open) std::copy(step_.x_pause.begin(), step_.x_pause.end(), y);
  step_.open = false;
  ctx_.x = y;
  at_.steps = 0;
  try {
    Reinitialize(at_.t);
    EvaluateAt(diagram_, &ctx_, at_.t, y);  // the outputs with the new held values
  } catch (const std::exception& e) {
    outcome_.ok = false;
    outcome_.t_reached = at_.t;
    outcome_.failure = e.what();
  }
}

void Simulator::EvaluateHere() {
  if (!outcome_.ok || step_.open) return;  // a pause left the context evaluated there
  if (results_.num_rows() > 0 && results_.last_time() == at_.t) return;  // so did the row there
  const FlushDenormals flush_denormals;
  try {
    EvaluateAt(diagram_, &ctx_, at_.t, cvode_->y());
  } catch (const std::exception& e) {
    outcome_.ok = false;
    outcome_.t_reached = at_.t;
    outcome_.failure = e.what();
  }
}

void Simulator::BeginRun(const std::function<void(double)>& progress) {
  const double t0 = options_.t_start;
  progress_ = progress;
  results_.Clear();  // a run again starts afresh (streaming, if set, stays)
  stats_ = SolverStats();
  cvode_ = std::make_unique<CvodeRun>(diagram_, &ctx_, options_, solver_choice_, &stats_, &failures_);
  failures_.Reset();
  control_.Reset();
  crossings_.Reset();
  reports_.Reset(t0);
  frozen_.Forget();
  sample_hits_.Reset(t0);
  at_ = Cursor{t0, 0, 0};
  step_.open = false;
  outcome_ = RunOutcome();
  const long expected_rows = grid_.Count() + 1;  // and a stopped or failed run's last row
  results_.Reserve(static_cast<int>(std::min(expected_rows, 10'000'000L)));
  ctx_.time = t0;
  ctx_.x = cvode_->y();
}

void Simulator::StartAt(double t0) {
  double* y = cvode_->y();
  InitializeStates(diagram_, &ctx_);
  if (!SettleModes(diagram_, &ctx_)) throw SimulationError("modes did not settle at t_start");
  if (control_.active()) control_.Call(t0, y, &RunControl::Start);
  if (sample_hits_.Next() == t0) sample_hits_.Handle(t0);
  if (control_.active() && control_.NextTimer() == t0) control_.Call(t0, y, &RunControl::Timer);
  SettleModes(diagram_, &ctx_);
  cvode_->Start(t0);
  if (grid_.Time(0) == t0) {
    rows_.Record(t0, y);
    Progress(t0);
    at_.next_output = 1;
  }
  crossings_.Start(t0, y);
}

double Simulator::NextStop() const {
  return std::min({sample_hits_.Next(), control_.NextTimer(), options_.t_end});
}

double Simulator::NextRowTime(double stop) const {
  const double t = std::min(grid_.Time(at_.next_output), stop);
  // an output time that rounding puts a hair before a sample hit is taken
  // at the hit, so the row shows the values after it (right-continuous)
  return SameInstant(stop, t) ? stop : t;
}

void Simulator::RowAtLastInstant() {
  double* y = cvode_->y();
  if (control_.active() && control_.Call(at_.t, y, &RunControl::Output)) Reinitialize(at_.t);
  rows_.Record(at_.t, y);
  ++at_.next_output;
}

int Simulator::TakeStep(double stop, double t_out, double* t_ret) {
  void* mem = cvode_->mem();
  Check(CVodeSetStopTime(mem, stop), "CVodeSetStopTime");
  if (at_.steps >= options_.max_steps) {
    double tn = at_.t;
    CVodeGetCurrentTime(mem, &tn);
    cvode_->solver_message() = "at t = " + std::to_string(tn) + ", " + std::to_string(options_.max_steps) +
                               " steps taken before reaching the output time";
    return CV_TOO_MUCH_WORK;
  }
  ++at_.steps;
  // One step at a time: its rows come from its interpolant. t_out only
  // sizes the first step after a start, as it would in CV_NORMAL mode.
  return CVode(mem, t_out, cvode_->step_end.get(), t_ret, CV_ONE_STEP);
}

bool Simulator::Restart(int flag) {
  void* mem = cvode_->mem();
  if (flag != CV_ERR_FAILURE && flag != CV_CONV_FAILURE) return false;
  double t_last = at_.t;
  CVodeGetCurrentTime(mem, &t_last);
  long since_start = 0;  // steps since CVODE last started (CVodeReInit resets the count)
  CVodeGetNumSteps(mem, &since_start);
  if (!RestartPolicy::Restarts(flag, failures_.any(), since_start) ||
      CVodeGetDky(mem, t_last, 0, cvode_->step_end.get()) != CV_SUCCESS)
    return false;
  std::copy(cvode_->step_end.data(), cvode_->step_end.data() + cvode_->n(), cvode_->y());
  ctx_.x = cvode_->y();
  at_.t = std::max(at_.t, t_last);
  at_.steps = 0;
  Reinitialize(t_last);
  ++stats_.restarts;
  return true;
}

void Simulator::Fail(int flag, RunOutcome* outcome) {
  void* mem = cvode_->mem();
  // keep what was reached: the state at the last successful step
  double t_last = at_.t;
  CVodeGetCurrentTime(mem, &t_last);
  if (t_last > at_.t && CVodeGetDky(mem, t_last, 0, cvode_->step_end.get()) == CV_SUCCESS) {
    try {
      rows_.Record(t_last, cvode_->step_end.data());
      at_.t = t_last;
    } catch (const std::exception&) {
      // the outputs fail there too: the rows up to the last output time stand
    }
  }
  double h = 0.0;
  const bool at_resolution = CVodeGetCurrentStep(mem, &h) == CV_SUCCESS &&
                             std::abs(h) <= 2.0 * MinimumStep(options_.t_start, options_.t_end);
  outcome->ok = false;
  outcome->t_reached = at_.t;
  outcome->failure = DescribeFailure(diagram_, &ctx_, flag, failures_, cvode_->solver_message(), at_resolution);
}

Simulator::Scan Simulator::ScanStep(double t_ret, double stop, bool at_stop, double limit) {
  for (;;) {
    double t_check = NextRowTime(stop);
    if (limit < t_ret && t_check > limit) return PauseAt(limit, t_ret);
    // a row at the stop time comes after its sample hits (ArriveAtStop)
    const bool row = t_check <= t_ret && !(at_stop && t_check >= t_ret);
    if (!row) {
      t_check = t_ret;  // the step's end
      if (t_check <= crossings_.lower_time() || crossings_.empty()) {
        WatchTo(t_ret);
        return Scan::kDone;
      }
    }
    double* x = cvode_->check.data();
    StateInStep(t_check, t_ret, x);
    double t_root = 0.0;
    if (!crossings_.empty() && crossings_.Check(*cvode_, t_check, x, row, &t_root, at_root_.data())) {
      EventAt(t_root, at_root_.data());
      return Scan::kCut;
    }
    WatchTo(t_check);
    if (!row) return Scan::kDone;
    if (crossings_.empty() || !reports_.empty()) EvaluateAt(diagram_, &ctx_, t_check, x);  // else the check did
    if (!step_.frozen_checked) frozen_.Check(*cvode_);
    step_.frozen_checked = true;
    if (RowInStep(t_check, x)) return Scan::kCut;
  }
}

Simulator::Scan Simulator::PauseAt(double limit, double t_ret) {
  step_.x_pause.resize(cvode_->n());
  double* x = cvode_->check.data();
  StateInStep(limit, t_ret, x);
  std::copy(x, x + cvode_->n(), step_.x_pause.begin());
  if (at_.t < limit) {  // no row here: the crossings up to the pause, then every output there
    double t_root = 0.0;
    if (!crossings_.empty() && limit > crossings_.lower_time() &&
        crossings_.Check(*cvode_, limit, x, false, &t_root, at_root_.data())) {
      EventAt(t_root, at_root_.data());
      return Scan::kCut;
    }
    WatchTo(limit);
    EvaluateAt(diagram_, &ctx_, limit, step_.x_pause.data());
    at_.t = limit;
  }
  return Scan::kPaused;
}

void Simulator::StateInStep(double t_check, double t_ret, double* x) {
  if (t_check == t_ret) {
    std::copy(cvode_->step_end.data(), cvode_->step_end.data() + cvode_->n(), x);
  } else if (cvode_->polynomial.known() || grid_.Time(at_.next_output + 1) <= t_ret) {
    cvode_->polynomial.At(cvode_->mem(), t_check, x);  // several rows in this step: its polynomial, once
  } else {
    cvode_->StateAt(t_check, cvode_->check.get());
  }
}

void Simulator::EventAt(double t_root, const double* x_root) {
  // continue from the located instant with the new modes
  WatchTo(t_root);
  double* y = cvode_->y();
  std::copy(x_root, x_root + cvode_->n(), y);
  at_.t = t_root;
  ctx_.x = y;
  at_.steps = 0;
  crossings_.Handle(t_root);
  Reinitialize(t_root);
}

bool Simulator::RowInStep(double t_check, double* x) {
  bool changed = false;
  if (control_.active()) changed = control_.Call(t_check, x, &RunControl::Output, true);
  if (changed) {
    // the control changed the model here: the solver must not go on from a
    // point beyond it, computed with the old values
    double* y = cvode_->y();
    std::copy(x, x + cvode_->n(), y);
    ctx_.x = y;
    Reinitialize(t_check);
    x = y;
  }
  rows_.Record(t_check, x, !changed);
  Progress(t_check);
  ++at_.next_output;
  at_.t = t_check;
  at_.steps = 0;
  return changed || control_.stop_requested() || Interrupted();
}

void Simulator::ArriveAtStop(double t_ret) {
  // a sample hit or control timer (also one at t_end): update before the row is taken
  double* y = cvode_->y();
  std::copy(cvode_->step_end.data(), cvode_->step_end.data() + cvode_->n(), y);
  ctx_.x = y;
  at_.t = t_ret;
  at_.steps = 0;
  sample_hits_.Handle(t_ret);
  if (control_.active() && SameInstant(control_.NextTimer(), t_ret)) control_.Call(t_ret, y, &RunControl::Timer);
  if (t_ret < options_.t_end) Reinitialize(t_ret);
  // no output time here (a sample hit or timer between them, or past the last given time)
  const double due = grid_.Time(at_.next_output);
  if (due > t_ret && !(std::isfinite(due) && SameInstant(t_ret, due))) return;
  if (control_.active() && control_.Call(t_ret, y, &RunControl::Output)) Reinitialize(t_ret);
  frozen_.Check(*cvode_);
  rows_.Record(t_ret, y);
  Progress(t_ret);
  ++at_.next_output;
}

void Simulator::EndRun(RunOutcome* outcome) {
  if (outcome->ok && Interrupted()) {
    outcome->ok = false;
    outcome->interrupted = *interrupt_;
    outcome->t_reached = at_.t;
    outcome->failure = std::string("interrupted by SIG") + sigabbrev_np(*interrupt_);  // SIGINT, SIGTERM, SIGHUP
  } else if (outcome->ok && control_.stop_requested()) {
    // the row at the instant the control stopped the run, unless it was one
    if (results_.num_rows() == 0 || results_.last_time() != ctx_.time) rows_.Record(ctx_.time, ctx_.x);
    outcome->stopped = true;
    outcome->stop_reason = control_.stop_reason();
    outcome->t_reached = ctx_.time;
  } else if (outcome->ok) {
    outcome->t_reached = at_.t >= options_.t_end ? options_.t_end : at_.t;  // a co-simulation may end early
  }
  if (outcome->ok && control_.active()) control_.Call(ctx_.time, ctx_.x, &RunControl::Finish);
}

void Simulator::Reinitialize(double t) {
  // what the solver found beyond t (a watched stretch) is void now
  reports_.Restart(t);
  if (!SettleModes(diagram_, &ctx_))
    throw SimulationError("modes did not settle at t = " + std::to_string(t) +
                          " (blocks keep switching each other's modes)");
  cvode_->Reinitialize(t);
  frozen_.Forget();  // a new start: the history compared against is gone
  crossings_.Start(t, cvode_->y());
}

void Simulator::WatchTo(double t) {
  reports_.WatchTo(t, [this](double tm) {
    cvode_->StateAt(tm, cvode_->watch.get());
    EvaluateAt(diagram_, &ctx_, tm, cvode_->watch.data());
  });
}

}  // namespace mechflow::blocks
