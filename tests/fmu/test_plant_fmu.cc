// The test plant FMU (FMI 2.0 and 3.0 co-simulation, both sets of functions in one
// library): one mass on a spring and a dashpot whose base is accelerated,
//   m x'' + c x' + k x = -m a_base   (x: deflection of the mass relative to the base),
// stepped exactly under the held input (the underdamped oscillator's closed form), so that
// the import master can be tested without shapebench's own export. Outputs besides the
// deflection: the largest |x| over the last step (its stationary points in closed form),
// the static compliance -m/k (deflection per held m/s^2) and the free vibration's amplitude about rest. fail_at_s >= 0
// makes a step reaching that time return Error; a non-positive mass or stiffness, or a
// damping ratio >= 1, makes initialisation return Error (with a logged message).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>
#include <string>

#include "bench/fmi/fmi2_api.h"
#include "bench/fmi/fmi3_api.h"

namespace {

enum Ref : unsigned {
  kMass, kStiffness, kDamping, kFailAt, kInput, kDeflection, kVelocity, kStepPeak, kCompliance, kResidual, kCount
};

struct Plant {
  double value[kCount] = {1.0, 24674.011002723397, 9.42477796076938, -1.0, 0, 0, 0, 0, 0, 0};
  std::string name;
  // 2.0: the callbacks; 3.0: the environment and its logger.
  const fmi2CallbackFunctions* callbacks2 = nullptr;
  void* environment3 = nullptr;
  fmi3LogMessageCallback logger3 = nullptr;

  void Log(int status, const std::string& message) const {
    if (callbacks2 != nullptr && callbacks2->logger != nullptr) {
      callbacks2->logger(callbacks2->componentEnvironment, name.c_str(), static_cast<fmi2Status>(status), "logError",
                         "%s", message.c_str());
    } else if (logger3 != nullptr) {
      logger3(environment3, static_cast<fmi3Status>(status), "logError", message.c_str());
    }
  }
  double Omega() const { return std::sqrt(value[kStiffness] / value[kMass]); }
  double Sigma() const { return value[kDamping] / (2.0 * value[kMass]); }

  // 0 OK, 3 Error (logged).
  int Initialize() {
    const double m = value[kMass], k = value[kStiffness], c = value[kDamping];
    if (!(m > 0.0) || !(k > 0.0) || !(c >= 0.0)) {
      Log(3, "mass_kg and stiffness_n_m must be > 0 and damping_n_s_m >= 0");
      return 3;
    }
    if (!(Sigma() < Omega())) {
      Log(3, "the damping ratio must be < 1 (an underdamped oscillator)");
      return 3;
    }
    value[kCompliance] = -m / k;  // deflection per held m/s^2: the mass lags
    Update();
    return 0;
  }
  void Update() {
    const double x = value[kDeflection], v = value[kVelocity], s = Sigma(), w = Omega();
    const double wd = std::sqrt(w * w - s * s);
    value[kResidual] = std::hypot(x, (v + s * x) / wd);
  }
  // The state after h under the held input, and the largest |x| over [0, h].
  int Step(double t, double h) {
    if (value[kFailAt] >= 0.0 && t + h >= value[kFailAt]) {
      Log(3, "fail_at_s reached at t = " + std::to_string(t + h) + " s");
      return 3;
    }
    const double s = Sigma(), w = Omega(), wd = std::sqrt(w * w - s * s);
    const double eq = -value[kInput] / (w * w);  // the equilibrium under the held input
    const double y0 = value[kDeflection] - eq, v0 = value[kVelocity];
    const double b = (v0 + s * y0) / wd;
    const auto y_at = [&](double tau) { return std::exp(-s * tau) * (y0 * std::cos(wd * tau) + b * std::sin(wd * tau)); };
    double peak = std::max(std::abs(value[kDeflection]), 0.0);
    // v = e^(-s t) (P cos(wd t) + Q sin(wd t)) is 0 where wd t = atan2(Q, P) + pi/2 + n pi.
    const double p = v0, q = -(w * w * y0 + s * v0) / wd;
    if (p != 0.0 || q != 0.0) {
      double theta = std::fmod(std::atan2(q, p) + 0.5 * M_PI, M_PI);
      if (theta <= 0.0) theta += M_PI;
      for (; theta < wd * h; theta += M_PI) peak = std::max(peak, std::abs(eq + y_at(theta / wd)));
    }
    const double c = std::cos(wd * h), sn = std::sin(wd * h), e = std::exp(-s * h);
    value[kDeflection] = eq + e * (y0 * c + b * sn);
    value[kVelocity] = e * (v0 * c - (w * w * y0 + s * v0) / wd * sn);
    value[kStepPeak] = std::max(peak, std::abs(value[kDeflection]));
    Update();
    return 0;
  }
  int Get(const unsigned* refs, size_t n, double* out) const {
    for (size_t i = 0; i < n; ++i) {
      if (refs[i] >= kCount) return 3;
      out[i] = value[refs[i]];
    }
    return 0;
  }
  int Set(const unsigned* refs, size_t n, const double* in) {
    for (size_t i = 0; i < n; ++i) {
      if (refs[i] > kInput) {
        Log(3, "value reference " + std::to_string(refs[i]) + " cannot be set");
        return 3;
      }
      value[refs[i]] = in[i];
    }
    return 0;
  }
};

Plant* AsPlant(void* instance) { return static_cast<Plant*>(instance); }

}  // namespace

