// The FMI 2.0 co-simulation functions of an exported FMU's shared library (only there: the
// library target of bench/CMakeLists.txt, whose version script exports nothing else). Each
// translates to Instance (fmu_instance.h); what this FMU does not support (saved states,
// directional and input derivatives, asynchronous steps, model exchange) returns fmi2Error
// with a logged message saying so.
#include <exception>
#include <memory>
#include <string>
#include <type_traits>

#include "bench/fmi/fmi2_api.h"
#include "bench/fmu/fmu_instance.h"

namespace {

using shapebench::bench::fmu::Instance;

struct Fmi2Instance {
  std::unique_ptr<Instance> instance;
  std::string name;
  fmi2CallbackFunctions callbacks{};
  bool logging_on = false;

  void Log(bool error, const std::string& message) const {
    if (callbacks.logger == nullptr || (!error && !logging_on)) return;
    callbacks.logger(callbacks.componentEnvironment, name.c_str(), error ? fmi2Error : fmi2OK,
                     error ? "logStatusError" : "logInfo", "%s", message.c_str());
  }
};

Fmi2Instance* Of(fmi2Component c) { return static_cast<Fmi2Instance*>(c); }
fmi2Status Status(bool ok) { return ok ? fmi2OK : fmi2Error; }
fmi2Status Refuse(fmi2Component c, const char* what) {
  if (c != nullptr && Of(c)->instance) Of(c)->instance->Unsupported(what);
  return fmi2Error;
}
// This FMU has Real variables only: other types take no value reference.
fmi2Status NoneOfType(fmi2Component c, size_t nvr, const char* type) {
  if (nvr == 0) return fmi2OK;
  Of(c)->Log(true, std::string("this FMU has no ") + type + " variables (all are Real)");
  return fmi2Error;
}

}  // namespace

extern "C" {

const char* fmi2GetTypesPlatform(void) { return SHAPEBENCH_FMI2_TYPES_PLATFORM; }
const char* fmi2GetVersion(void) { return SHAPEBENCH_FMI2_VERSION; }

fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean logging_on, size_t, const fmi2String[]) {
  Of(c)->logging_on = logging_on != fmi2False;
  return fmi2OK;
}

fmi2Component fmi2Instantiate(fmi2String instance_name, fmi2Type fmu_type, fmi2String guid,
                              fmi2String resource_location, const fmi2CallbackFunctions* functions,
                              fmi2Boolean, fmi2Boolean logging_on) {
  auto self = std::make_unique<Fmi2Instance>();
  self->name = instance_name != nullptr ? instance_name : "";
  if (functions != nullptr) self->callbacks = *functions;
  self->logging_on = logging_on != fmi2False;
  if (fmu_type != fmi2CoSimulation) {
    self->Log(true, "this FMU is for co-simulation only, not model exchange");
    return nullptr;
  }
  try {
    const Fmi2Instance* raw = self.get();
    self->instance = std::make_unique<Instance>(
        shapebench::bench::fmu::ResourceDirFromUri(resource_location != nullptr ? resource_location : ""),
        guid != nullptr ? guid : "", [raw](bool error, const std::string& m) { raw->Log(error, m); });
  } catch (const std::exception& e) {
    self->Log(true, std::string("instantiation: ") + e.what());
    return nullptr;
  }
  return self.release();
}

void fmi2FreeInstance(fmi2Component c) { delete Of(c); }

fmi2Status fmi2SetupExperiment(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real) {
  return fmi2OK;
}
fmi2Status fmi2EnterInitializationMode(fmi2Component c) { return Status(Of(c)->instance->EnterInitialization()); }
fmi2Status fmi2ExitInitializationMode(fmi2Component c) { return Status(Of(c)->instance->ExitInitialization()); }
fmi2Status fmi2Terminate(fmi2Component c) {
  Of(c)->instance->Terminate();
  return fmi2OK;
}
fmi2Status fmi2Reset(fmi2Component c) {
  Of(c)->instance->Reset();
  return fmi2OK;
}

fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, fmi2Real value[]) {
  return Status(Of(c)->instance->GetReals(vr, nvr, value));
}
fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr, const fmi2Real value[]) {
  return Status(Of(c)->instance->SetReals(vr, nvr, value));
}
fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Integer[]) {
  return NoneOfType(c, nvr, "Integer");
}
fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2Boolean[]) {
  return NoneOfType(c, nvr, "Boolean");
}
fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, fmi2String[]) {
  return NoneOfType(c, nvr, "String");
}
fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Integer[]) {
  return NoneOfType(c, nvr, "Integer");
}
fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2Boolean[]) {
  return NoneOfType(c, nvr, "Boolean");
}
fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference[], size_t nvr, const fmi2String[]) {
  return NoneOfType(c, nvr, "String");
}

fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate*) { return Refuse(c, "fmi2GetFMUstate"); }
fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate) { return Refuse(c, "fmi2SetFMUstate"); }
fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate*) { return Refuse(c, "fmi2FreeFMUstate"); }
fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate, size_t*) {
  return Refuse(c, "fmi2SerializedFMUstateSize");
}
fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate, fmi2Byte[], size_t) {
  return Refuse(c, "fmi2SerializeFMUstate");
}
fmi2Status fmi2DeSerializeFMUstate(fmi2Component c, const fmi2Byte[], size_t, fmi2FMUstate*) {
  return Refuse(c, "fmi2DeSerializeFMUstate");
}
fmi2Status fmi2GetDirectionalDerivative(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2ValueReference[], size_t, const fmi2Real[], fmi2Real[]) {
  return Refuse(c, "fmi2GetDirectionalDerivative");
}

fmi2Status fmi2SetRealInputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                       const fmi2Integer[], const fmi2Real[]) {
  return Refuse(c, "fmi2SetRealInputDerivatives (the inputs are held over a step)");
}
fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c, const fmi2ValueReference[], size_t,
                                        const fmi2Integer[], fmi2Real[]) {
  return Refuse(c, "fmi2GetRealOutputDerivatives");
}
fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean) {
  return Status(Of(c)->instance->DoStep(t, h));
}
fmi2Status fmi2CancelStep(fmi2Component c) { return Refuse(c, "fmi2CancelStep (doStep is synchronous)"); }
fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind, fmi2Status*) {
  return Refuse(c, "fmi2GetStatus (doStep is synchronous)");
}
fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Real* value) {
  if (kind != fmi2LastSuccessfulTime) return Refuse(c, "fmi2GetRealStatus of this kind");
  *value = Of(c)->instance->time();
  return fmi2OK;
}
fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind, fmi2Integer*) {
  return Refuse(c, "fmi2GetIntegerStatus");
}
fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind kind, fmi2Boolean* value) {
  if (kind != fmi2Terminated) return Refuse(c, "fmi2GetBooleanStatus of this kind");
  *value = fmi2False;  // the FMU never asks to end the simulation
  return fmi2OK;
}
fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind, fmi2String*) {
  return Refuse(c, "fmi2GetStringStatus");
}

// Model exchange: not this FMU's interface (fmi2Instantiate refuses it already).
fmi2Status fmi2EnterEventMode(fmi2Component c) { return Refuse(c, "model exchange"); }
fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo*) { return Refuse(c, "model exchange"); }
fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) { return Refuse(c, "model exchange"); }
fmi2Status fmi2CompletedIntegratorStep(fmi2Component c, fmi2Boolean, fmi2Boolean*, fmi2Boolean*) {
  return Refuse(c, "model exchange");
}
fmi2Status fmi2SetTime(fmi2Component c, fmi2Real) { return Refuse(c, "model exchange"); }
fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real[], size_t) { return Refuse(c, "model exchange"); }
fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real[], size_t) { return Refuse(c, "model exchange"); }
fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real[], size_t) { return Refuse(c, "model exchange"); }
fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real[], size_t) { return Refuse(c, "model exchange"); }
fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real[], size_t) {
  return Refuse(c, "model exchange");
}

}  // extern "C"

// Every definition has the type the declarations give it (bench/fmi/fmi2_api.h).
#define SHAPEBENCH_FMI2_SAME_TYPE(name) \
  static_assert(std::is_same<decltype(&name), name##Fn>::value, #name " differs from its declaration");
SHAPEBENCH_FMI2_CS_FUNCTIONS(SHAPEBENCH_FMI2_SAME_TYPE)
SHAPEBENCH_FMI2_ME_FUNCTIONS(SHAPEBENCH_FMI2_SAME_TYPE)
#undef SHAPEBENCH_FMI2_SAME_TYPE
