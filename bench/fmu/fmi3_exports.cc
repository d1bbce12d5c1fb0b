// The FMI 3.0 co-simulation functions of an exported FMU's shared library (only there, as
// fmi2_exports.cc). No event mode, clocks, saved states, derivatives or intermediate
// updates: those functions return fmi3Error with a logged message saying so.
#include <cstring>
#include <exception>
#include <memory>
#include <string>
#include <type_traits>

#include "bench/fmi/fmi3_api.h"
#include "bench/fmu/fmi3_instance.h"

namespace {

using shapebench::bench::fmu::Fmi3Instance;
using shapebench::bench::fmu::Instance;


Fmi3Instance* Of(fmi3Instance c) { return static_cast<Fmi3Instance*>(c); }
fmi3Status Status(bool ok) { return ok ? fmi3OK : fmi3Error; }
fmi3Status Refuse(fmi3Instance c, const char* what) {
  if (c != nullptr && Of(c)->instance) Of(c)->instance->Unsupported(what);
  return fmi3Error;
}
fmi3Status NoneOfType(fmi3Instance c, size_t n, const char* type) {
  if (n == 0) return fmi3OK;
  Of(c)->Log(true, std::string("this FMU has no ") + type + " variables (all are Float64)");
  return fmi3Error;
}
fmi3Status Scalars(fmi3Instance c, size_t n_refs, size_t n_values) {
  if (n_refs == n_values) return fmi3OK;
  Of(c)->Log(true, "every variable of this FMU is a scalar: nValues must equal nValueReferences");
  return fmi3Error;
}

}  // namespace

extern "C" {

const char* fmi3GetVersion(void) { return SHAPEBENCH_FMI3_VERSION; }

fmi3Status fmi3SetDebugLogging(fmi3Instance c, fmi3Boolean logging_on, size_t, const fmi3String[]) {
  Of(c)->logging_on = logging_on;
  return fmi3OK;
}

fmi3Instance fmi3InstantiateCoSimulation(fmi3String, fmi3String token, fmi3String resource_path,
                                         fmi3Boolean, fmi3Boolean logging_on, fmi3Boolean event_mode_used,
                                         fmi3Boolean, const fmi3ValueReference[], size_t,
                                         fmi3InstanceEnvironment environment, fmi3LogMessageCallback log,
                                         fmi3IntermediateUpdateCallback) {
  auto self = std::make_unique<Fmi3Instance>();
  self->environment = environment;
  self->log = log;
  self->logging_on = logging_on;
  if (event_mode_used) {
    self->Log(true, "this FMU has no event mode (hasEventMode is false): instantiate with eventModeUsed false");
    return nullptr;
  }
  try {
    std::string dir = resource_path != nullptr ? resource_path : "";
    while (dir.size() > 1 && dir.back() == '/') dir.pop_back();
    const Fmi3Instance* raw = self.get();
    self->instance = std::make_unique<Instance>(dir, token != nullptr ? token : "",
                                                [raw](bool error, const std::string& m) { raw->Log(error, m); });
  } catch (const std::exception& e) {
    self->Log(true, std::string("instantiation: ") + e.what());
    return nullptr;
  }
  return self.release();
}

fmi3Instance fmi3InstantiateModelExchange(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                          fmi3InstanceEnvironment environment, fmi3LogMessageCallback log) {
  if (log != nullptr) log(environment, fmi3Error, "logStatusError", "this FMU is for co-simulation only");
  return nullptr;
}
fmi3Instance fmi3InstantiateScheduledExecution(fmi3String, fmi3String, fmi3String, fmi3Boolean, fmi3Boolean,
                                               fmi3InstanceEnvironment environment, fmi3LogMessageCallback log,
                                               fmi3ClockUpdateCallback, fmi3LockPreemptionCallback,
                                               fmi3UnlockPreemptionCallback) {
  if (log != nullptr) log(environment, fmi3Error, "logStatusError", "this FMU is for co-simulation only");
  return nullptr;
}
void fmi3FreeInstance(fmi3Instance c) { delete Of(c); }

fmi3Status fmi3EnterInitializationMode(fmi3Instance c, fmi3Boolean, fmi3Float64, fmi3Float64, fmi3Boolean, fmi3Float64) {
  return Status(Of(c)->instance->EnterInitialization());
}
// Without event mode the FMU goes straight to step mode.
fmi3Status fmi3ExitInitializationMode(fmi3Instance c) { return Status(Of(c)->instance->ExitInitialization()); }
fmi3Status fmi3EnterEventMode(fmi3Instance c) { return Refuse(c, "fmi3EnterEventMode (no event mode)"); }
fmi3Status fmi3Terminate(fmi3Instance c) {
  Of(c)->instance->Terminate();
  return fmi3OK;
}
fmi3Status fmi3Reset(fmi3Instance c) {
  Of(c)->instance->Reset();
  return fmi3OK;
}

fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr, fmi3Float64 v[], size_t nv) {
  if (Scalars(c, nvr, nv) != fmi3OK) return fmi3Error;
  return Status(Of(c)->instance->GetReals(vr, nvr, v));
}
fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t nvr, const fmi3Float64 v[], size_t nv) {
  if (Scalars(c, nvr, nv) != fmi3OK) return fmi3Error;
  return Status(Of(c)->instance->SetReals(vr, nvr, v));
}