extern "C" {

// FMI 2.0.
__attribute__((visibility("default"))) const char* fmi2GetTypesPlatform(void) { return "default"; }
__attribute__((visibility("default"))) const char* fmi2GetVersion(void) { return "2.0"; }
__attribute__((visibility("default"))) fmi2Component fmi2Instantiate(fmi2String name, fmi2Type type, fmi2String guid,
                                                                     fmi2String, const fmi2CallbackFunctions* functions,
                                                                     fmi2Boolean, fmi2Boolean) {
  if (type != fmi2CoSimulation || guid == nullptr || std::strcmp(guid, "{shapebench-test-plant-1}") != 0) return nullptr;
  Plant* plant = new (std::nothrow) Plant;
  if (plant == nullptr) return nullptr;
  plant->name = name == nullptr ? "" : name;
  plant->callbacks2 = functions;
  return plant;
}
__attribute__((visibility("default"))) void fmi2FreeInstance(fmi2Component c) { delete AsPlant(c); }
__attribute__((visibility("default"))) fmi2Status fmi2SetupExperiment(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real,
                                                                      fmi2Boolean, fmi2Real) {
  return fmi2OK;
}
__attribute__((visibility("default"))) fmi2Status fmi2EnterInitializationMode(fmi2Component) { return fmi2OK; }
__attribute__((visibility("default"))) fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  return static_cast<fmi2Status>(AsPlant(c)->Initialize());
}
__attribute__((visibility("default"))) fmi2Status fmi2Terminate(fmi2Component) { return fmi2OK; }
__attribute__((visibility("default"))) fmi2Status fmi2Reset(fmi2Component) { return fmi2Error; }
__attribute__((visibility("default"))) fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                              fmi2Real value[]) {
  return static_cast<fmi2Status>(AsPlant(c)->Get(vr, n, value));
}
__attribute__((visibility("default"))) fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t n,
                                                              const fmi2Real value[]) {
  return static_cast<fmi2Status>(AsPlant(c)->Set(vr, n, value));
}
__attribute__((visibility("default"))) fmi2Status fmi2DoStep(fmi2Component c, fmi2Real t, fmi2Real h, fmi2Boolean) {
  return static_cast<fmi2Status>(AsPlant(c)->Step(t, h));
}

// FMI 3.0.
__attribute__((visibility("default"))) const char* fmi3GetVersion(void) { return "3.0"; }
__attribute__((visibility("default"))) fmi3Instance fmi3InstantiateCoSimulation(
    fmi3String name, fmi3String token, fmi3String, fmi3Boolean, fmi3Boolean, fmi3Boolean, fmi3Boolean,
    const fmi3ValueReference[], size_t, fmi3InstanceEnvironment environment, fmi3LogMessageCallback log,
    fmi3IntermediateUpdateCallback) {
  if (token == nullptr || std::strcmp(token, "{shapebench-test-plant-1}") != 0) return nullptr;
  Plant* plant = new (std::nothrow) Plant;
  if (plant == nullptr) return nullptr;
  plant->name = name == nullptr ? "" : name;
  plant->environment3 = environment;
  plant->logger3 = log;
  return plant;
}
__attribute__((visibility("default"))) void fmi3FreeInstance(fmi3Instance c) { delete AsPlant(c); }
__attribute__((visibility("default"))) fmi3Status fmi3EnterInitializationMode(fmi3Instance, fmi3Boolean, fmi3Float64,
                                                                              fmi3Float64, fmi3Boolean, fmi3Float64) {
  return fmi3OK;
}
__attribute__((visibility("default"))) fmi3Status fmi3ExitInitializationMode(fmi3Instance c) {
  return static_cast<fmi3Status>(AsPlant(c)->Initialize());
}
__attribute__((visibility("default"))) fmi3Status fmi3Terminate(fmi3Instance) { return fmi3OK; }
__attribute__((visibility("default"))) fmi3Status fmi3GetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                                                                 fmi3Float64 value[], size_t) {
  return static_cast<fmi3Status>(AsPlant(c)->Get(vr, n, value));
}
__attribute__((visibility("default"))) fmi3Status fmi3SetFloat64(fmi3Instance c, const fmi3ValueReference vr[], size_t n,
                                                                 const fmi3Float64 value[], size_t) {
  return static_cast<fmi3Status>(AsPlant(c)->Set(vr, n, value));
}
__attribute__((visibility("default"))) fmi3Status fmi3DoStep(fmi3Instance c, fmi3Float64 t, fmi3Float64 h, fmi3Boolean,
                                                             fmi3Boolean* event, fmi3Boolean* terminate,
                                                             fmi3Boolean* early, fmi3Float64* last) {
  *event = fmi3False;
  *terminate = fmi3False;
  *early = fmi3False;
  const int status = AsPlant(c)->Step(t, h);
  *last = status == 0 ? t + h : t;
  return static_cast<fmi3Status>(status);
}

}  // extern "C"
