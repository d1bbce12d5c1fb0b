// The FMI 3.0 functions an exported FMU has but does not support (fmi3_exports.cc has the
// rest): each returns fmi3Error and logs what it is.
#include <type_traits>

#include "bench/fmi/fmi3_api.h"
#include "bench/fmu/fmi3_instance.h"

namespace {

fmi3Status Refused(fmi3Instance c, const char* what) {
  const auto* self = static_cast<const shapebench::bench::fmu::Fmi3Instance*>(c);
  if (self != nullptr && self->instance) self->instance->Unsupported(what);
  return fmi3Error;
}

}  // namespace

#define SHAPEBENCH_REFUSE(name, ...) \
  fmi3Status name(fmi3Instance c, ##__VA_ARGS__) { return Refused(c, #name); }

extern "C" {

SHAPEBENCH_REFUSE(fmi3GetNumberOfVariableDependencies, fmi3ValueReference, size_t*)
SHAPEBENCH_REFUSE(fmi3GetVariableDependencies, fmi3ValueReference, size_t[], fmi3ValueReference[], size_t[],
                  fmi3DependencyKind[], size_t)
SHAPEBENCH_REFUSE(fmi3GetFMUState, fmi3FMUState*)
SHAPEBENCH_REFUSE(fmi3SetFMUState, fmi3FMUState)
SHAPEBENCH_REFUSE(fmi3FreeFMUState, fmi3FMUState*)
SHAPEBENCH_REFUSE(fmi3SerializedFMUStateSize, fmi3FMUState, size_t*)
SHAPEBENCH_REFUSE(fmi3SerializeFMUState, fmi3FMUState, fmi3Byte[], size_t)
SHAPEBENCH_REFUSE(fmi3DeserializeFMUState, const fmi3Byte[], size_t, fmi3FMUState*)
SHAPEBENCH_REFUSE(fmi3GetDirectionalDerivative, const fmi3ValueReference[], size_t, const fmi3ValueReference[],
                  size_t, const fmi3Float64[], size_t, fmi3Float64[], size_t)
SHAPEBENCH_REFUSE(fmi3GetAdjointDerivative, const fmi3ValueReference[], size_t, const fmi3ValueReference[], size_t,
                  const fmi3Float64[], size_t, fmi3Float64[], size_t)
SHAPEBENCH_REFUSE(fmi3EnterConfigurationMode)
SHAPEBENCH_REFUSE(fmi3ExitConfigurationMode)
SHAPEBENCH_REFUSE(fmi3GetIntervalDecimal, const fmi3ValueReference[], size_t, fmi3Float64[], fmi3IntervalQualifier[])
SHAPEBENCH_REFUSE(fmi3GetIntervalFraction, const fmi3ValueReference[], size_t, fmi3UInt64[], fmi3UInt64[],
                  fmi3IntervalQualifier[])
SHAPEBENCH_REFUSE(fmi3GetShiftDecimal, const fmi3ValueReference[], size_t, fmi3Float64[])
SHAPEBENCH_REFUSE(fmi3GetShiftFraction, const fmi3ValueReference[], size_t, fmi3UInt64[], fmi3UInt64[])
SHAPEBENCH_REFUSE(fmi3SetIntervalDecimal, const fmi3ValueReference[], size_t, const fmi3Float64[])
SHAPEBENCH_REFUSE(fmi3SetIntervalFraction, const fmi3ValueReference[], size_t, const fmi3UInt64[], const fmi3UInt64[])
SHAPEBENCH_REFUSE(fmi3SetShiftDecimal, const fmi3ValueReference[], size_t, const fmi3Float64[])
SHAPEBENCH_REFUSE(fmi3SetShiftFraction, const fmi3ValueReference[], size_t, const fmi3UInt64[], const fmi3UInt64[])
SHAPEBENCH_REFUSE(fmi3EvaluateDiscreteStates)
SHAPEBENCH_REFUSE(fmi3UpdateDiscreteStates, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*, fmi3Boolean*,
                  fmi3Float64*)
SHAPEBENCH_REFUSE(fmi3EnterStepMode)
SHAPEBENCH_REFUSE(fmi3GetOutputDerivatives, const fmi3ValueReference[], size_t, const fmi3Int32[], fmi3Float64[],
                  size_t)
// Model exchange and scheduled execution: not this FMU's interfaces.
SHAPEBENCH_REFUSE(fmi3EnterContinuousTimeMode)
SHAPEBENCH_REFUSE(fmi3CompletedIntegratorStep, fmi3Boolean, fmi3Boolean*, fmi3Boolean*)
SHAPEBENCH_REFUSE(fmi3SetTime, fmi3Float64)
SHAPEBENCH_REFUSE(fmi3SetContinuousStates, const fmi3Float64[], size_t)
SHAPEBENCH_REFUSE(fmi3GetContinuousStateDerivatives, fmi3Float64[], size_t)
SHAPEBENCH_REFUSE(fmi3GetEventIndicators, fmi3Float64[], size_t)
SHAPEBENCH_REFUSE(fmi3GetContinuousStates, fmi3Float64[], size_t)
SHAPEBENCH_REFUSE(fmi3GetNominalsOfContinuousStates, fmi3Float64[], size_t)
SHAPEBENCH_REFUSE(fmi3GetNumberOfEventIndicators, size_t*)
SHAPEBENCH_REFUSE(fmi3GetNumberOfContinuousStates, size_t*)
SHAPEBENCH_REFUSE(fmi3ActivateModelPartition, fmi3ValueReference, fmi3Float64)

}  // extern "C"

#undef SHAPEBENCH_REFUSE

// Every definition of both files has the type the declarations give it (fmi3_api.h).
#define SHAPEBENCH_FMI3_SAME_TYPE(name) \
  static_assert(std::is_same<decltype(&name), name##Fn>::value, #name " differs from its declaration");
extern "C" {
#define SHAPEBENCH_FMI3_DECLARE(name) extern std::remove_pointer_t<name##Fn> name;
SHAPEBENCH_FMI3_CS_FUNCTIONS(SHAPEBENCH_FMI3_DECLARE)
#undef SHAPEBENCH_FMI3_DECLARE
}
SHAPEBENCH_FMI3_CS_FUNCTIONS(SHAPEBENCH_FMI3_SAME_TYPE)
SHAPEBENCH_FMI3_OTHER_FUNCTIONS(SHAPEBENCH_FMI3_SAME_TYPE)
#undef SHAPEBENCH_FMI3_SAME_TYPE
