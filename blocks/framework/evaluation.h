#pragma once
// The passes over a built diagram that the simulator runs at each instant.
//
// Each pass walks precomputed index lists: nothing here allocates or looks a
// name up (but InitializeStates, which starts a run). The caller points the Context's x / xdot / crossings at the right
// buffers and sets its time first.

#include "blocks/framework/block_context.h"
#include "blocks/framework/diagram.h"

namespace mechflow::blocks {

// Starts a run: claims what the diagram's runs must (Diagram::run_claim;
// throws when it cannot), makes the run's scratch afresh (every block's and
// algebraic loop's, Context::scratch; this allocates), then sets every
// block's initial continuous and discrete states.
void InitializeStates(const Diagram& d, Context* ctx);

// Computes every output port in schedule order.
void EvaluateOutputs(const Diagram& d, Context* ctx);
// Computes the given entries of the schedule, in their order
// (Diagram::dynamics_schedule, rest_schedule).
void EvaluateOutputs(const Diagram& d, const std::vector<OutputNode>& entries, Context* ctx);

// Writes the derivative of every continuous state (outputs must be current).
void EvaluateDerivatives(const Diagram& d, Context* ctx);

// Writes every zero-crossing function (outputs must be current).
void EvaluateZeroCrossings(const Diagram& d, Context* ctx);

// Brings modes into agreement with inputs after initialisation or an event:
// evaluates outputs, lets each block update its modes, and repeats while any
// mode changed (at most `max_passes` times). Returns false if modes did not
// settle, which means the diagram chatters at this instant.
bool SettleModes(const Diagram& d, Context* ctx, int max_passes = 20);

}  // namespace mechflow::blocks
