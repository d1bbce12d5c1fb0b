#include "bench/fmi/fmu_instance.h"

#include <dlfcn.h>

#include <cstdarg>
#include <cstdio>

#include "bench/fmi/fmi2_api.h"
#include "bench/fmi/fmi3_api.h"
#include "common/format.h"
#include "model/integrator.h"

namespace shapebench::bench {
namespace {

constexpr std::size_t kKeptMessages = 8;

const char* StatusWord(bool v3, int status) {
  static const char* const kWords2[] = {"fmi2OK", "fmi2Warning", "fmi2Discard", "fmi2Error", "fmi2Fatal", "fmi2Pending"};
  static const char* const kWords3[] = {"fmi3OK", "fmi3Warning", "fmi3Discard", "fmi3Error", "fmi3Fatal"};
  const int count = v3 ? 5 : 6;
  if (status < 0 || status >= count) return "an unknown status";
  return v3 ? kWords3[status] : kWords2[status];
}

// FMI 2.0's logger: a printf format and its arguments.
void Fmi2Logger(fmi2ComponentEnvironment environment, fmi2String /*instance*/, fmi2Status status,
                fmi2String category, fmi2String message, ...) {
  if (environment == nullptr || message == nullptr) return;
  char text[1024];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message, args);
  va_end(args);
  static_cast<FmuInstance*>(environment)->Log(status, category == nullptr ? "" : category, text);
}

void Fmi3Logger(fmi3InstanceEnvironment environment, fmi3Status status, fmi3String category,
                fmi3String message) {
  if (environment == nullptr || message == nullptr) return;
  static_cast<FmuInstance*>(environment)->Log(status, category == nullptr ? "" : category, message);
}

}  // namespace

// The functions the master calls, per version (the others are never resolved).
struct FmuInstance::Api {
  fmi2CallbackFunctions callbacks2{};
#define SHAPEBENCH_FMI_POINTER(name) name##Fn name = nullptr;
#define SHAPEBENCH_FMI2_MASTER(X)                                                                  \
  X(fmi2Instantiate) X(fmi2FreeInstance) X(fmi2SetupExperiment) X(fmi2EnterInitializationMode) \
  X(fmi2ExitInitializationMode) X(fmi2Terminate) X(fmi2GetReal) X(fmi2SetReal) X(fmi2DoStep)
#define SHAPEBENCH_FMI3_MASTER(X)                                                               \
  X(fmi3InstantiateCoSimulation) X(fmi3FreeInstance) X(fmi3EnterInitializationMode)           \
  X(fmi3ExitInitializationMode) X(fmi3Terminate) X(fmi3GetFloat64) X(fmi3SetFloat64) X(fmi3DoStep)
  SHAPEBENCH_FMI2_MASTER(SHAPEBENCH_FMI_POINTER)
  SHAPEBENCH_FMI3_MASTER(SHAPEBENCH_FMI_POINTER)
#undef SHAPEBENCH_FMI_POINTER
};

void FmuInstance::LibraryCloser::operator()(void* handle) const { dlclose(handle); }

FmuInstance::FmuInstance(std::shared_ptr<const UnpackedFmu> fmu,
                         const std::vector<std::pair<unsigned, double>>& parameters, double stop_time_s)
    : fmu_(std::move(fmu)), v3_(fmu_->description().version == FmiVersion::k3), api_(std::make_unique<Api>()) {
  // RTLD_LOCAL: two FMUs (or two copies of one) keep their own symbols and globals.
  library_.reset(dlopen(fmu_->binary().c_str(), RTLD_NOW | RTLD_LOCAL));
  if (!library_) {
    const char* why = dlerror();
    throw FmuError(fmu_->fmu_path() + ": its binary cannot be loaded: " + (why ? why : "dlopen failed"));
  }
  Resolve();
  Instantiate();
  try {
    Initialize(parameters, stop_time_s);
  } catch (...) {
    // A refused initialisation (fmi2ExitInitializationMode returned Error, say) leaves an
    // instance the destructor will not see: the constructor did not finish.
    Release();
    throw;
  }
}

FmuInstance::~FmuInstance() { Release(); }

void FmuInstance::Release() {
  if (instance_ == nullptr || fatal_) return;  // after Fatal no function may be called
  if (v3_) {
    if (initialized_ && !failed_) api_->fmi3Terminate(instance_);
    api_->fmi3FreeInstance(instance_);
  } else {
    if (initialized_ && !failed_) api_->fmi2Terminate(instance_);
    api_->fmi2FreeInstance(instance_);
  }
  instance_ = nullptr;
}

void FmuInstance::Resolve() {
  Api& api = *api_;
  const std::string file = fmu_->fmu_path();
  void* library = library_.get();
  const auto resolve = [&](const char* name) {
    void* symbol = dlsym(library, name);
    if (symbol == nullptr) {
      throw FmuError(file + ": its binary does not export " + name + " (FMI " + fmu_->description().fmi_version +
                     " co-simulation)");
    }
    return symbol;
  };
#define SHAPEBENCH_FMI_RESOLVE(name) api.name = reinterpret_cast<name##Fn>(resolve(#name));
  if (v3_) {
    SHAPEBENCH_FMI3_MASTER(SHAPEBENCH_FMI_RESOLVE)
  } else {
    SHAPEBENCH_FMI2_MASTER(SHAPEBENCH_FMI_RESOLVE)
  }
#undef SHAPEBENCH_FMI_RESOLVE
}

