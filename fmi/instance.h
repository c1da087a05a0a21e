#pragma once
// One instance of an exported FMU: the packed diagram loaded as a
// run::Model, run as a run::Session from fmi2ExitInitializationMode on.
//
// States (FMI 2.0, co-simulation): instantiated -> initialisation (from
// fmi2EnterInitializationMode) -> stepping (fmi2ExitInitializationMode, or
// the first output read in initialisation) -> terminated; a failed step
// leaves it in `step failed` (outputs readable, fmi2Terminate, fmi2Reset).
// Parameters are fixed: set before the run starts, then refused. Inputs are
// held over each fmi2DoStep. The run is the diagram's own, with the Lua
// sandbox on; it writes no file. What is wrong is logged through the
// importer's logger (category logStatusError or logStatusDiscard) and
// returned as fmi2Error or fmi2Discard; no exception leaves the instance.

#include <memory>
#include <string>
#include <vector>

#include "fmi/fmi2_api.h"
#include "fmi/packed_settings.h"
#include "fmi/variables.h"
#include "run/session.h"

namespace mechflow::fmi {

class Instance {
 public:
  // Throws std::runtime_error (the message to log) when the FMU cannot be made.
  Instance(const std::string& name, const std::string& guid, const std::string& resource_location,
           const fmi2CallbackFunctions& callbacks);

  fmi2Status SetupExperiment(bool tolerance_defined, double tolerance, double start, bool stop_defined, double stop);
  fmi2Status EnterInitializationMode();
  fmi2Status ExitInitializationMode();
  fmi2Status DoStep(double t, double h);
  fmi2Status Terminate();
  fmi2Status Reset();
  fmi2Status GetReal(const fmi2ValueReference vr[], std::size_t n, fmi2Real value[]);
  fmi2Status SetReal(const fmi2ValueReference vr[], std::size_t n, const fmi2Real value[]);
  fmi2Status LastSuccessfulTime(double* t) const;
  bool terminated() const { return state_ == State::kTerminated || ended_; }

  // Logs `message` through the importer's logger and returns `status`.
  fmi2Status Log(fmi2Status status, const std::string& message) const;

 private:
  enum class State { kInstantiated, kInitialization, kStepping, kStepFailed, kTerminated };

  void Load();  // the model afresh, every variable at its start value
  // The session, started, with the parameters set so far; fmi2Error when the model refuses one.
  fmi2Status EnsureRunning();
  const Variable* Find(fmi2ValueReference vr) const;

  std::string name_;
  fmi2CallbackFunctions callbacks_;
  std::string resources_;
  PackedSettings settings_;
  std::unique_ptr<run::Model> model_;
  std::unique_ptr<run::Session> session_;
  std::vector<Variable> variables_;
  std::vector<double> values_;  // per variable: inputs and parameters as set, in their units
  State state_ = State::kInstantiated;
  bool tolerance_defined_ = false, stop_defined_ = false, ended_ = false;
  double tolerance_ = 0.0, start_ = 0.0, stop_ = 0.0, last_successful_ = 0.0;
};

// The folder a "file:" URI names ("file:///a/b", "file:/a/b", "file://localhost/a/b"),
// percent-escapes decoded; "" when it names none.
std::string PathOfFileUri(const std::string& uri);

}  // namespace mechflow::fmi
