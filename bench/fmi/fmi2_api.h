// The C interface of FMI 2.0 for co-simulation, declared here from the standard's text
// (FMI 2.0.5, chapters 2.1 and 4.2; modelica/fmi-standard, branch v2.0.x): the platform types,
// the status enums, the callback struct, one function-pointer typedef per function an FMU's
// library exports, and the list of exported names. The export side (bench/fmu) defines the
// functions under these names; the import side loads them with dlsym through the typedefs.
// Plain C so that a master written in C can use it too.
#pragma once

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

// Platform types of the "default" platform (the only one the standard names).
#define SHAPEBENCH_FMI2_TYPES_PLATFORM "default"
#define SHAPEBENCH_FMI2_VERSION "2.0"

typedef void* fmi2Component;             // one FMU instance, opaque to the master
typedef void* fmi2ComponentEnvironment;  // the master's pointer, handed back to its callbacks
typedef void* fmi2FMUstate;              // a saved instance state, opaque to the master
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char* fmi2String;
typedef char fmi2Byte;

#define fmi2True 1
#define fmi2False 0

typedef enum {
  fmi2OK = 0,
  fmi2Warning = 1,
  fmi2Discard = 2,
  fmi2Error = 3,
  fmi2Fatal = 4,
  fmi2Pending = 5
} fmi2Status;

typedef enum { fmi2ModelExchange = 0, fmi2CoSimulation = 1 } fmi2Type;

typedef enum {
  fmi2DoStepStatus = 0,
  fmi2PendingStatus = 1,
  fmi2LastSuccessfulTime = 2,
  fmi2Terminated = 3
} fmi2StatusKind;

// Callbacks the master hands to fmi2Instantiate. The logger's message is a printf format.
typedef void (*fmi2CallbackLogger)(fmi2ComponentEnvironment environment, fmi2String instance_name,
                                   fmi2Status status, fmi2String category, fmi2String message,
                                   ...);
typedef void* (*fmi2CallbackAllocateMemory)(size_t count, size_t size);
typedef void (*fmi2CallbackFreeMemory)(void* pointer);
typedef void (*fmi2StepFinished)(fmi2ComponentEnvironment environment, fmi2Status status);