void FmuInstance::Instantiate() {
  const ModelDescription& md = fmu_->description();
  const std::string name = md.model_identifier;
  if (v3_) {
    // FMI 3.0 wants the resources folder's path with a trailing separator.
    const std::string resources = fmu_->resources_dir() + "/";
    instance_ = api_->fmi3InstantiateCoSimulation(name.c_str(), md.token.c_str(), resources.c_str(), fmi3False,
                                                  fmi3True, fmi3False, fmi3False, nullptr, 0, this, Fmi3Logger,
                                                  nullptr);
  } else {
    api_->callbacks2 = {Fmi2Logger, std::calloc, std::free, nullptr, this};
    instance_ = api_->fmi2Instantiate(name.c_str(), fmi2CoSimulation, md.token.c_str(),
                                      fmu_->resources_uri().c_str(), &api_->callbacks2, fmi2False, fmi2True);
  }
  if (instance_ == nullptr) {
    std::string text = (v3_ ? "fmi3InstantiateCoSimulation" : "fmi2Instantiate") +
                       std::string(" returned no instance (FMU ") + fmu_->fmu_path() + ")";
    for (const std::string& line : log_) text += "; the FMU logged: " + line;
    throw model::SolverError("FMU_ERROR", text);
  }
}

void FmuInstance::Initialize(const std::vector<std::pair<unsigned, double>>& parameters, double stop_time_s) {
  std::vector<unsigned> refs;
  std::vector<double> values;
  for (const auto& [ref, value] : parameters) {
    refs.push_back(ref);
    values.push_back(value);
  }
  if (v3_) {
    if (!refs.empty()) SetReal(refs, values.data());
    Check(api_->fmi3EnterInitializationMode(instance_, fmi3False, 0.0, 0.0, fmi3True, stop_time_s),
          "fmi3EnterInitializationMode", 0.0);
    initialized_ = true;
    Check(api_->fmi3ExitInitializationMode(instance_), "fmi3ExitInitializationMode", 0.0);
  } else {
    Check(api_->fmi2SetupExperiment(instance_, fmi2False, 0.0, 0.0, fmi2True, stop_time_s), "fmi2SetupExperiment",
          0.0);
    if (!refs.empty()) SetReal(refs, values.data());
    Check(api_->fmi2EnterInitializationMode(instance_), "fmi2EnterInitializationMode", 0.0);
    initialized_ = true;
    Check(api_->fmi2ExitInitializationMode(instance_), "fmi2ExitInitializationMode", 0.0);
  }
}

void FmuInstance::SetReal(const std::vector<unsigned>& refs, const double* values) {
  if (v3_) {
    Check(api_->fmi3SetFloat64(instance_, refs.data(), refs.size(), values, refs.size()), "fmi3SetFloat64");
  } else {
    Check(api_->fmi2SetReal(instance_, refs.data(), refs.size(), values), "fmi2SetReal");
  }
}

void FmuInstance::GetReal(const std::vector<unsigned>& refs, double* values) {
  if (v3_) {
    Check(api_->fmi3GetFloat64(instance_, refs.data(), refs.size(), values, refs.size()), "fmi3GetFloat64");
  } else {
    Check(api_->fmi2GetReal(instance_, refs.data(), refs.size(), values), "fmi2GetReal");
  }
}

void FmuInstance::DoStep(double t, double h) {
  if (v3_) {
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    fmi3Float64 last = t;
    Check(api_->fmi3DoStep(instance_, t, h, fmi3True, &event, &terminate, &early, &last), "fmi3DoStep", t);
    if (terminate) {
      failed_ = true;
      throw model::SolverError("FMU_ERROR", "fmi3DoStep at t = " + FormatNumber(t) + " s asked to terminate the "
                                                "simulation (FMU " + fmu_->fmu_path() + ")");
    }
  } else {
    Check(api_->fmi2DoStep(instance_, t, h, fmi2True), "fmi2DoStep", t);
  }
}

void FmuInstance::Log(int status, const std::string& category, const std::string& message) {
  log_.push_back(std::string(StatusWord(v3_, status)) + (category.empty() ? "" : " [" + category + "]") + ": " +
                 message);
  if (log_.size() > kKeptMessages) log_.pop_front();
}

void FmuInstance::Check(int status, const char* function, double t) {
  if (status == 0 || status == 1) return;  // OK, Warning
  failed_ = true;
  fatal_ = status == 4;
  std::string text = std::string(function) + " returned " + StatusWord(v3_, status);
  if (t >= 0.0) text += " at t = " + FormatNumber(t) + " s";
  text += " (FMU " + fmu_->fmu_path() + ")";
  if (log_.empty()) text += "; the FMU logged nothing";
  for (const std::string& line : log_) text += "; the FMU logged " + line;
  throw model::SolverError("FMU_ERROR", text);
}

}  // namespace shapebench::bench
