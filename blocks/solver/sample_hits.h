#pragma once
// SampleHits: the periodic blocks' sample hits. The integrator stops exactly
// at each hit (never passing it); there the due blocks update.

#include <vector>

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/solver/solver_options.h"

namespace mechflow::blocks {

class SampleHits {
 public:
  // Counts the hits into `stats` (not owned).
  SampleHits(const Diagram& diagram, Context* ctx, SolverStats* stats);

  // A new run from t0: every block's first hit at or after t0.
  void Reset(double t0);
  // The next hit of any periodic block, +infinity for none.
  double Next() const;
  // Evaluates the outputs at t (at ctx.x) and updates the blocks due at t.
  void Handle(double t);

 private:
  const Diagram& diagram_;
  Context& ctx_;
  SolverStats& stats_;
  std::vector<long> next_hit_;  // per periodic block: next k
};

}  // namespace mechflow::blocks
