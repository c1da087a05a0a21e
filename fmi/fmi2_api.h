#pragma once
// The C interface of an FMI 2.0 co-simulation FMU: its types and the
// functions of the common and co-simulation sets, declared from the
// standard's text (FMI 2.0, chapters 2.1 and 4). An importer looks them up
// by these names in binaries/linux64/MODEL.so; their meaning is the
// standard's, what they do here is in fmi/instance.h.

#include <cstddef>

extern "C" {

typedef void* fmi2Component;
typedef void* fmi2ComponentEnvironment;
typedef void* fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char* fmi2String;
typedef char fmi2Byte;

#define fmi2True 1
#define fmi2False 0

typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum { fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated } fmi2StatusKind;

typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment, fmi2String instance_name, fmi2Status, fmi2String category,
                                   fmi2String message, ...);
typedef void* (*fmi2CallbackAllocateMemory)(size_t count, size_t size);
typedef void (*fmi2CallbackFreeMemory)(void*);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment, fmi2Status);

typedef struct {
  fmi2CallbackLogger logger;
  fmi2CallbackAllocateMemory allocateMemory;
  fmi2CallbackFreeMemory freeMemory;
  fmi2StepFinished stepFinished;
  fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

#define MECHFLOW_FMI2_EXPORT __attribute__((visibility("default")))

// the common set
MECHFLOW_FMI2_EXPORT const char* fmi2GetTypesPlatform(void);
MECHFLOW_FMI2_EXPORT const char* fmi2GetVersion(void);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component, fmi2Boolean on, size_t count,
                                                    const fmi2String categories[]);
MECHFLOW_FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String instance_name, fmi2Type, fmi2String guid,
                                                   fmi2String resource_location, const fmi2CallbackFunctions*,
                                                   fmi2Boolean visible, fmi2Boolean logging_on);
MECHFLOW_FMI2_EXPORT void fmi2FreeInstance(fmi2Component);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component, fmi2Boolean tolerance_defined, fmi2Real tolerance,
                                                    fmi2Real start_time, fmi2Boolean stop_time_defined,
                                                    fmi2Real stop_time);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2Terminate(fmi2Component);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2Reset(fmi2Component);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetReal(fmi2Component, const fmi2ValueReference[], size_t, fmi2Real[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetInteger(fmi2Component, const fmi2ValueReference[], size_t, fmi2Integer[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetBoolean(fmi2Component, const fmi2ValueReference[], size_t, fmi2Boolean[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetString(fmi2Component, const fmi2ValueReference[], size_t, fmi2String[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetReal(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Real[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetInteger(fmi2Component, const fmi2ValueReference[], size_t,
                                               const fmi2Integer[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetBoolean(fmi2Component, const fmi2ValueReference[], size_t,
                                               const fmi2Boolean[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetString(fmi2Component, const fmi2ValueReference[], size_t, const fmi2String[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component, fmi2FMUstate*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component, fmi2FMUstate);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component, fmi2FMUstate*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component, fmi2FMUstate, size_t*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component, fmi2FMUstate, fmi2Byte[], size_t);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component, const fmi2Byte[], size_t, fmi2FMUstate*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component, const fmi2ValueReference[], size_t,
                                                             const fmi2ValueReference[], size_t, const fmi2Real[],
                                                             fmi2Real[]);
// the co-simulation set
MECHFLOW_FMI2_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component, const fmi2ValueReference[], size_t,
                                                            const fmi2Integer[], const fmi2Real[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component, const fmi2ValueReference[], size_t,
                                                             const fmi2Integer[], fmi2Real[]);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2DoStep(fmi2Component, fmi2Real current_time, fmi2Real step,
                                           fmi2Boolean no_set_state_before);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2CancelStep(fmi2Component);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetStatus(fmi2Component, const fmi2StatusKind, fmi2Status*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component, const fmi2StatusKind, fmi2Real*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component, const fmi2StatusKind, fmi2Integer*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component, const fmi2StatusKind, fmi2Boolean*);
MECHFLOW_FMI2_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component, const fmi2StatusKind, fmi2String*);

}  // extern "C"
