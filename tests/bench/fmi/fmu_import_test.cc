// The import master's pieces against the test plant FMU (tests/fmu/test_plant_fmu.cc), FMI
// 2.0 and 3.0: the archive and its modelDescription, the FMU stepped tick by tick against a
// matrix-exponential oracle, and its error statuses in words.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "bench/fmi/fmu_archive.h"
#include "bench/fmi/fmu_plant.h"
#include "model/integrator.h"
#include "model/multi_axis_machine.h"
#include "tests/support/bench_test_support.h"
#include "tests/support/test_fmu.h"

namespace shapebench::bench::fmu_import_test {
namespace {

using testing::TestPlantFmu;

// The test plant's default: m = 1 kg, k = (2 pi 25)^2 N/m, c = 2 0.03 (2 pi 25) N s/m.
struct MsdParameters {
  long double m = 1.0L;
  long double k = 24674.011002723397L;
  long double c = 9.42477796076938L;
};

// x(t_k), v(t_k) under inputs held over steps of h: the augmented matrix exponential
// exp([[A, B], [0, 0]] h) in long double, A = [[0, 1], [-k/m, -c/m]], B = [0, -1].
class MatrixExponentialOracle {
 public:
  MatrixExponentialOracle(const MsdParameters& p, long double h) {
    Eigen::Matrix<long double, 3, 3> augmented = Eigen::Matrix<long double, 3, 3>::Zero();
    augmented(0, 1) = 1.0L;
    augmented(1, 0) = -p.k / p.m;
    augmented(1, 1) = -p.c / p.m;
    augmented(1, 2) = -1.0L;
    transition_ = (augmented * h).exp();
  }
  void Step(long double a) {
    const Eigen::Matrix<long double, 3, 1> z(x_, v_, a);
    const Eigen::Matrix<long double, 3, 1> next = transition_ * z;
    x_ = next(0);
    v_ = next(1);
  }
  long double x() const { return x_; }

