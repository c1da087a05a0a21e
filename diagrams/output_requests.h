#pragma once
// The output requests of a diagram, resolved against its built blocks: the
// logged signals and their columns' units (<log>, recorders), <report>s,
// <spectrum>s and <xy> panels. Every error is an InputError naming file:line.

#include "diagrams/description.h"
#include "diagrams/evaluator.h"
#include "diagrams/loader.h"

namespace mechflow::diagrams {

// Fills out->logged, units, groups, reports, spectra and xy_plots from `d`;
// out->diagram and out->identifiers must be built.
void CollectOutputRequests(const DiagramDescription& d, const Evaluator& eval, LoadedDiagram* out);

// The unit of a signal's values as a run gives them when no <log> chose one
// (a run's own list of signals to log): the block's own (SI), or "" when the
// signal is an identifier's given in another unit than SI (its values are SI).
std::string RawSignalUnit(const LoadedDiagram& loaded, const blocks::SignalRef& s);

}  // namespace mechflow::diagrams
