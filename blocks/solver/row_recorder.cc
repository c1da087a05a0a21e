#include "blocks/solver/row_recorder.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "blocks/solver/evaluate_at.h"
#include "blocks/solver/run_failure.h"
#include "mech/errors.h"

namespace mechflow::blocks {

namespace {

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

}  // namespace

RowRecorder::RowRecorder(const Diagram& diagram, Context* ctx, const std::vector<SignalRef>& logged,
                         Results* results)
    : diagram_(diagram), ctx_(*ctx), results_(*results) {
  row_.resize(results_.num_columns());
  for (const SignalRef& s : logged)
    for (int i = 0; i < s.width; ++i) {
      row_signals_.push_back(s.offset + i);
      row_factors_.push_back(s.column_factor);
    }
}

void RowRecorder::Record(double t, double* x, bool evaluated) {
  if (!evaluated) EvaluateAt(diagram_, &ctx_, t, x);
  if (!AllFinite(ctx_.signals)) [[unlikely]]
    RefuseNonFiniteOutputs(t);
  row_[0] = t;
  const double* signals = ctx_.signals.data();
  // times 1 is exact: columns in SI keep the signal's bits
  for (std::size_t c = 0; c < row_signals_.size(); ++c) row_[c + 1] = signals[row_signals_[c]] * row_factors_[c];
  results_.AddRow(row_.data());
  if (observer_) observer_->OnRow(t, x, ctx_);
}

void RowRecorder::RefuseNonFiniteOutputs(double t) const {
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
  out << DescribeSignal(diagram_, bad) << " is not finite (" << NotFiniteText(signals[bad]) << ") at t = " << t
      << "; the rows before are kept (a value out of the range of double precision, or undefined: check what the "
         "block computes from its inputs and parameters there)";
  throw SimulationError(out.str());
}

}  // namespace mechflow::blocks
