#include "fmi/instance.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "blocks/support/input_file.h"
#include "diagrams/units.h"
#include "mech/errors.h"

namespace mechflow::fmi {
namespace {

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// Times given by the importer that stand for one instant (t + h summed in another order).
bool SameTime(double a, double b) { return std::abs(a - b) <= 1e-12 * std::max({1.0, std::abs(a), std::abs(b)}); }

}  // namespace

std::string PathOfFileUri(const std::string& uri) {
  std::string rest;
  if (uri.rfind("file://", 0) == 0) {
    rest = uri.substr(7);
    if (rest.rfind("localhost/", 0) == 0) rest = rest.substr(9);
    if (rest.empty() || rest[0] != '/') return "";
  } else if (uri.rfind("file:/", 0) == 0) {
    rest = uri.substr(5);
  } else {
    return "";
  }
  std::string path;
  for (std::size_t i = 0; i < rest.size(); ++i) {
    if (rest[i] == '%' && i + 2 < rest.size() && std::isxdigit(static_cast<unsigned char>(rest[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(rest[i + 2]))) {
      path += static_cast<char>(std::stoi(rest.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      path += rest[i];
    }
  }
  return path;
}

Instance::Instance(const std::string& name, const std::string& guid, const std::string& resource_location,
                   const fmi2CallbackFunctions& callbacks)
    : name_(name), callbacks_(callbacks) {
  resources_ = PathOfFileUri(resource_location);
  if (resources_.empty())
    throw std::runtime_error("fmi2Instantiate: the resource location '" + resource_location +
                             "' is no file: URI; the FMU needs its unpacked resources folder");
  const std::string settings_file = (std::filesystem::path(resources_) / "mechflow.txt").string();
  settings_ = PackedSettings::Parse(blocks::ReadInputFile(settings_file, "the FMU's settings"), settings_file);
  if (guid != settings_.guid)
    throw std::runtime_error("fmi2Instantiate: GUID " + guid + " is not this FMU's (" + settings_.guid +
                             "): its modelDescription.xml belongs to another export");
  diagrams::UseUnitsDatabase((std::filesystem::path(resources_) / "udunits" / "udunits2.xml").string());
  Load();
}

void Instance::Load() {
  session_.reset();
  // the sandbox on, nothing read beyond the resources folder
  model_ = std::make_unique<run::Model>((std::filesystem::path(resources_) / settings_.diagram).string(),
                                        settings_.Options(resources_));
  variables_ = CollectVariables(model_->Loaded());
  values_.clear();
  for (const Variable& v : variables_) values_.push_back(v.start);
  const blocks::SolverOptions& solver = model_->Loaded().solver;
  start_ = solver.t_start;
  last_successful_ = start_;
  ended_ = false;
  tolerance_defined_ = stop_defined_ = false;  // fmi2SetupExperiment again after fmi2Reset
  state_ = State::kInstantiated;
}

fmi2Status Instance::Log(fmi2Status status, const std::string& message) const {
  if (callbacks_.logger) {
    std::string escaped;  // the logger takes a format
    for (const char c : message) escaped += c == '%' ? std::string("%%") : std::string(1, c);
    callbacks_.logger(callbacks_.componentEnvironment, name_.c_str(), status,
                      status == fmi2Discard ? "logStatusDiscard" : "logStatusError", escaped.c_str());
  }
  return status;
}

const Variable* Instance::Find(fmi2ValueReference vr) const {
  return vr >= 1 && vr <= variables_.size() ? &variables_[vr - 1] : nullptr;
}

fmi2Status Instance::SetupExperiment(bool tolerance_defined, double tolerance, double start, bool stop_defined,
                                     double stop) {
  if (state_ != State::kInstantiated) return Log(fmi2Error, "fmi2SetupExperiment: only before initialization mode");
  const double t_start = model_->Loaded().solver.t_start;
  if (!SameTime(start, t_start))
    return Log(fmi2Error, "fmi2SetupExperiment: the diagram starts at t = " + Number(t_start) +
                              " s (its <solver t_start>); a start time of " + Number(start) + " s cannot be used");
  if (tolerance_defined && !(tolerance > 0.0 && tolerance < 1.0))
    return Log(fmi2Error, "fmi2SetupExperiment: tolerance " + Number(tolerance) + " is not from 0 to 1");
  if (stop_defined && !(stop > t_start))
    return Log(fmi2Error, "fmi2SetupExperiment: stop time " + Number(stop) + " is not after the start");
  tolerance_defined_ = tolerance_defined;
  tolerance_ = tolerance;
  stop_defined_ = stop_defined;
  stop_ = stop;
  return fmi2OK;
}

fmi2Status Instance::EnterInitializationMode() {
  if (state_ != State::kInstantiated) return Log(fmi2Error, "fmi2EnterInitializationMode: only after fmi2Instantiate");
  state_ = State::kInitialization;
  return fmi2OK;
}

fmi2Status Instance::EnsureRunning() {
  if (session_) return fmi2OK;
  try {
    for (std::size_t k = 0; k < variables_.size(); ++k)
      if (variables_[k].causality == Causality::kParameter && values_[k] != variables_[k].start)
        model_->Set(variables_[k].name, values_[k]);
    run::RunOptions options;
    if (stop_defined_) options.t_end = stop_;
    if (tolerance_defined_) options.rtol = tolerance_;
    session_ = std::make_unique<run::Session>(*model_, options);
    for (std::size_t k = 0; k < variables_.size(); ++k)
      if (variables_[k].causality == Causality::kInput) session_->SetInput(variables_[k].index, values_[k]);
    session_->Start();
  } catch (const std::exception& e) {
    session_.reset();
    return Log(fmi2Error, std::string("the run cannot start: ") + e.what());
  }
  if (!session_->ok()) {
    state_ = State::kStepFailed;
    return Log(fmi2Error, "the run failed at its start: " + session_->failure());
  }
  return fmi2OK;
}

fmi2Status Instance::ExitInitializationMode() {
  if (state_ != State::kInitialization)
    return Log(fmi2Error, "fmi2ExitInitializationMode: only in initialization mode");
  const fmi2Status status = EnsureRunning();
  if (status == fmi2OK) state_ = State::kStepping;
  return status;
}

fmi2Status Instance::DoStep(double t, double h) {
  if (state_ != State::kStepping)
    return Log(fmi2Error, state_ == State::kStepFailed ? "fmi2DoStep: an earlier step failed; fmi2Reset starts again"
                                                       : "fmi2DoStep: only after fmi2ExitInitializationMode");
  if (ended_) return Log(fmi2Error, "fmi2DoStep: the run has ended (the diagram's control script stopped it)");
  if (!SameTime(t, session_->time()))
    return Log(fmi2Error, "fmi2DoStep: the step starts at t = " + Number(t) + " s, but the FMU is at t = " +
                              Number(session_->time()) + " s");
  if (!(h > 0.0)) return Log(fmi2Error, "fmi2DoStep: the step size " + Number(h) + " is not > 0");
  const double t_end = session_->solver().t_end;
  double target = session_->time() + h;
  if (SameTime(target, t_end)) target = t_end;
  if (target > t_end)
    return Log(fmi2Error, "fmi2DoStep: t + h = " + Number(target) + " s is past the stop time " + Number(t_end) +
                              " s (fmi2SetupExperiment's stopTime, else the diagram's <solver t_end>)");
  if (session_->AdvanceTo(target)) {
    last_successful_ = session_->time();
    return fmi2OK;
  }
  last_successful_ = session_->time();
  if (session_->ok()) {  // the control script stopped it
    ended_ = true;
    return Log(fmi2Discard, "the run ended at t = " + Number(session_->time()) + " s: " + session_->failure());
  }
  state_ = State::kStepFailed;
  return Log(fmi2Discard, "the integration failed; time reached t = " + Number(session_->time()) +
                              " s: " + session_->failure());
}

fmi2Status Instance::Terminate() {
  if (state_ != State::kStepping && state_ != State::kStepFailed)
    return Log(fmi2Error, "fmi2Terminate: only after fmi2ExitInitializationMode");
  if (session_) session_->Finish();
  state_ = State::kTerminated;
  return fmi2OK;
}

fmi2Status Instance::Reset() {
  try {
    Load();
  } catch (const std::exception& e) {
    return Log(fmi2Error, std::string("fmi2Reset: ") + e.what());
  }
  return fmi2OK;
}

fmi2Status Instance::GetReal(const fmi2ValueReference vr[], std::size_t n, fmi2Real value[]) {
  for (std::size_t k = 0; k < n; ++k) {
    const Variable* v = Find(vr[k]);
    if (!v) return Log(fmi2Error, "fmi2GetReal: no variable has value reference " + std::to_string(vr[k]));
    if (v->causality != Causality::kOutput) {
      value[k] = values_[v->value_reference - 1];
      continue;
    }
    if (state_ == State::kInstantiated || state_ == State::kTerminated)
      return Log(fmi2Error, "fmi2GetReal: output '" + v->name + "' is known from initialization mode until "
                                                                 "fmi2Terminate");
    if (const fmi2Status s = EnsureRunning(); s != fmi2OK) return s;
    value[k] = session_->Row()[v->index];
  }
  return fmi2OK;
}

fmi2Status Instance::SetReal(const fmi2ValueReference vr[], std::size_t n, const fmi2Real value[]) {
  for (std::size_t k = 0; k < n; ++k) {
    const Variable* v = Find(vr[k]);
    if (!v) return Log(fmi2Error, "fmi2SetReal: no variable has value reference " + std::to_string(vr[k]));
    if (v->causality == Causality::kOutput) return Log(fmi2Error, "fmi2SetReal: '" + v->name + "' is an output");
    if (!std::isfinite(value[k])) return Log(fmi2Error, "fmi2SetReal: '" + v->name + "' is given " + Number(value[k]));
    if (v->causality == Causality::kParameter && session_)
      return Log(fmi2Error, "fmi2SetReal: parameter '" + v->name +
                                "' is fixed: set it before fmi2ExitInitializationMode (and before reading an output)");
    if (state_ == State::kTerminated || state_ == State::kStepFailed)
      return Log(fmi2Error, "fmi2SetReal: the run has ended; fmi2Reset starts again");
    values_[v->value_reference - 1] = value[k];
    if (v->causality == Causality::kInput && session_) session_->SetInput(v->index, value[k]);
  }
  return fmi2OK;
}

fmi2Status Instance::LastSuccessfulTime(double* t) const {
  *t = last_successful_;
  return fmi2OK;
}

}  // namespace mechflow::fmi
