#pragma once
// What the commands print: run summary, check listing, DOT graph.

#include <ostream>
#include <string>
#include <vector>

#include "blocks/solver/simulator.h"
#include "diagrams/loader.h"

namespace mechflow::cli {

// Solver counters, one line each group.
void PrintStats(const blocks::SolverStats& stats, std::ostream& out);

// Minimum and maximum of every logged column, with the times they occur.
// `mechflow check`: warns of every global a Lua chunk (control script, Lua
// block) reads that nothing defines (scripting/global_reads.h), naming
// file:line; returns how many.
int PrintUnknownGlobals(const diagrams::LoadedDiagram& loaded, std::ostream& out);

void PrintSignalRanges(const blocks::Results& results, std::ostream& out);

// The figures of the diagram's <report>s, one line each:
//   "peak contact force: 285.219 N at t = 0.094022 s"
// (6 significant digits; "up to the failure" after a failed run).
void PrintFigures(const std::vector<blocks::ReportFigure>& figures, bool finished, std::ostream& out);

// Warnings carried by events (an element crossing that means "check the
// model", e.g. a contact's penetration beyond its max_penetration): one line
// per element, at the first such event, with its time.
// The event log (mechflow run --verbose): every event with its time, the
// block, and for a mechanism the element and what the event means for it.
void PrintEventLog(const blocks::Diagram& diagram, const std::vector<blocks::EventRecord>& events,
                   std::ostream& out);

void PrintEventWarnings(const blocks::Diagram& diagram, const std::vector<blocks::EventRecord>& events,
                        std::ostream& out);

// After a run (`run`: its Context): what blocks saw that the model may not mean (a unilateral
// friction block fed a pulling normal force), one line per block.
void PrintRunWarnings(const blocks::Diagram& diagram, const blocks::Context& run, std::ostream& out);

// What the control script did: callbacks run, and per identifier it set the
// number of changes with the first and last (time, value).
void PrintScriptChanges(const scripting::ControlScript& script, const scripting::IdentifierTable& identifiers,
                        std::ostream& out);

// Every change of the script, one CSV line each: time,identifier,value.
void WriteScriptChanges(const scripting::ControlScript& script, const scripting::IdentifierTable& identifiers,
                        std::ostream& out);

// `mechflow check`: identifiers, schedule, state layout, crossings, sampled
// blocks, and the tree of subsystem and part instances when there are any.
void PrintCheck(const diagrams::LoadedDiagram& loaded, std::ostream& out);

// `mechflow graph`: Graphviz DOT of blocks (with ports) and connections, the
// blocks of each subsystem instance in a cluster labelled with its path.
void PrintDot(const diagrams::LoadedDiagram& loaded, std::ostream& out);

}  // namespace mechflow::cli
