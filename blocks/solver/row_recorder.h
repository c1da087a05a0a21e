#pragma once
// RowRecorder: writes the logged signals' row at an output time into the
// results (and to the row observer), refusing a row with a signal that is not
// finite.

#include <string>
#include <vector>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/outputs/results.h"

namespace mechflow::blocks {

// Sees every row as it is recorded, with the continuous state and the
// Context's signals at that time (an animation records the bodies' poses).
class RowObserver {
 public:
  virtual ~RowObserver() = default;
  virtual void OnRow(double t, const double* x, const Context& ctx) = 0;
};

class RowRecorder {
 public:
  // `logged`: the columns after time, in order; the results must have their
  // columns (LoggedColumnNames, blocks/outputs/column_names.h). Neither is owned.
  RowRecorder(const Diagram& diagram, Context* ctx, const std::vector<SignalRef>& logged, Results* results);

  // `observer` (not owned) sees every row after it is recorded.
  void SetObserver(RowObserver* observer) { observer_ = observer; }
  // Writes a row at (t, x); `evaluated`: every output is current there.
  void Record(double t, double* x, bool evaluated = false);

 private:
  // Before a row is written, with every output evaluated at t, when some
  // signal is not finite (an overflow, 0/0; Record checks the whole signal
  // vector once per row, not the right-hand side, whose Newton iterates may
  // stray and recover): throws SimulationError naming the block and port,
  // the first in schedule order.
  [[noreturn]] void RefuseNonFiniteOutputs(double t) const;

  const Diagram& diagram_;
  Context& ctx_;
  Results& results_;
  RowObserver* observer_ = nullptr;
  std::vector<double> row_;
  std::vector<int> row_signals_;     // per column after time: the signal it logs
  std::vector<double> row_factors_;  // and the factor to its column's unit (SignalRef::column_factor)
};

}  // namespace mechflow::blocks
