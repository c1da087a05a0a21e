#include "blocks/framework/evaluation.h"

namespace mechflow::blocks {

void InitializeStates(const Diagram& d, Context* ctx) {
  // the claim first: a run refused there leaves nothing half made
  ctx->run_claim.reset();
  if (d.run_claim()) ctx->run_claim = d.run_claim()();
  // fresh scratch: a run never starts from caches or counters of another
  ctx->scratch.clear();
  ctx->scratch.reserve(d.num_blocks());
  for (int b = 0; b < d.num_blocks(); ++b) ctx->scratch.push_back(d.block(b).MakeScratch());
  ctx->loop_scratch.clear();
  ctx->loop_scratch.reserve(d.loops().size());
  for (const AlgebraicLoop& loop : d.loops()) ctx->loop_scratch.push_back(loop.MakeScratch());
  for (int b = 0; b < d.num_blocks(); ++b) d.block(b).Initialize(BlockContext(ctx, &d.layout(b)));
}

void EvaluateOutputs(const Diagram& d, Context* ctx) { EvaluateOutputs(d, d.schedule(), ctx); }

void EvaluateOutputs(const Diagram& d, const std::vector<OutputNode>& entries, Context* ctx) {
  for (const OutputNode& node : entries) {
    if (node.loop >= 0)
      d.loops()[node.loop].Solve(d, ctx);
    else
      d.block(node.block).CalcOutput(node.port, BlockContext(ctx, &d.layout(node.block)));
  }
}

void EvaluateDerivatives(const Diagram& d, Context* ctx) {
  for (const int b : d.stateful_blocks()) d.block(b).CalcDerivatives(BlockContext(ctx, &d.layout(b)));
}

void EvaluateZeroCrossings(const Diagram& d, Context* ctx) {
  for (const int b : d.crossing_blocks()) d.block(b).CalcZeroCrossings(BlockContext(ctx, &d.layout(b)));
}

bool SettleModes(const Diagram& d, Context* ctx, int max_passes) {
  for (int pass = 0; pass < max_passes; ++pass) {
    ++ctx->evaluation;
    EvaluateOutputs(d, ctx);
    bool changed = false;
    for (int b = 0; b < d.num_blocks(); ++b)
      changed |= d.block(b).UpdateModes(BlockContext(ctx, &d.layout(b)));
    if (!changed) return true;
  }
  EvaluateOutputs(d, ctx);
  return false;
}

}  // namespace mechflow::blocks
