// Exported FMUs driven by a master that uses only dlopen and the FMI C API
// (bench/fmi/fmi2_api.h, fmi3_api.h): the controller's command samples against the
// period-boundary rows of run's full trace.csv, bit for bit (issue 40, must-show 2); the
// machine's deflection against the native exact run's; a parameter; a refused step.
#include <dlfcn.h>

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/fmi/fmi2_api.h"
#include "bench/fmi/fmi3_api.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/fmu_files.h"

namespace shapebench::bench::fmu_master_test {
namespace {

using testing::RunCli;
using testing::ScratchDir;

std::string g_last_log;  // the last message an FMU logged

void Fmi2Log(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String message, ...) {
  char text[2048];
  va_list args;
  va_start(args, message);
  std::vsnprintf(text, sizeof text, message, args);
  va_end(args);
  g_last_log = text;
}
void Fmi3Log(fmi3InstanceEnvironment, fmi3Status, fmi3String, fmi3String message) { g_last_log = message; }

// One unpacked FMU: its library and its variables' value references by name.
struct LoadedFmu {
  void* library = nullptr;
  std::string resources;
  std::string token;
  std::vector<std::string> names;  // by value reference
  ~LoadedFmu() {
    if (library != nullptr) dlclose(library);
  }
  unsigned Ref(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return static_cast<unsigned>(i);
    }
    ADD_FAILURE() << "no variable " << name;
    return 0;
  }
  template <typename F>
  F Get(const char* name) const {
    void* symbol = dlsym(library, name);
    EXPECT_NE(symbol, nullptr) << name;
    return reinterpret_cast<F>(symbol);
  }
};

std::string Attribute(const std::string& xml, std::size_t at, const std::string& name) {
  const std::size_t start = xml.find(" " + name + "=\"", at) + name.size() + 3;
  return xml.substr(start, xml.find('"', start) - start);
}

// Writes the FMU with `shapebench fmu`, checks it against the schema, unpacks and loads it.
void ExportAndLoad(const ScratchDir& dir, const std::vector<std::string>& args, int version, LoadedFmu* fmu) {
  const std::string out = dir.File("part.fmu");
  std::vector<std::string> command = {"fmu"};
  command.insert(command.end(), args.begin(), args.end());
  command.insert(command.end(), {"--out", out, "--fmi-version", std::to_string(version)});
  const testing::CliResult result = RunCli(command, kSourceDir);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const std::filesystem::path unpacked = dir.path() / ("unpacked" + std::to_string(version));
  ASSERT_TRUE(testing::UnpackFmu(out, unpacked));
  const std::string description = (unpacked / "modelDescription.xml").string();
  const testing::CliResult schema = testing::ValidateAgainstSchema(description, version);
  ASSERT_EQ(schema.exit_code, 0) << schema.err;
  const std::string xml = testing::ReadText(description);
  fmu->token = Attribute(xml, 0, version == 3 ? "instantiationToken" : "guid");
  for (std::size_t at = xml.find(version == 3 ? "<Float64 " : "<ScalarVariable "); at != std::string::npos;
       at = xml.find(version == 3 ? "<Float64 " : "<ScalarVariable ", at + 1)) {
    fmu->names.push_back(Attribute(xml, at, "name"));
  }
  const std::string so = (unpacked / "binaries" / (version == 3 ? "x86_64-linux" : "linux64") / "part.so").string();
  // RTLD_NODELETE: the library stays mapped after dlclose, so what its own statics hold
  // (built once per load, freed at exit) stays reachable for LeakSanitizer.
  fmu->library = dlopen(so.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
  ASSERT_NE(fmu->library, nullptr) << dlerror();
  fmu->resources = (unpacked / "resources").string();
}

// A stepped FMU of either version behind one face: set inputs, step, read outputs.
class Master {
 public:
  Master(const LoadedFmu& fmu, int version) : fmu_(fmu), version_(version) {
    if (version == 2) {
      callbacks_ = {Fmi2Log, nullptr, nullptr, nullptr, nullptr};
      instance_ = fmu.Get<fmi2InstantiateFn>("fmi2Instantiate")("m", fmi2CoSimulation, fmu.token.c_str(),
                                                                ("file://" + fmu.resources).c_str(), &callbacks_,
                                                                fmi2False, fmi2False);
    } else {
      instance_ = fmu.Get<fmi3InstantiateCoSimulationFn>("fmi3InstantiateCoSimulation")(
          "m", fmu.token.c_str(), (fmu.resources + "/").c_str(), fmi3False, fmi3False, fmi3False, fmi3False,
          nullptr, 0, nullptr, Fmi3Log, nullptr);
    }
    EXPECT_NE(instance_, nullptr) << g_last_log;
  }
  ~Master() {
    if (instance_ == nullptr) return;
    if (version_ == 2) {
      fmu_.Get<fmi2TerminateFn>("fmi2Terminate")(instance_);
      fmu_.Get<fmi2FreeInstanceFn>("fmi2FreeInstance")(instance_);
    } else {
      fmu_.Get<fmi3TerminateFn>("fmi3Terminate")(instance_);
      fmu_.Get<fmi3FreeInstanceFn>("fmi3FreeInstance")(instance_);
    }
  }
  bool ok() const { return instance_ != nullptr; }
  bool Initialize() {
    if (version_ == 2) {
      return fmu_.Get<fmi2SetupExperimentFn>("fmi2SetupExperiment")(instance_, fmi2False, 0, 0, fmi2False, 0) == fmi2OK &&
             fmu_.Get<fmi2EnterInitializationModeFn>("fmi2EnterInitializationMode")(instance_) == fmi2OK &&
             fmu_.Get<fmi2ExitInitializationModeFn>("fmi2ExitInitializationMode")(instance_) == fmi2OK;
    }
    return fmu_.Get<fmi3EnterInitializationModeFn>("fmi3EnterInitializationMode")(instance_, fmi3False, 0, 0, fmi3False, 0) == fmi3OK &&
           fmu_.Get<fmi3ExitInitializationModeFn>("fmi3ExitInitializationMode")(instance_) == fmi3OK;
  }
  // Sets a variable in instantiated mode (a parameter) or in step mode (an input).
  bool Set(const std::string& name, double value) {
    const unsigned ref = fmu_.Ref(name);
    if (version_ == 2) return fmu_.Get<fmi2SetRealFn>("fmi2SetReal")(instance_, &ref, 1, &value) == fmi2OK;
    return fmu_.Get<fmi3SetFloat64Fn>("fmi3SetFloat64")(instance_, &ref, 1, &value, 1) == fmi3OK;
  }
  double Value(const std::string& name) const {
    const unsigned ref = fmu_.Ref(name);
    double value = std::nan("");
    if (version_ == 2) {
      EXPECT_EQ(fmu_.Get<fmi2GetRealFn>("fmi2GetReal")(instance_, &ref, 1, &value), fmi2OK);
    } else {
      EXPECT_EQ(fmu_.Get<fmi3GetFloat64Fn>("fmi3GetFloat64")(instance_, &ref, 1, &value, 1), fmi3OK);
    }
    return value;
  }
  bool Step(double t, double h) {
    if (version_ == 2) return fmu_.Get<fmi2DoStepFn>("fmi2DoStep")(instance_, t, h, fmi2True) == fmi2OK;
    fmi3Boolean event = fmi3False, terminate = fmi3False, early = fmi3False;
    fmi3Float64 last = 0.0;
    return fmu_.Get<fmi3DoStepFn>("fmi3DoStep")(instance_, t, h, fmi3True, &event, &terminate, &early, &last) == fmi3OK;
  }

 private:
  const LoadedFmu& fmu_;
  int version_;
  fmi2CallbackFunctions callbacks_{};
  void* instance_ = nullptr;
};

// trace.csv's rows as numbers, by column name.
struct TraceCsv {
  std::vector<std::string> columns;
  std::vector<std::vector<double>> rows;
  std::size_t Column(const std::string& name) const {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      if (columns[c] == name) return c;
    }
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

TraceCsv ReadTrace(const std::string& path) {
  TraceCsv trace;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_NE(line[0], '#') << "trace.csv is decimated: " << line;
  std::stringstream header(line);
  for (std::string name; std::getline(header, name, ',');) trace.columns.push_back(name);
  while (std::getline(in, line)) {
    std::vector<double> row;
    std::stringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) row.push_back(std::strtod(field.c_str(), nullptr));
    trace.rows.push_back(row);
  }
  return trace;
}

// The rows at t_k = k dt (the trace has `substeps` rows a period, the first at t = 0).
std::size_t SubstepsOf(const TraceCsv& trace, double dt) {
  for (std::size_t i = 1; i < trace.rows.size(); ++i) {
    if (std::abs(trace.rows[i][0] - dt) < 1e-15) return i;
  }
  ADD_FAILURE() << "no row at one period";
  return 1;
}

}  // namespace

// Tests that the exported controller FMU (FMI 2.0 and 3.0), stepped one interpolation period
// at a time by a dlopen master, gives at every period boundary of run's full trace.csv its
// commanded position per axis and the view's velocity and acceleration, bit for bit, on the
// demo (a shaped move along Y) and on the circle test (two axes).
TEST(FmuMaster, ControllerCommandEqualsTheTraceBitForBit) {
  for (const char* scenario : {"configs/demo.yaml", "configs/scenarios/circle_test.yaml"}) {
    ScratchDir dir;
    const testing::CliResult run = RunCli({"run", scenario, "--out", dir.File("run")}, kSourceDir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const TraceCsv trace = ReadTrace(dir.File("run/trace.csv"));
    const double dt = 0.001;
    const std::size_t substeps = SubstepsOf(trace, dt);
    const bool single_axis = std::string(scenario) == "configs/demo.yaml";
    for (int version : {2, 3}) {
      SCOPED_TRACE(std::string(scenario) + " FMI " + std::to_string(version));
      LoadedFmu fmu;
      ExportAndLoad(dir, {scenario, "--part", "controller"}, version, &fmu);
      Master master(fmu, version);
      ASSERT_TRUE(master.ok() && master.Initialize()) << g_last_log;
      std::size_t compared = 0;
      for (std::size_t k = 0; k * substeps < trace.rows.size(); ++k) {
        if (k > 0) {
          ASSERT_TRUE(master.Step(static_cast<double>(k - 1) * dt, dt)) << g_last_log;
        }
        const std::vector<double>& row = trace.rows[k * substeps];
        for (const char* axis : {"x", "y", "z"}) {
          ASSERT_EQ(master.Value(std::string("position_") + axis), row[trace.Column(std::string("command_") + axis + "_m")])
              << "axis " << axis << " at tick " << k;
        }
        if (single_axis) {
          ASSERT_EQ(master.Value("velocity_y"), row[trace.Column("command_velocity_m_s")]) << "tick " << k;
          ASSERT_EQ(master.Value("accel_y"), row[trace.Column("command_accel_m_s2")]) << "tick " << k;
        }
        ++compared;
      }
      EXPECT_GT(compared, 700u);
    }
  }
}

// Tests that the exported machine FMU (FMI 2.0 and 3.0), its input the run's commanded
// acceleration held over each period, gives the native exact run's deflection at every
// period boundary within 1e-12 of the static displacement, and that the largest of its
// per-step peaks is the run's peak deflection within 1e-9 of it (in-step peaks survive).
TEST(FmuMaster, MachineDeflectionEqualsTheExactRun) {
  ScratchDir dir;
  const std::vector<std::string> exact = {"--set", "integrator.method=exact"};
  const testing::CliResult run = RunCli(testing::Args({"run", "configs/demo.yaml", "--out", dir.File("run")}, exact), kSourceDir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const TraceCsv trace = ReadTrace(dir.File("run/trace.csv"));
  const nlohmann::json metrics = nlohmann::json::parse(testing::ReadText(dir.File("run/metrics.json")));
  const double statik = metrics["static_displacement_m"].get<double>();
  const double dt = 0.001;
  const std::size_t substeps = SubstepsOf(trace, dt);
  for (int version : {2, 3}) {
    SCOPED_TRACE("FMI " + std::to_string(version));
    LoadedFmu fmu;
    ExportAndLoad(dir, testing::Args({"configs/demo.yaml", "--part", "machine"}, exact), version, &fmu);
    Master master(fmu, version);
    ASSERT_TRUE(master.ok() && master.Initialize()) << g_last_log;
    double peak = 0.0, worst = 0.0;
    for (std::size_t k = 1; k * substeps < trace.rows.size(); ++k) {
      // The acceleration held over period k is the trace's at the period's rows.
      ASSERT_TRUE(master.Set("base_accel_y", trace.rows[k * substeps][trace.Column("command_accel_m_s2")]));
      ASSERT_TRUE(master.Step(static_cast<double>(k - 1) * dt, dt)) << g_last_log;
      const double native = trace.rows[k * substeps][trace.Column("deflection_y_m")];
      worst = std::max(worst, std::abs(master.Value("deflection_y") - native));
      peak = std::max(peak, master.Value("deflection_peak_y"));
    }
    EXPECT_LE(worst, 1e-12 * statik);
    EXPECT_NEAR(peak, metrics["peak_deflection_m"].get<double>(), 1e-9 * statik);
    double max_accel = 0.0;
    for (const std::vector<double>& row : trace.rows) max_accel = std::max(max_accel, std::abs(row[trace.Column("command_accel_m_s2")]));
    EXPECT_NEAR(std::abs(master.Value("static_compliance_y")) * max_accel, statik, 1e-12 * statik);
  }
}

// Tests that a parameter set before initialization (a mode's frequency) gives the same
// outputs as the FMU exported with that value, and that a step size other than the first
// (10 periods at once, then one) is taken: the deflection after 0.01 s is the same to 1e-12.
TEST(FmuMaster, ParameterAndAnyStepSize) {
  ScratchDir dir;
  const char* scenario = "configs/scenarios/method1.yaml";
  const std::string key = "machine.modes[0].frequency_hz";
  double by_parameter = 0.0, by_export = 0.0, by_tens = 0.0;
  {
    LoadedFmu fmu;
    ExportAndLoad(dir, {scenario, "--part", "machine"}, 2, &fmu);
    Master master(fmu, 2);
    ASSERT_TRUE(master.ok() && master.Set(key, 31.0) && master.Initialize()) << g_last_log;
    ASSERT_TRUE(master.Set("base_accel_y", 2.0));
    for (int k = 0; k < 10; ++k) ASSERT_TRUE(master.Step(k * 0.001, 0.001)) << g_last_log;
    by_parameter = master.Value("deflection_y");
  }
  {
    LoadedFmu fmu;
    ExportAndLoad(dir, {scenario, "--part", "machine", "--set", key + "=31"}, 3, &fmu);
    Master master(fmu, 3);
    ASSERT_TRUE(master.ok() && master.Initialize()) << g_last_log;
    ASSERT_TRUE(master.Set("base_accel_y", 2.0));
    for (int k = 0; k < 10; ++k) ASSERT_TRUE(master.Step(k * 0.001, 0.001)) << g_last_log;
    by_export = master.Value("deflection_y");
    ASSERT_TRUE(master.Step(0.01, 0.002) && master.Step(0.012, 0.001)) << g_last_log;  // any step size
    EXPECT_GT(master.Value("deflection_peak_y"), 0.0);
    Master tens(fmu, 3);
    ASSERT_TRUE(tens.ok() && tens.Initialize() && tens.Set("base_accel_y", 2.0) && tens.Step(0.0, 0.01)) << g_last_log;
    by_tens = tens.Value("deflection_y");
  }
  EXPECT_EQ(by_parameter, by_export);
  EXPECT_NE(by_parameter, 0.0);
  EXPECT_NEAR(by_tens, by_export, 1e-12 * std::abs(by_export));
}

// Tests that the controller refuses a step that is not one interpolation period with
// fmi2Error and says why in its log, and that a parameter cannot be set after
// initialization.
TEST(FmuMaster, RefusalsAreLoggedErrors) {
  ScratchDir dir;
  LoadedFmu fmu;
  ExportAndLoad(dir, {"configs/demo.yaml", "--part", "controller"}, 2, &fmu);
  Master master(fmu, 2);
  ASSERT_TRUE(master.ok() && master.Initialize());
  EXPECT_FALSE(master.Step(0.0, 0.002));
  EXPECT_NE(g_last_log.find("one interpolation period at a time"), std::string::npos) << g_last_log;
  LoadedFmu machine;
  ScratchDir machine_dir;
  ExportAndLoad(machine_dir, {"configs/scenarios/method1.yaml", "--part", "machine"}, 2, &machine);
  Master plant(machine, 2);
  ASSERT_TRUE(plant.ok() && plant.Initialize());
  EXPECT_FALSE(plant.Set("machine.modes[0].frequency_hz", 30.0));
  EXPECT_NE(g_last_log.find("after initialization"), std::string::npos) << g_last_log;
}

// Tests that a nonlinear machine (backlash, stepped by CVODE) is driven through its FMU: a
// held acceleration deflects it, and a step size other than its first is refused with the
// reason logged.
TEST(FmuMaster, NonlinearMachineStepsByCvode) {
  ScratchDir dir;
  LoadedFmu fmu;
  ExportAndLoad(dir, {"configs/scenarios/backlash_reversal.yaml", "--part", "machine"}, 3, &fmu);
  std::string input;
  for (const std::string& name : fmu.names) {
    if (input.empty() && name.rfind("base_accel_", 0) == 0) input = name;
  }
  ASSERT_FALSE(input.empty());
  const std::string output = "deflection_" + input.substr(std::string("base_accel_").size());
  Master master(fmu, 3);
  ASSERT_TRUE(master.ok() && master.Initialize()) << g_last_log;
  ASSERT_TRUE(master.Set(input, 3.0));
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(master.Step(k * 0.001, 0.001)) << g_last_log;
  EXPECT_TRUE(std::isfinite(master.Value(output)));
  EXPECT_NE(master.Value(output), 0.0);
  EXPECT_GE(master.Value("deflection_peak_" + output.substr(std::string("deflection_").size())),
            std::abs(master.Value(output)));
  EXPECT_FALSE(master.Step(0.02, 0.002));
  EXPECT_NE(g_last_log.find("the communication step must stay"), std::string::npos) << g_last_log;
}

}  // namespace shapebench::bench::fmu_master_test