#define SHAPEBENCH_FMI3_NONE(Name, Type)                                                             \
  fmi3Status fmi3Get##Name(fmi3Instance c, const fmi3ValueReference[], size_t nvr, Type[], size_t) { \
    return NoneOfType(c, nvr, #Name);                                                                \
  }                                                                                                  \
  fmi3Status fmi3Set##Name(fmi3Instance c, const fmi3ValueReference[], size_t nvr, const Type[], size_t) { \
    return NoneOfType(c, nvr, #Name);                                                                \
  }
SHAPEBENCH_FMI3_NONE(Float32, fmi3Float32)
SHAPEBENCH_FMI3_NONE(Int8, fmi3Int8)
SHAPEBENCH_FMI3_NONE(UInt8, fmi3UInt8)
SHAPEBENCH_FMI3_NONE(Int16, fmi3Int16)
SHAPEBENCH_FMI3_NONE(UInt16, fmi3UInt16)
SHAPEBENCH_FMI3_NONE(Int32, fmi3Int32)
SHAPEBENCH_FMI3_NONE(UInt32, fmi3UInt32)
SHAPEBENCH_FMI3_NONE(Int64, fmi3Int64)
SHAPEBENCH_FMI3_NONE(UInt64, fmi3UInt64)
SHAPEBENCH_FMI3_NONE(Boolean, fmi3Boolean)
SHAPEBENCH_FMI3_NONE(String, fmi3String)
#undef SHAPEBENCH_FMI3_NONE
fmi3Status fmi3GetBinary(fmi3Instance c, const fmi3ValueReference[], size_t nvr, size_t[], fmi3Binary[], size_t) {
  return NoneOfType(c, nvr, "Binary");
}
fmi3Status fmi3SetBinary(fmi3Instance c, const fmi3ValueReference[], size_t nvr, const size_t[], const fmi3Binary[], size_t) {
  return NoneOfType(c, nvr, "Binary");
}
fmi3Status fmi3GetClock(fmi3Instance c, const fmi3ValueReference[], size_t nvr, fmi3Clock[]) {
  return NoneOfType(c, nvr, "Clock");
}
fmi3Status fmi3SetClock(fmi3Instance c, const fmi3ValueReference[], size_t nvr, const fmi3Clock[]) {
  return NoneOfType(c, nvr, "Clock");
}

fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean, fmi3Boolean* event_handling_needed,
                      fmi3Boolean* terminate_simulation, fmi3Boolean* early_return, fmi3Float64* last_successful_time) {
  const bool ok = Of(c)->instance->DoStep(t, h);
  if (event_handling_needed != nullptr) *event_handling_needed = fmi3False;
  if (terminate_simulation != nullptr) *terminate_simulation = fmi3False;
  if (early_return != nullptr) *early_return = fmi3False;
  if (last_successful_time != nullptr) *last_successful_time = Of(c)->instance->time();
  return Status(ok);
}

}  // extern "C"

