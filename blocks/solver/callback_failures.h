#pragma once
// What the run's CVODE callbacks (right-hand side, Jacobian, projection)
// report when they fail: the flag CVODE expects back and the reason kept for
// the run's failure message.
//
// A failure is recoverable at first: CVODE retries with smaller steps, so a
// failing run stops close to the failing instant; after kMaxRecoverable of
// them it is final, so that a model that cannot go on does not creep towards
// it with ever smaller steps.

#include <string>
#include <utility>

namespace mechflow::blocks {

class CallbackFailures {
 public:
  // Right-hand-side failures (exceptions) tolerated in one run before it stops.
  static constexpr int kMaxRecoverable = 30;

  void Reset() {
    reason_.clear();
    no_solution_ = false;
    count_ = 0;
  }
  // An exception in a callback: 1 (retry smaller) until too many, then -1.
  int Recoverable(std::string reason) {
    reason_ = std::move(reason);
    return ++count_ > kMaxRecoverable ? -1 : 1;
  }
  // A value CVODE may avoid by a smaller step (a derivative not finite):
  // 1, not counted, as CVODE fails by itself if it persists.
  int Retry(std::string reason) {
    reason_ = std::move(reason);
    return 1;
  }
  // A bug (a block's Jacobian outside its own pattern): -1, never retried.
  int Final(std::string reason) {
    reason_ = std::move(reason);
    return -1;
  }
  // The last right-hand side failed as an algebraic loop without a solution
  // (then a tiny step says nothing of the tolerances).
  void set_no_solution(bool no_solution) { no_solution_ = no_solution; }

  bool any() const { return !reason_.empty(); }
  const std::string& reason() const { return reason_; }
  bool no_solution() const { return no_solution_; }

 private:
  std::string reason_;
  bool no_solution_ = false;
  int count_ = 0;
};

}  // namespace mechflow::blocks
