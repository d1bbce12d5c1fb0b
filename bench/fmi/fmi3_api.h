// The C interface of FMI 3.0 for co-simulation, declared here from the standard's text
// (FMI 3.0, chapters 2.2 and 4.2; modelica/fmi-standard, branch v3.0.x): the platform types,
// the status enums, the callbacks, one function-pointer typedef per function an FMU's library
// exports, and the list of exported names. The export side (bench/fmu) defines the functions
// under these names; the import side loads them with dlsym through the typedefs.
// Plain C so that a master written in C can use it too.
#pragma once

#include <stddef.h>
#include <stdint.h>
#ifndef __cplusplus
#include <stdbool.h>
#endif

#ifdef __cplusplus
extern "C" {
#endif

#define SHAPEBENCH_FMI3_VERSION "3.0"

typedef void* fmi3Instance;             // one FMU instance, opaque to the master
typedef void* fmi3InstanceEnvironment;  // the master's pointer, handed back to its callbacks
typedef void* fmi3FMUState;             // a saved instance state, opaque to the master
typedef uint32_t fmi3ValueReference;
typedef float fmi3Float32;
typedef double fmi3Float64;
typedef int8_t fmi3Int8;
typedef uint8_t fmi3UInt8;
typedef int16_t fmi3Int16;
typedef uint16_t fmi3UInt16;
typedef int32_t fmi3Int32;
typedef uint32_t fmi3UInt32;
typedef int64_t fmi3Int64;
typedef uint64_t fmi3UInt64;
typedef bool fmi3Boolean;
typedef char fmi3Char;
typedef const fmi3Char* fmi3String;
typedef uint8_t fmi3Byte;
typedef const fmi3Byte* fmi3Binary;
typedef bool fmi3Clock;

#define fmi3True true
#define fmi3False false
#define fmi3ClockActive true
#define fmi3ClockInactive false

typedef enum {
  fmi3OK = 0,
  fmi3Warning = 1,
  fmi3Discard = 2,
  fmi3Error = 3,
  fmi3Fatal = 4
} fmi3Status;

typedef enum {
  fmi3Independent = 0,
  fmi3Constant = 1,
  fmi3Fixed = 2,
  fmi3Tunable = 3,
  fmi3Discrete = 4,
  fmi3Dependent = 5
} fmi3DependencyKind;

typedef enum {
  fmi3IntervalNotYetKnown = 0,
  fmi3IntervalUnchanged = 1,
  fmi3IntervalChanged = 2
} fmi3IntervalQualifier;

// Callbacks the master hands to the instantiate functions. The message is plain text (no
// format, unlike FMI 2.0).
typedef void (*fmi3LogMessageCallback)(fmi3InstanceEnvironment environment, fmi3Status status,
                                       fmi3String category, fmi3String message);
typedef void (*fmi3ClockUpdateCallback)(fmi3InstanceEnvironment environment);
typedef void (*fmi3IntermediateUpdateCallback)(
    fmi3InstanceEnvironment environment, fmi3Float64 intermediate_update_time,
    fmi3Boolean intermediate_variable_set_requested, fmi3Boolean intermediate_variable_get_allowed,
    fmi3Boolean intermediate_step_finished, fmi3Boolean can_return_early,
    fmi3Boolean* early_return_requested, fmi3Float64* early_return_time);
typedef void (*fmi3LockPreemptionCallback)(void);
typedef void (*fmi3UnlockPreemptionCallback)(void);

// Version, logging, instances.
typedef const char* (*fmi3GetVersionFn)(void);
typedef fmi3Status (*fmi3SetDebugLoggingFn)(fmi3Instance instance, fmi3Boolean logging_on,
                                            size_t n_categories, const fmi3String categories[]);
typedef fmi3Instance (*fmi3InstantiateModelExchangeFn)(
    fmi3String instance_name, fmi3String instantiation_token, fmi3String resource_path,
    fmi3Boolean visible, fmi3Boolean logging_on, fmi3InstanceEnvironment environment,
    fmi3LogMessageCallback log_message);
typedef fmi3Instance (*fmi3InstantiateCoSimulationFn)(
    fmi3String instance_name, fmi3String instantiation_token, fmi3String resource_path,
    fmi3Boolean visible, fmi3Boolean logging_on, fmi3Boolean event_mode_used,
    fmi3Boolean early_return_allowed, const fmi3ValueReference required_intermediate[],
    size_t n_required_intermediate, fmi3InstanceEnvironment environment,
    fmi3LogMessageCallback log_message, fmi3IntermediateUpdateCallback intermediate_update);
typedef fmi3Instance (*fmi3InstantiateScheduledExecutionFn)(
    fmi3String instance_name, fmi3String instantiation_token, fmi3String resource_path,
    fmi3Boolean visible, fmi3Boolean logging_on, fmi3InstanceEnvironment environment,
    fmi3LogMessageCallback log_message, fmi3ClockUpdateCallback clock_update,
    fmi3LockPreemptionCallback lock_preemption, fmi3UnlockPreemptionCallback unlock_preemption);
typedef void (*fmi3FreeInstanceFn)(fmi3Instance instance);

// State machine.
typedef fmi3Status (*fmi3EnterInitializationModeFn)(fmi3Instance instance,
                                                    fmi3Boolean tolerance_defined,
                                                    fmi3Float64 tolerance, fmi3Float64 start_time,
                                                    fmi3Boolean stop_time_defined,
                                                    fmi3Float64 stop_time);
typedef fmi3Status (*fmi3ExitInitializationModeFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3EnterEventModeFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3TerminateFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3ResetFn)(fmi3Instance instance);

// Getters and setters, one pair per type; the same shape, so one macro writes them.
#define SHAPEBENCH_FMI3_GET_SET(Name, Type)                                                      \
  typedef fmi3Status (*fmi3Get##Name##Fn)(fmi3Instance instance,                              \
                                          const fmi3ValueReference value_references[],        \
                                          size_t n_value_references, Type values[],           \
                                          size_t n_values);                                   \
  typedef fmi3Status (*fmi3Set##Name##Fn)(fmi3Instance instance,                              \
                                          const fmi3ValueReference value_references[],        \
                                          size_t n_value_references, const Type values[],     \
                                          size_t n_values);
SHAPEBENCH_FMI3_GET_SET(Float32, fmi3Float32)
SHAPEBENCH_FMI3_GET_SET(Float64, fmi3Float64)
SHAPEBENCH_FMI3_GET_SET(Int8, fmi3Int8)
SHAPEBENCH_FMI3_GET_SET(UInt8, fmi3UInt8)
SHAPEBENCH_FMI3_GET_SET(Int16, fmi3Int16)
SHAPEBENCH_FMI3_GET_SET(UInt16, fmi3UInt16)
SHAPEBENCH_FMI3_GET_SET(Int32, fmi3Int32)
SHAPEBENCH_FMI3_GET_SET(UInt32, fmi3UInt32)
SHAPEBENCH_FMI3_GET_SET(Int64, fmi3Int64)
SHAPEBENCH_FMI3_GET_SET(UInt64, fmi3UInt64)
SHAPEBENCH_FMI3_GET_SET(Boolean, fmi3Boolean)
SHAPEBENCH_FMI3_GET_SET(String, fmi3String)
#undef SHAPEBENCH_FMI3_GET_SET
typedef fmi3Status (*fmi3GetBinaryFn)(fmi3Instance instance,
                                      const fmi3ValueReference value_references[],
                                      size_t n_value_references, size_t value_sizes[],
                                      fmi3Binary values[], size_t n_values);
typedef fmi3Status (*fmi3SetBinaryFn)(fmi3Instance instance,
                                      const fmi3ValueReference value_references[],
                                      size_t n_value_references, const size_t value_sizes[],
                                      const fmi3Binary values[], size_t n_values);
typedef fmi3Status (*fmi3GetClockFn)(fmi3Instance instance,
                                     const fmi3ValueReference value_references[],
                                     size_t n_value_references, fmi3Clock values[]);
typedef fmi3Status (*fmi3SetClockFn)(fmi3Instance instance,
                                     const fmi3ValueReference value_references[],
                                     size_t n_value_references, const fmi3Clock values[]);

// Structure, saved states, derivatives.
typedef fmi3Status (*fmi3GetNumberOfVariableDependenciesFn)(fmi3Instance instance,
                                                            fmi3ValueReference value_reference,
                                                            size_t* n_dependencies);
typedef fmi3Status (*fmi3GetVariableDependenciesFn)(
    fmi3Instance instance, fmi3ValueReference dependent, size_t element_indices_of_dependent[],
    fmi3ValueReference independents[], size_t element_indices_of_independents[],
    fmi3DependencyKind dependency_kinds[], size_t n_dependencies);
typedef fmi3Status (*fmi3GetFMUStateFn)(fmi3Instance instance, fmi3FMUState* state);
typedef fmi3Status (*fmi3SetFMUStateFn)(fmi3Instance instance, fmi3FMUState state);
typedef fmi3Status (*fmi3FreeFMUStateFn)(fmi3Instance instance, fmi3FMUState* state);
typedef fmi3Status (*fmi3SerializedFMUStateSizeFn)(fmi3Instance instance, fmi3FMUState state,
                                                   size_t* size);
typedef fmi3Status (*fmi3SerializeFMUStateFn)(fmi3Instance instance, fmi3FMUState state,
                                              fmi3Byte serialized[], size_t size);
typedef fmi3Status (*fmi3DeserializeFMUStateFn)(fmi3Instance instance,
                                                const fmi3Byte serialized[], size_t size,
                                                fmi3FMUState* state);
typedef fmi3Status (*fmi3GetDirectionalDerivativeFn)(
    fmi3Instance instance, const fmi3ValueReference unknowns[], size_t n_unknowns,
    const fmi3ValueReference knowns[], size_t n_knowns, const fmi3Float64 seed[], size_t n_seed,
    fmi3Float64 sensitivity[], size_t n_sensitivity);
typedef fmi3Status (*fmi3GetAdjointDerivativeFn)(
    fmi3Instance instance, const fmi3ValueReference unknowns[], size_t n_unknowns,
    const fmi3ValueReference knowns[], size_t n_knowns, const fmi3Float64 seed[], size_t n_seed,
    fmi3Float64 sensitivity[], size_t n_sensitivity);

// Configuration mode, clocks, discrete states.
typedef fmi3Status (*fmi3EnterConfigurationModeFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3ExitConfigurationModeFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3GetIntervalDecimalFn)(fmi3Instance instance,
                                               const fmi3ValueReference value_references[],
                                               size_t n_value_references, fmi3Float64 intervals[],
                                               fmi3IntervalQualifier qualifiers[]);
typedef fmi3Status (*fmi3GetIntervalFractionFn)(fmi3Instance instance,
                                                const fmi3ValueReference value_references[],
                                                size_t n_value_references, fmi3UInt64 counters[],
                                                fmi3UInt64 resolutions[],
                                                fmi3IntervalQualifier qualifiers[]);
typedef fmi3Status (*fmi3GetShiftDecimalFn)(fmi3Instance instance,
                                            const fmi3ValueReference value_references[],
                                            size_t n_value_references, fmi3Float64 shifts[]);
typedef fmi3Status (*fmi3GetShiftFractionFn)(fmi3Instance instance,
                                             const fmi3ValueReference value_references[],
                                             size_t n_value_references, fmi3UInt64 counters[],
                                             fmi3UInt64 resolutions[]);
typedef fmi3Status (*fmi3SetIntervalDecimalFn)(fmi3Instance instance,
                                               const fmi3ValueReference value_references[],
                                               size_t n_value_references,
                                               const fmi3Float64 intervals[]);
typedef fmi3Status (*fmi3SetIntervalFractionFn)(fmi3Instance instance,
                                                const fmi3ValueReference value_references[],
                                                size_t n_value_references,
                                                const fmi3UInt64 counters[],
                                                const fmi3UInt64 resolutions[]);
typedef fmi3Status (*fmi3SetShiftDecimalFn)(fmi3Instance instance,
                                            const fmi3ValueReference value_references[],
                                            size_t n_value_references, const fmi3Float64 shifts[]);
typedef fmi3Status (*fmi3SetShiftFractionFn)(fmi3Instance instance,
                                             const fmi3ValueReference value_references[],
                                             size_t n_value_references,
                                             const fmi3UInt64 counters[],
                                             const fmi3UInt64 resolutions[]);
typedef fmi3Status (*fmi3EvaluateDiscreteStatesFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3UpdateDiscreteStatesFn)(
    fmi3Instance instance, fmi3Boolean* discrete_states_need_update,
    fmi3Boolean* terminate_simulation, fmi3Boolean* nominals_of_continuous_states_changed,
    fmi3Boolean* values_of_continuous_states_changed, fmi3Boolean* next_event_time_defined,
    fmi3Float64* next_event_time);

// Model exchange only (an FMU that is co-simulation only may leave them out; shapebench's
// export defines them anyway, refusing, for masters that resolve every name).
typedef fmi3Status (*fmi3EnterContinuousTimeModeFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3CompletedIntegratorStepFn)(fmi3Instance instance,
                                                    fmi3Boolean no_set_fmu_state_prior,
                                                    fmi3Boolean* enter_event_mode,
                                                    fmi3Boolean* terminate_simulation);
typedef fmi3Status (*fmi3SetTimeFn)(fmi3Instance instance, fmi3Float64 time);
typedef fmi3Status (*fmi3SetContinuousStatesFn)(fmi3Instance instance, const fmi3Float64 states[],
                                                size_t n_states);
typedef fmi3Status (*fmi3GetContinuousStateDerivativesFn)(fmi3Instance instance,
                                                          fmi3Float64 derivatives[],
                                                          size_t n_states);
typedef fmi3Status (*fmi3GetEventIndicatorsFn)(fmi3Instance instance, fmi3Float64 indicators[],
                                               size_t n_indicators);
typedef fmi3Status (*fmi3GetContinuousStatesFn)(fmi3Instance instance, fmi3Float64 states[],
                                                size_t n_states);
typedef fmi3Status (*fmi3GetNominalsOfContinuousStatesFn)(fmi3Instance instance,
                                                          fmi3Float64 nominals[], size_t n_states);
typedef fmi3Status (*fmi3GetNumberOfEventIndicatorsFn)(fmi3Instance instance,
                                                       size_t* n_indicators);
typedef fmi3Status (*fmi3GetNumberOfContinuousStatesFn)(fmi3Instance instance, size_t* n_states);

// Co-simulation.
typedef fmi3Status (*fmi3EnterStepModeFn)(fmi3Instance instance);
typedef fmi3Status (*fmi3GetOutputDerivativesFn)(fmi3Instance instance,
                                                 const fmi3ValueReference value_references[],
                                                 size_t n_value_references,
                                                 const fmi3Int32 orders[], fmi3Float64 values[],
                                                 size_t n_values);
typedef fmi3Status (*fmi3DoStepFn)(fmi3Instance instance, fmi3Float64 current_communication_point,
                                   fmi3Float64 communication_step_size,
                                   fmi3Boolean no_set_fmu_state_prior_to_current_point,
                                   fmi3Boolean* event_handling_needed,
                                   fmi3Boolean* terminate_simulation, fmi3Boolean* early_return,
                                   fmi3Float64* last_successful_time);

// Scheduled execution only.
typedef fmi3Status (*fmi3ActivateModelPartitionFn)(fmi3Instance instance,
                                                   fmi3ValueReference clock_reference,
                                                   fmi3Float64 activation_time);

// Every function a co-simulation FMU's library exports (the common ones and the
// co-simulation ones), by exported name; X(name) is applied to each and name##Fn is its
// pointer type above.
#define SHAPEBENCH_FMI3_CS_FUNCTIONS(X)                                                    \
  X(fmi3GetVersion) X(fmi3SetDebugLogging) X(fmi3InstantiateModelExchange)                 \
  X(fmi3InstantiateCoSimulation) X(fmi3InstantiateScheduledExecution) X(fmi3FreeInstance)  \
  X(fmi3EnterInitializationMode) X(fmi3ExitInitializationMode) X(fmi3EnterEventMode)       \
  X(fmi3Terminate) X(fmi3Reset)                                                            \
  X(fmi3GetFloat32) X(fmi3GetFloat64) X(fmi3GetInt8) X(fmi3GetUInt8) X(fmi3GetInt16)       \
  X(fmi3GetUInt16) X(fmi3GetInt32) X(fmi3GetUInt32) X(fmi3GetInt64) X(fmi3GetUInt64)       \
  X(fmi3GetBoolean) X(fmi3GetString) X(fmi3GetBinary) X(fmi3GetClock)                      \
  X(fmi3SetFloat32) X(fmi3SetFloat64) X(fmi3SetInt8) X(fmi3SetUInt8) X(fmi3SetInt16)       \
  X(fmi3SetUInt16) X(fmi3SetInt32) X(fmi3SetUInt32) X(fmi3SetInt64) X(fmi3SetUInt64)       \
  X(fmi3SetBoolean) X(fmi3SetString) X(fmi3SetBinary) X(fmi3SetClock)                      \
  X(fmi3GetNumberOfVariableDependencies) X(fmi3GetVariableDependencies)                    \
  X(fmi3GetFMUState) X(fmi3SetFMUState) X(fmi3FreeFMUState) X(fmi3SerializedFMUStateSize)  \
  X(fmi3SerializeFMUState) X(fmi3DeserializeFMUState) X(fmi3GetDirectionalDerivative)      \
  X(fmi3GetAdjointDerivative) X(fmi3EnterConfigurationMode) X(fmi3ExitConfigurationMode)   \
  X(fmi3GetIntervalDecimal) X(fmi3GetIntervalFraction) X(fmi3GetShiftDecimal)              \
  X(fmi3GetShiftFraction) X(fmi3SetIntervalDecimal) X(fmi3SetIntervalFraction)             \
  X(fmi3SetShiftDecimal) X(fmi3SetShiftFraction) X(fmi3EvaluateDiscreteStates)             \
  X(fmi3UpdateDiscreteStates) X(fmi3EnterStepMode) X(fmi3GetOutputDerivatives) X(fmi3DoStep)

// The model-exchange and scheduled-execution functions, for libraries that export them all.
#define SHAPEBENCH_FMI3_OTHER_FUNCTIONS(X)                                                   \
  X(fmi3EnterContinuousTimeMode) X(fmi3CompletedIntegratorStep) X(fmi3SetTime)               \
  X(fmi3SetContinuousStates) X(fmi3GetContinuousStateDerivatives) X(fmi3GetEventIndicators)  \
  X(fmi3GetContinuousStates) X(fmi3GetNominalsOfContinuousStates)                            \
  X(fmi3GetNumberOfEventIndicators) X(fmi3GetNumberOfContinuousStates)                       \
  X(fmi3ActivateModelPartition)

#ifdef __cplusplus
}  // extern "C"
#endif
