#pragma once
// CrossingEvents: the diagram's zero crossings during a run. They are checked
// at every step end and output time, as CVODE's own root finding would in
// CV_NORMAL mode (blocks/solver/crossing_search.h), located on the step's
// interpolant, and handed to the blocks that own them; each handled crossing
// is kept as an EventRecord.

#include <memory>
#include <string>
#include <vector>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/solver/crossing_search.h"
#include "blocks/solver/refiring_limit.h"
#include "blocks/solver/solver_options.h"

namespace mechflow::blocks {

class CvodeRun;

// One handled zero crossing, kept so a user can ask when contacts, impacts or
// mode switches happened without resampling the output grid.
struct EventRecord {
  double time = 0.0;   // [s], located by CVODE's root finding
  int block = 0;       // index in the diagram
  int crossing = 0;    // the block's own zero-crossing index
  int direction = 0;   // +1 rising, -1 falling
};

// The event as the event log names it: "block: what happened" (a mechanism's
// "block.element ..."), or the block's crossing number and direction when
// the block gives that crossing no name.
std::string EventName(const Diagram& diagram, const EventRecord& event);

class CrossingEvents {
 public:
  // Counts root evaluations and events into `stats` (not owned).
  CrossingEvents(const Diagram& diagram, Context* ctx, SolverStats* stats);
  ~CrossingEvents();

  bool empty() const { return search_->size() == 0; }
  // Where the search last started or accepted a check.
  double lower_time() const { return search_->lower_time(); }
  const std::vector<EventRecord>& events() const { return events_; }

  // A new run: no events, no firings counted.
  void Reset();
  // A new start of the search at (t, x) (with CVODE's).
  void Start(double t, double* x);
  // Checks the crossings at (t, x) after a step of `cvode`: all outputs
  // evaluated there when `row`. On a crossing between the last check and t,
  // returns true with it located and the state there in x_root, at *t_root;
  // otherwise the check is accepted.
  bool Check(const CvodeRun& cvode, double t, double* x, bool row, double* t_root, double* x_root);
  // Lets each block whose crossing Check located at t handle it (may change
  // modes and states); throws SimulationError when a crossing keeps firing
  // at one instant (RefiringLimit).
  void Handle(double t);

 private:
  // The zero-crossing functions at (t, x) into values_, after evaluating the
  // outputs there (all of them for a row, else the dynamics schedule's).
  void EvaluateAt(double t, double* x, bool row);

  const Diagram& diagram_;
  Context& ctx_;
  SolverStats& stats_;
  std::unique_ptr<CrossingSearch> search_;
  std::vector<int> owner_;        // crossing index -> block
  std::vector<double> values_;    // at the last check
  std::vector<int> found_;        // per crossing: its direction at the located instant, 0 if none
  bool probe_pending_ = false;    // a function was exactly zero at the start
  RefiringLimit refiring_;
  std::vector<EventRecord> events_;
};

}  // namespace mechflow::blocks
