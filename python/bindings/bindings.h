#pragma once
// The pieces of the _mechflow extension (python/bindings/module.cc puts them
// together). The Python package mechflow (python/mechflow/) wraps what they
// return, plain dicts, lists and numpy arrays, into its classes; only this
// folder includes pybind11.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <csignal>
#include <string>
#include <utility>
#include <vector>

#include "diagrams/loader.h"

namespace mechflow::python {

namespace py = pybind11;

// --set values of one call: numbers and expressions, as the command line's
// --set NAME=VALUE and --set NAME=EXPR.
struct Settings {
  std::vector<std::pair<std::string, double>> numbers;
  std::vector<std::pair<std::string, std::string>> expressions;
};
// From a Python mapping {name: number or expression text}; TypeError otherwise.
Settings ToSettings(const py::handle& mapping);
// `base` with `settings` applied after its own (a later --set wins).
diagrams::LoadOptions WithSettings(diagrams::LoadOptions base, const Settings& settings);

// Ctrl-C during a computation that runs without the GIL: while a guard with
// `install` lives, SIGINT only sets the flag (which the simulator polls
// between rows); Python's own handler comes back when it ends, however it
// ends. A signal Python ignores stays ignored. Without `install` (not the
// main thread: Python's handlers belong to that one) the guard does nothing.
class SigintGuard {
 public:
  explicit SigintGuard(bool install);
  ~SigintGuard();
  SigintGuard(const SigintGuard&) = delete;
  SigintGuard& operator=(const SigintGuard&) = delete;
  // The flag to poll: null when not installed.
  const volatile std::sig_atomic_t* flag() const;

 private:
  bool installed_ = false;
  struct sigaction old_ {};
};

void BindModel(py::module_& m);     // python/bindings/model.cc
void BindAnalysis(py::module_& m);  // python/bindings/analysis.cc

// `mechflow check` as data (python/bindings/check.cc).
py::dict CheckToPython(const diagrams::LoadedDiagram& loaded);

// A numpy array that owns `values` (moved, not copied).
py::array_t<double> ToArray(std::vector<double>&& values);

}  // namespace mechflow::python