// The standard packs its structs to 8 bytes; on x86-64 this is the natural layout anyway.
typedef struct {
  fmi2CallbackLogger logger;
  fmi2CallbackAllocateMemory allocateMemory;
  fmi2CallbackFreeMemory freeMemory;
  fmi2StepFinished stepFinished;  // only for asynchronous doStep; NULL is allowed
  fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef struct {
  fmi2Boolean newDiscreteStatesNeeded;
  fmi2Boolean terminateSimulation;
  fmi2Boolean nominalsOfContinuousStatesChanged;
  fmi2Boolean valuesOfContinuousStatesChanged;
  fmi2Boolean nextEventTimeDefined;
  fmi2Real nextEventTime;
} fmi2EventInfo;

// Common functions (model exchange and co-simulation).
typedef const char* (*fmi2GetTypesPlatformFn)(void);
typedef const char* (*fmi2GetVersionFn)(void);
typedef fmi2Status (*fmi2SetDebugLoggingFn)(fmi2Component c, fmi2Boolean logging_on,
                                            size_t n_categories, const fmi2String categories[]);
typedef fmi2Component (*fmi2InstantiateFn)(fmi2String instance_name, fmi2Type fmu_type,
                                           fmi2String guid, fmi2String resource_location,
                                           const fmi2CallbackFunctions* functions,
                                           fmi2Boolean visible, fmi2Boolean logging_on);
typedef void (*fmi2FreeInstanceFn)(fmi2Component c);
typedef fmi2Status (*fmi2SetupExperimentFn)(fmi2Component c, fmi2Boolean tolerance_defined,
                                            fmi2Real tolerance, fmi2Real start_time,
                                            fmi2Boolean stop_time_defined, fmi2Real stop_time);
typedef fmi2Status (*fmi2EnterInitializationModeFn)(fmi2Component c);
typedef fmi2Status (*fmi2ExitInitializationModeFn)(fmi2Component c);
typedef fmi2Status (*fmi2TerminateFn)(fmi2Component c);
typedef fmi2Status (*fmi2ResetFn)(fmi2Component c);

typedef fmi2Status (*fmi2GetRealFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                    fmi2Real value[]);
typedef fmi2Status (*fmi2GetIntegerFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       fmi2Integer value[]);
typedef fmi2Status (*fmi2GetBooleanFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       fmi2Boolean value[]);
typedef fmi2Status (*fmi2GetStringFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                      fmi2String value[]);
typedef fmi2Status (*fmi2SetRealFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                    const fmi2Real value[]);
typedef fmi2Status (*fmi2SetIntegerFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Integer value[]);
typedef fmi2Status (*fmi2SetBooleanFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                       const fmi2Boolean value[]);
typedef fmi2Status (*fmi2SetStringFn)(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                      const fmi2String value[]);

typedef fmi2Status (*fmi2GetFMUstateFn)(fmi2Component c, fmi2FMUstate* state);
typedef fmi2Status (*fmi2SetFMUstateFn)(fmi2Component c, fmi2FMUstate state);
typedef fmi2Status (*fmi2FreeFMUstateFn)(fmi2Component c, fmi2FMUstate* state);
typedef fmi2Status (*fmi2SerializedFMUstateSizeFn)(fmi2Component c, fmi2FMUstate state,
                                                   size_t* size);
typedef fmi2Status (*fmi2SerializeFMUstateFn)(fmi2Component c, fmi2FMUstate state,
                                              fmi2Byte serialized[], size_t size);
typedef fmi2Status (*fmi2DeSerializeFMUstateFn)(fmi2Component c, const fmi2Byte serialized[],
                                                size_t size, fmi2FMUstate* state);
typedef fmi2Status (*fmi2GetDirectionalDerivativeFn)(
    fmi2Component c, const fmi2ValueReference unknown_refs[], size_t n_unknown,
    const fmi2ValueReference known_refs[], size_t n_known, const fmi2Real d_known[],
    fmi2Real d_unknown[]);

// Model exchange only (a co-simulation FMU may leave them out; shapebench's export defines
// them anyway, refusing, for masters that resolve every name).
typedef fmi2Status (*fmi2EnterEventModeFn)(fmi2Component c);
typedef fmi2Status (*fmi2NewDiscreteStatesFn)(fmi2Component c, fmi2EventInfo* event_info);
typedef fmi2Status (*fmi2EnterContinuousTimeModeFn)(fmi2Component c);
typedef fmi2Status (*fmi2CompletedIntegratorStepFn)(fmi2Component c,
                                                    fmi2Boolean no_set_fmu_state_prior,
                                                    fmi2Boolean* enter_event_mode,
                                                    fmi2Boolean* terminate_simulation);
typedef fmi2Status (*fmi2SetTimeFn)(fmi2Component c, fmi2Real time);
typedef fmi2Status (*fmi2SetContinuousStatesFn)(fmi2Component c, const fmi2Real x[], size_t nx);
typedef fmi2Status (*fmi2GetDerivativesFn)(fmi2Component c, fmi2Real derivatives[], size_t nx);
typedef fmi2Status (*fmi2GetEventIndicatorsFn)(fmi2Component c, fmi2Real indicators[],
                                               size_t ni);
typedef fmi2Status (*fmi2GetContinuousStatesFn)(fmi2Component c, fmi2Real x[], size_t nx);
typedef fmi2Status (*fmi2GetNominalsOfContinuousStatesFn)(fmi2Component c, fmi2Real nominals[],
                                                          size_t nx);

// Co-simulation functions.
typedef fmi2Status (*fmi2SetRealInputDerivativesFn)(fmi2Component c, const fmi2ValueReference vr[],
                                                    size_t nvr, const fmi2Integer order[],
                                                    const fmi2Real value[]);
typedef fmi2Status (*fmi2GetRealOutputDerivativesFn)(fmi2Component c,
                                                     const fmi2ValueReference vr[], size_t nvr,
                                                     const fmi2Integer order[], fmi2Real value[]);
typedef fmi2Status (*fmi2DoStepFn)(fmi2Component c, fmi2Real current_communication_point,
                                   fmi2Real communication_step_size,
                                   fmi2Boolean no_set_fmu_state_prior_to_current_point);
typedef fmi2Status (*fmi2CancelStepFn)(fmi2Component c);
typedef fmi2Status (*fmi2GetStatusFn)(fmi2Component c, const fmi2StatusKind kind,
                                      fmi2Status* value);
typedef fmi2Status (*fmi2GetRealStatusFn)(fmi2Component c, const fmi2StatusKind kind,
                                          fmi2Real* value);
typedef fmi2Status (*fmi2GetIntegerStatusFn)(fmi2Component c, const fmi2StatusKind kind,
                                             fmi2Integer* value);
typedef fmi2Status (*fmi2GetBooleanStatusFn)(fmi2Component c, const fmi2StatusKind kind,
                                             fmi2Boolean* value);
typedef fmi2Status (*fmi2GetStringStatusFn)(fmi2Component c, const fmi2StatusKind kind,
                                            fmi2String* value);

// Every function a co-simulation FMU's library exports, by exported name; X(name) is applied
// to each and name##Fn is its pointer type above, so a loader can write
// `#define LOAD(name) name##Fn name = (name##Fn)dlsym(handle, #name);`.
#define SHAPEBENCH_FMI2_CS_FUNCTIONS(X) \
  X(fmi2GetTypesPlatform)               \
  X(fmi2GetVersion)                     \
  X(fmi2SetDebugLogging)                \
  X(fmi2Instantiate)                    \
  X(fmi2FreeInstance)                   \
  X(fmi2SetupExperiment)                \
  X(fmi2EnterInitializationMode)        \
  X(fmi2ExitInitializationMode)         \
  X(fmi2Terminate)                      \
  X(fmi2Reset)                          \
  X(fmi2GetReal)                        \
  X(fmi2GetInteger)                     \
  X(fmi2GetBoolean)                     \
  X(fmi2GetString)                      \
  X(fmi2SetReal)                        \
  X(fmi2SetInteger)                     \
  X(fmi2SetBoolean)                     \
  X(fmi2SetString)                      \
  X(fmi2GetFMUstate)                    \
  X(fmi2SetFMUstate)                    \
  X(fmi2FreeFMUstate)                   \
  X(fmi2SerializedFMUstateSize)         \
  X(fmi2SerializeFMUstate)              \
  X(fmi2DeSerializeFMUstate)            \
  X(fmi2GetDirectionalDerivative)       \
  X(fmi2SetRealInputDerivatives)        \
  X(fmi2GetRealOutputDerivatives)       \
  X(fmi2DoStep)                         \
  X(fmi2CancelStep)                     \
  X(fmi2GetStatus)                      \
  X(fmi2GetRealStatus)                  \
  X(fmi2GetIntegerStatus)               \
  X(fmi2GetBooleanStatus)               \
  X(fmi2GetStringStatus)

// The model-exchange functions, for libraries that export them all.
#define SHAPEBENCH_FMI2_ME_FUNCTIONS(X)                                                     \
  X(fmi2EnterEventMode) X(fmi2NewDiscreteStates) X(fmi2EnterContinuousTimeMode)             \
  X(fmi2CompletedIntegratorStep) X(fmi2SetTime) X(fmi2SetContinuousStates)                  \
  X(fmi2GetDerivatives) X(fmi2GetEventIndicators) X(fmi2GetContinuousStates)                \
  X(fmi2GetNominalsOfContinuousStates)

#ifdef __cplusplus
}  // extern "C"
#endif
