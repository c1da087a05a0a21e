#pragma once
// What the commands print: run summary, check listing, DOT graph.

#include <ostream>

#include "blocks/simulator.h"
#include "diagrams/loader.h"

namespace mechflow::cli {

// Solver counters, one line each group.
void PrintStats(const blocks::SolverStats& stats, std::ostream& out);

// Minimum and maximum of every logged column, with the times they occur.
void PrintSignalRanges(const blocks::Results& results, std::ostream& out);

// `mechflow check`: identifiers, schedule, state layout, crossings, sampled blocks.
void PrintCheck(const diagrams::LoadedDiagram& loaded, std::ostream& out);

// `mechflow graph`: Graphviz DOT of blocks (with ports) and connections.
void PrintDot(const diagrams::LoadedDiagram& loaded, std::ostream& out);

}  // namespace mechflow::cli