 private:
  Eigen::Matrix<long double, 3, 3> transition_;
  long double x_ = 0.0L, v_ = 0.0L;
};

FmuMachine TestPlantMachine(int version, std::vector<std::pair<std::string, double>> parameters = {}) {
  FmuMachine machine;
  machine.fmu = std::make_shared<const UnpackedFmu>(TestPlantFmu(version));
  const ModelDescription& md = machine.fmu->description();
  const auto signal = [&md](const std::string& name) {
    return FmuSignal{name, md.Find(name)->value_reference};
  };
  machine.base_acceleration[1] = signal("base_accel_y");
  machine.deflection[1] = signal("deflection_y");
  machine.deflection_peak[1] = signal("deflection_peak_y");
  machine.static_compliance[1] = signal("static_compliance_y");
  for (const auto& [name, value] : parameters) machine.parameters.emplace_back(signal(name), value);
  return machine;
}

// A held acceleration that changes every few steps, both signs: steps inside the periods
// where the oscillator turns.
double TestInput(int k) { return ((k / 7) % 3 - 1) * 1.7 + ((k / 23) % 2) * 0.4; }

// Tests that both versions' modelDescription.xml read as written: version, token,
// co-simulation model identifier, and each variable's value reference, causality,
// variability, unit and start (the Integer/Int32 one kept but not a double).
TEST(FmuArchive, ReadsModelDescriptionOfBothVersions) {
  for (int version : {2, 3}) {
    const UnpackedFmu fmu(TestPlantFmu(version));
    const ModelDescription& md = fmu.description();
    EXPECT_EQ(md.version, version == 2 ? FmiVersion::k2 : FmiVersion::k3);
    EXPECT_EQ(md.token, "{shapebench-test-plant-1}");
    EXPECT_EQ(md.model_identifier, "test_plant");
    EXPECT_TRUE(std::filesystem::exists(fmu.binary())) << fmu.binary();
    EXPECT_NE(fmu.binary().find(version == 2 ? "/binaries/linux64/" : "/binaries/x86_64-linux/"), std::string::npos);
    const FmuVariable* k = md.Find("stiffness_n_m");
    ASSERT_NE(k, nullptr);
    EXPECT_EQ(k->value_reference, 1u);
    EXPECT_EQ(k->causality, "parameter");
    EXPECT_EQ(k->variability, "fixed");
    EXPECT_EQ(k->unit, "N/m");
    ASSERT_TRUE(k->start.has_value());
    EXPECT_EQ(*k->start, 24674.011002723397);
    const FmuVariable* input = md.Find("base_accel_y");
    ASSERT_NE(input, nullptr);
    EXPECT_EQ(input->causality, "input");
    EXPECT_EQ(input->variability, "continuous");
    EXPECT_TRUE(input->IsDouble());
    const FmuVariable* count = md.Find("mode_count");
    ASSERT_NE(count, nullptr);
    EXPECT_FALSE(count->IsDouble());
    EXPECT_EQ(md.DoubleNames("input"), "base_accel_y");
  }
}

// Tests that the private directory goes with the object, and that a missing file, a file
// that is not a zip and a zip without modelDescription.xml are refused naming the file.
TEST(FmuArchive, RemovesItsDirectoryAndRefusesBadArchives) {
  std::string dir;
  {
    const UnpackedFmu fmu(TestPlantFmu(2));
    dir = fmu.dir();
    EXPECT_TRUE(std::filesystem::exists(dir + "/modelDescription.xml"));
  }
  EXPECT_FALSE(std::filesystem::exists(dir)) << dir;
  testing::ScratchDir scratch;
  const std::string not_zip = scratch.Write("plain.fmu", "not a zip\n");
  const std::string missing = scratch.File("missing.fmu");
  for (const std::string& file : {not_zip, missing}) {
    try {
      UnpackedFmu fmu(file);
      ADD_FAILURE() << file;
    } catch (const FmuError& error) {
      EXPECT_NE(std::string(error.what()).find(file + ": cannot be opened as an FMU"), std::string::npos)
          << error.what();
    }
  }
  const std::string empty_zip = scratch.File("empty.fmu");
  ASSERT_EQ(std::system(("cd " + scratch.path().string() + " && echo x > readme.txt && cmake -E tar cf empty.fmu "
                         "--format=zip readme.txt").c_str()),
            0);
  try {
    UnpackedFmu fmu(empty_zip);
    ADD_FAILURE() << empty_zip;
  } catch (const FmuError& error) {
    EXPECT_NE(std::string(error.what()).find("no modelDescription.xml"), std::string::npos) << error.what();
  }
}

// Tests that the FMU stepped by the master (set input, doStep, get output, per tick of
// 1 ms, FMI 2.0 and 3.0) gives the matrix-exponential oracle's deflection at every
// communication point within 1e-12 of the static deflection, also with fmu_parameters set
// (a stiffer, more damped plant), and its step peak is at least both ends' |x| and at most
// the largest of 200 oracle samples inside the step plus 1e-12.
TEST(FmuPlant, TraceMatchesTheMatrixExponentialOracle) {
  for (int version : {2, 3}) {
    for (const bool stiffer : {false, true}) {
      MsdParameters p;
      std::vector<std::pair<std::string, double>> set;
      if (stiffer) {
        p.k = 4.0e4L;
        p.c = 30.0L;
        set = {{"stiffness_n_m", 4.0e4}, {"damping_n_s_m", 30.0}};
      }
      const FmuMachine machine = TestPlantMachine(version, set);
      FmuPlant plant(machine, 1e-3, 1, 1.0);
      Eigen::Matrix3d gain;
      ASSERT_TRUE(plant.StaticGain(&gain));
      EXPECT_DOUBLE_EQ(gain(1, 1), -static_cast<double>(p.m / p.k));  // the tool lags
      ASSERT_TRUE(plant.WatchExtremum(model::kDeflectionRow + 1));
      const double scale = 2.1 * static_cast<double>(p.m / p.k);  // the largest input's static deflection
      MatrixExponentialOracle oracle(p, 1e-3L), fine(p, 1e-3L / 200);
      double worst = 0.0;
      double out[model::kNumOutputRows];
      for (int k = 1; k <= 400; ++k) {
        const double a = TestInput(k);
        const double accel[3] = {0.0, a, 0.0};
        const double start = static_cast<double>(oracle.x());
        plant.AdvancePeriod(accel, 1, out);
        oracle.Step(a);
        double inside = std::abs(start);
        for (int j = 0; j < 200; ++j) {
          fine.Step(a);
          inside = std::max(inside, static_cast<double>(std::fabs(fine.x())));
        }
        worst = std::max(worst, std::abs(out[model::kDeflectionRow + 1] - static_cast<double>(oracle.x())));
        EXPECT_EQ(out[model::kDeflectionRow + 0], 0.0);
        EXPECT_EQ(out[model::kToolErrorRow + 1], out[model::kDeflectionRow + 1]);  // unmapped: the deflection
        EXPECT_GE(plant.PeriodExtremum(), std::abs(out[model::kDeflectionRow + 1]));
        EXPECT_GE(plant.PeriodExtremum(), inside - 1e-12 * scale) << k;
        EXPECT_LE(plant.PeriodExtremum(), inside + 2e-6 * scale) << k;  // 200 samples miss a top by < 1.2e-4 * 1e-2
        EXPECT_DOUBLE_EQ(plant.Time(), 1e-3 * k);
      }
      EXPECT_LE(worst, 1e-12 * scale) << "FMI " << version << (stiffer ? " stiffer" : "");
    }
  }
}

// Tests that an Error status from the FMU becomes a SolverError FMU_ERROR naming the
// function, the status in words, the time and the FMU's logged message: at a doStep
// (fail_at_s) and at initialisation (a negative stiffness), in both versions.
TEST(FmuPlant, ErrorStatusIsASolverErrorInWords) {
  for (int version : {2, 3}) {
    const std::string v = std::to_string(version);
    FmuPlant plant(TestPlantMachine(version, {{"fail_at_s", 0.0025}}), 1e-3, 1, 1.0);
    const double accel[3] = {0.0, 1.0, 0.0};
    double out[model::kNumOutputRows];
    plant.AdvancePeriod(accel, 1, out);
    try {
      plant.AdvancePeriod(accel, 1, out);
      plant.AdvancePeriod(accel, 1, out);
      ADD_FAILURE() << "no error";
    } catch (const model::SolverError& error) {
      EXPECT_EQ(error.flag_name(), "FMU_ERROR");
      const std::string text = error.what();
      EXPECT_NE(text.find("fmi" + v + "DoStep returned fmi" + v + "Error at t = 0.002 s"), std::string::npos) << text;
      EXPECT_NE(text.find("fail_at_s reached at t = 0.003"), std::string::npos) << text;
      EXPECT_NE(text.find(TestPlantFmu(version)), std::string::npos) << text;
    }
    try {
      FmuPlant bad(TestPlantMachine(version, {{"stiffness_n_m", -1.0}}), 1e-3, 1, 1.0);
      ADD_FAILURE() << "no error";
    } catch (const model::SolverError& error) {
      const std::string text = error.what();
      EXPECT_NE(text.find("fmi" + v + "ExitInitializationMode returned fmi" + v + "Error"), std::string::npos) << text;
      EXPECT_NE(text.find("stiffness_n_m must be > 0"), std::string::npos) << text;
    }
  }
}

}  // namespace
}  // namespace shapebench::bench::fmu_import_test
