// The FMU's C entry points (fmi/fmi2_api.h): each checks its instance and
// hands over to fmi/instance.h; no exception crosses into the importer.

#include <exception>
#include <string>

#include "fmi/fmi2_api.h"
#include "fmi/instance.h"

using mechflow::fmi::Instance;

namespace {

Instance* Of(fmi2Component c) { return static_cast<Instance*>(c); }

// Runs `call` on the instance, turning an escaped exception into fmi2Error.
template <typename Call>
fmi2Status Guarded(fmi2Component c, const char* function, Call call) {
  if (!c) return fmi2Error;
  try {
    return call(*Of(c));
  } catch (const std::exception& e) {
    return Of(c)->Log(fmi2Error, std::string(function) + ": " + e.what());
  }
}

fmi2Status Unsupported(fmi2Component c, const std::string& what) {
  return c ? Of(c)->Log(fmi2Error, what) : fmi2Error;
}

// No Integer, Boolean or String variables: a call naming none is fine.
fmi2Status NoneOfType(fmi2Component c, size_t n, const char* function) {
  return n == 0 ? fmi2OK : Unsupported(c, std::string(function) + ": the FMU has no variables of this type");
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return "default"; }
const char* fmi2GetVersion(void) { return "2.0"; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean, size_t, const fmi2String[]) {
  return c ? fmi2OK : fmi2Error;  // errors and discarded steps are always logged; there is nothing more
}

fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid, fmi2String resources,
                              const fmi2CallbackFunctions* callbacks, fmi2Boolean, fmi2Boolean) {
  const auto fail = [&](const std::string& message) -> fmi2Component {
    if (callbacks && callbacks->logger) {
      std::string escaped;
      for (const char c : message) escaped += c == '%' ? std::string("%%") : std::string(1, c);
      callbacks->logger(callbacks->componentEnvironment, name ? name : "", fmi2Error, "logStatusError",
                        escaped.c_str());
    }
    return nullptr;
  };
  if (!callbacks) return nullptr;
  if (type != fmi2CoSimulation) return fail("fmi2Instantiate: this FMU is for co-simulation only");
  try {
    return new Instance(name ? name : "", guid ? guid : "", resources ? resources : "", *callbacks);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
}

void fmi2FreeInstance(fmi2Component c) { delete Of(c); }

fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean tolerance_defined, fmi2Real tolerance, fmi2Real start,
                               fmi2Boolean stop_defined, fmi2Real stop) {
  return Guarded(c, "fmi2SetupExperiment", [&](Instance& i) {
    return i.SetupExperiment(tolerance_defined, tolerance, start, stop_defined, stop);
  });
}

fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  return Guarded(c, "fmi2EnterInitializationMode", [](Instance& i) { return i.EnterInitializationMode(); });
}
fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return Guarded(c, "fmi2ExitInitializationMode", [](Instance& i) { return i.ExitInitializationMode(); });
}
fmi2Status fmi2Terminate(fmi2Component c) {
  return Guarded(c, "fmi2Terminate", [](Instance& i) { return i.Terminate(); });
}
fmi2Status fmi2Reset(fmi2Component c) {
  return Guarded(c, "fmi2Reset", [](Instance& i) { return i.Reset(); });
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, fmi2Real value[]) {
  return Guarded(c, "fmi2GetReal", [&](Instance& i) { return i.GetReal(vr, n, value); });
}
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n, const fmi2Real value[]) {
  return Guarded(c, "fmi2SetReal", [&](Instance& i) { return i.SetReal(vr, n, value); });
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference[], size_t n, fmi2Integer[]) {
  return NoneOfType(c, n, "fmi2GetInteger");
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t n, fmi2Boolean[]) {
  return NoneOfType(c, n, "fmi2GetBoolean");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t n, fmi2String[]) {
  return NoneOfType(c, n, "fmi2GetString");
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference[], size_t n, const fmi2Integer[]) {
  return NoneOfType(c, n, "fmi2SetInteger");
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t n, const fmi2Boolean[]) {
  return NoneOfType(c, n, "fmi2SetBoolean");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t n, const fmi2String[]) {
  return NoneOfType(c, n, "fmi2SetString");
}

// canGetAndSetFMUstate, canSerializeFMUstate and providesDirectionalDerivative are false
fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate*) {
  return Unsupported(c, "fmi2GetFMUstate: not supported (canGetAndSetFMUstate=\"false\")");
}
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate) {
  return Unsupported(c, "fmi2SetFMUstate: not supported (canGetAndSetFMUstate=\"false\")");
}
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate*) {
  return Unsupported(c, "fmi2FreeFMUstate: not supported (canGetAndSetFMUstate=\"false\")");
}
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
  return Unsupported(c, "fmi2SerializedFMUstateSize: not supported (canSerializeFMUstate=\"false\")");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return Unsupported(c, "fmi2SerializeFMUstate: not supported (canSerializeFMUstate=\"false\")");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return Unsupported(c, "fmi2DeSerializeFMUstate: not supported (canSerializeFMUstate=\"false\")");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2ValueReference[], size_t, const fmi2Real[], fmi2Real[]) {
  return Unsupported(c, "fmi2GetDirectionalDerivative: not supported (providesDirectionalDerivative=\"false\")");
}

// inputs are held over a step (canInterpolateInputs="false", maxOutputDerivativeOrder="0")
fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                       const fmi2Real[]) {
  return Unsupported(c, "fmi2SetRealInputDerivatives: not supported: inputs are held over a step "
                        "(canInterpolateInputs=\"false\")");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t, const fmi2Integer[],
                                        fmi2Real[]) {
  return Unsupported(c, "fmi2GetRealOutputDerivatives: not supported (maxOutputDerivativeOrder=\"0\")");
}

fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean) {
  return Guarded(c, "fmi2DoStep", [&](Instance& i) { return i.DoStep(t, h); });
}
fmi2Status fmi2CancelStep(fmi2Component c) {
  return Unsupported(c, "fmi2CancelStep: steps are never pending (fmi2DoStep returns when done)");
}

// the standard's status queries: the last successful time and whether the run ended
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return c ? fmi2Discard : fmi2Error;  // no asynchronous step whose status could be asked for
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Real* value) {
  if (!c || !value) return fmi2Error;
  if (kind != fmi2LastSuccessfulTime) return fmi2Discard;
  return Of(c)->LastSuccessfulTime(value);
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return c ? fmi2Discard : fmi2Error;
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Boolean* value) {
  if (!c || !value) return fmi2Error;
  if (kind != fmi2Terminated) return fmi2Discard;
  *value = Of(c)->terminated() ? fmi2True : fmi2False;
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return c ? fmi2Discard : fmi2Error;
}

}  // extern "C"
