#pragma once
// Every output of the diagram at (t, x), the evaluation each part of a run
// (rows, crossings, reports, sample hits, the control) starts from.

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"
#include "blocks/framework/evaluation.h"

namespace mechflow::blocks {

// Every output at (t, x), or the dynamics schedule's alone.
inline void EvaluateAt(const Diagram& diagram, Context* ctx, double t, double* x, bool dynamics_only = false) {
  ctx->time = t;
  ctx->x = x;
  ++ctx->evaluation;
  EvaluateOutputs(diagram, dynamics_only ? diagram.dynamics_schedule() : diagram.schedule(), ctx);
}

}  // namespace mechflow::blocks
