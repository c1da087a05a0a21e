#pragma once
// `mechflow sweep`: the diagram run once for every combination of the varied
// identifiers' values (the cartesian product, last --vary fastest), several
// runs at a time.
//
// The file is read once; each worker thread keeps a run::Model of it, and
// each run builds that model afresh with its values as --set overrides after
// the common ones (run/model.h), so it owns its Lua state, identifiers,
// blocks and solver: runs share nothing that changes, and a run gives the
// same numbers whether it runs alone, on a worker thread or on another MPI
// rank. Threads take the runs in index order from a shared counter; results
// are kept by index, so the summary is in cartesian order whatever finishes
// first. Under mpirun (cli/ranks.h) run i belongs to rank i mod K, each rank
// runs its share on its own threads and writes those runs' results, and the
// summary rows go to rank 0, which alone writes the summary.
//
// Files (in the output folder, beside where `run` puts NAME.csv):
//   NAME.runK.ID=VALUE[.ID=VALUE].csv  each run's results, K from 1, padded
//   NAME.sweep.csv                      one row per run:
//     run,ID...,status,t_reached,error,results,<figure> [unit],<figure> time [s],...
// status is ok, stopped (ended early by its control script's sim:stop, which
// is not a failure; the reason in the error column) or failed. A run that
// fails (solver failure, a value its model refuses, an error in a script) is
// a row with its error; the sweep goes on.
// Before anything runs, the diagram is loaded once with the common options and
// every --vary is checked (a known identifier defined by a number, not varied
// twice, not also given by --set): bad input exits 2 without a run.

#include <functional>
#include <ostream>
#include <thread>
#include <vector>

#include "cli/arguments.h"

namespace mechflow::cli {

// Exit code: 0 every run finished, 1 some failed (summary written), 2 bad input.
int SweepCommand(const Arguments& args, std::ostream& out, std::ostream& err);

// Starts a thread running `worker` (std::thread's constructor in a sweep).
using ThreadStarter = std::function<std::thread(const std::function<void()>& worker)>;
// Up to `wanted` threads running `worker`, started by `start`; stops at the
// first that cannot start (std::system_error: a process limit such as
// ulimit -u, or the system's), so the threads already running are returned
// to be joined instead of being destroyed joinable (std::terminate).
std::vector<std::thread> StartThreads(int wanted, const std::function<void()>& worker, const ThreadStarter& start);

}  // namespace mechflow::cli
