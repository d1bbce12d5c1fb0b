// bench/scenario/structure_numbers.h: a sweep point that changes only numbers of the structure is
// set on a scenario loaded once. The oracle is the loader itself, reading the point from
// its sources: the two must agree field for field and run for run, bit for bit.
#include "bench/scenario/structure_numbers.h"

#include <cstring>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/run/run_scenario.h"
#include "bench/scenario/scenario_loader.h"
#include "bench/sweep/sweep.h"
#include "tests/support/bench_test_support.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {
namespace {

using testing::DataPath;
using testing::ScratchDir;


void ExpectSamePlant(const Scenario& a, const Scenario& b) {
  const model::MachinePlant x = model::BuildMachinePlant(a.machine, a.drive);
  const model::MachinePlant y = model::BuildMachinePlant(b.machine, b.drive);
  EXPECT_TRUE(x.plant.A == y.plant.A);
  EXPECT_TRUE(x.plant.B_accel == y.plant.B_accel);
  EXPECT_TRUE(x.plant.B_vel == y.plant.B_vel);
  EXPECT_TRUE(x.plant.C == y.plant.C);
  EXPECT_TRUE(x.static_gain == y.static_gain);
}

struct StructureCase {
  const char* name;
  std::string base;
  std::vector<Override> first;   // the point loaded from its sources
  std::vector<Override> second;  // the point set on it
};

void PrintTo(const StructureCase& c, std::ostream* os) { *os << c.name; }

class StructureNumbersTest : public ::testing::TestWithParam<StructureCase> {};

// Tests that setting a point's structure numbers on the scenario of another point gives
// the scenario the loader reads for it: the same model and, for the single mode, the same
// metrics bit for bit.
TEST_P(StructureNumbersTest, EqualsLoadingThePoint) {
  const StructureCase& c = GetParam();
  Scenario set = LoadScenario(c.base, c.first);
  ASSERT_TRUE(SetStructureNumbers(&set, c.second));
  const Scenario loaded = LoadScenario(c.base, c.second);
  ExpectSamePlant(set, loaded);
  if (loaded.machine.single_form) {
    const auto x = RunScenario(set, RunOptions{false}).metrics.Named();
    const auto y = RunScenario(loaded, RunOptions{false}).metrics.Named();
    for (std::size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(std::memcmp(&x[i].second, &y[i].second, sizeof(double)), 0) << x[i].first;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Keys, StructureNumbersTest,
    ::testing::Values(
        StructureCase{"modal_frequency", DataPath("sweeps/sdof_method1.yaml"),
                      {{"machine.modes[0].frequency_hz", "25"}},
                      {{"machine.modes[0].frequency_hz", "21.3456789012345"}}},
        StructureCase{"modal_three_fields", DataPath("sweeps/sdof_method1.yaml"),
                      {{"machine.modes[0].damping_ratio", "0"}, {"machine.modes[0].gain", "1"},
                       {"machine.modes[0].frequency_hz", "25"}},
                      {{"machine.modes[0].damping_ratio", "0.03"}, {"machine.modes[0].gain", ".7"},
                       {"machine.modes[0].frequency_hz", "3.1e1"}}},
        StructureCase{"lumped_axes", kSourceDir + "/configs/scenarios/pocket_corner.yaml",
                      {{"machine.axes.y.bodies[1].mass_kg", "2400"},
                       {"machine.axes.x.elements[1].stiffness_n_m", "1e8"},
                       {"machine.axes.z.elements[0].damping_n_s_m", "2.7e5"}},
                      {{"machine.axes.y.bodies[1].mass_kg", "+2000.5"},
                       {"machine.axes.x.elements[1].stiffness_n_m", "9.5E7"},
                       {"machine.axes.z.elements[0].damping_n_s_m", "1000"}}},
        StructureCase{"lumped_modal_damping", DataPath("sweeps/damped_chain.yaml"),
                      {{"machine.damping.modal[1]", "0.045"}, {"machine.bodies[2].mass_kg", "40"}},
                      {{"machine.damping.modal[1]", "0.0731"}, {"machine.bodies[2].mass_kg", "35"},
                       {"machine.damping.modal[0]", "1e-3"}}},
        StructureCase{"coupled_modes", DataPath("sweeps/coupled_two_modes.yaml"),
                      {{"machine.modes[1].participation.x", "3"}, {"machine.modes[1].shape.z", "6e-4"},
                       {"machine.modes[0].frequency_hz", "25"}},
                      {{"machine.modes[1].participation.x", "-4.5"}, {"machine.modes[1].shape.z", "1.25e-3"},
                       {"machine.modes[0].frequency_hz", "24.5"}}},
        StructureCase{"lumped_rayleigh_damping", DataPath("sweeps/rayleigh_chain.yaml"),
                      {{"machine.damping.rayleigh.alpha", "12"}},
                      {{"machine.damping.rayleigh.alpha", "7.25"},
                       {"machine.damping.rayleigh.beta", "1.5e-5"}}}),
    [](const ::testing::TestParamInfo<StructureCase>& info) { return info.param.name; });

// Tests which keys are structure numbers: the three modal fields, a body's mass, an
// element's stiffness and damping, in either form; nothing else.
TEST(StructureNumbers, KnowsItsKeys) {
  for (const char* key :
       {"machine.modes[0].frequency_hz", "machine.modes[12].damping_ratio", "machine.modes[0].gain",
        "machine.bodies[3].mass_kg", "machine.elements[0].stiffness_n_m",
        "machine.elements[1].damping_n_s_m", "machine.axes.x.modes[0].frequency_hz",
        "machine.axes.z.bodies[0].mass_kg", "machine.axes.y.elements[2].damping_n_s_m",
        "machine.damping.modal[0]", "machine.axes.x.damping.modal[2]",
        "machine.damping.rayleigh.alpha", "machine.axes.z.damping.rayleigh.beta",
        "machine.modes[1].participation.x", "machine.modes[0].shape.z"}) {
    EXPECT_TRUE(IsStructureNumberKey(key)) << key;
  }
  for (const char* key :
       {"controller.feed_mm_min", "machine.modes[0]", "machine.modes.frequency_hz",
        "machine.modes[0].frequency_hz.x", "machine.bodies[0].name", "machine.elements[0].from",
        "machine.stroke.x", "machine.axes.w.modes[0].gain", "machine.axes.x.modes.gain",
        "machine.axes.x", "machine.modes[0].mass_kg", "drive.position_gain", "machine",
        "machine.damping.modal", "machine.damping.rayleigh", "machine.damping.rayleigh.gamma",
        "machine.damping.rayleigh[0]", "machine.damping.modal.alpha", "machine.damping[0].modal",
        "machine.damping.modal[0].x", "machine.axes.x.damping.rayleigh[1]",
        "machine.modes[0].shape.w", "machine.modes[0].shape", "machine.axes.x.modes[0].shape.x",
        "machine.modes[0].gain.x", "machine.bodies[0].shape.x"}) {
    EXPECT_FALSE(IsStructureNumberKey(key)) << key;
  }
}

// Tests that every value the loader would refuse, or reads otherwise, is not set: the
// point then goes to the loader, which locates the error.
TEST(StructureNumbers, LeavesWhatTheLoaderRefusesToIt) {
  const std::string base = DataPath("sweeps/sdof_method1.yaml");
  const Scenario loaded = LoadScenario(base, {});
  for (const char* text : {"abc", "0x10", ".inf", "1e999", "'25'", "25 # c", "", "[25]", "1_000"}) {
    Scenario scenario = loaded;
    EXPECT_FALSE(SetStructureNumbers(&scenario, {{"machine.modes[0].frequency_hz", text}})) << text;
  }
  for (const Override& bad : std::vector<Override>{
           {"machine.modes[0].frequency_hz", "-25"},        // validate(): must be > 0
           {"machine.modes[0].damping_ratio", "1.5"},       // validate(): in [0, 1)
           {"machine.modes[1].frequency_hz", "30"},         // no second mode
           {"machine.axes.y.modes[0].frequency_hz", "30"},  // the other form
           {"machine.bodies[0].mass_kg", "10"},             // the other form
           {"machine.modes[0].frequency_hz", "1e-9"}}) {    // a run far beyond limits:
    Scenario scenario = loaded;
    EXPECT_FALSE(SetStructureNumbers(&scenario, {bad})) << bad.key_path << "=" << bad.value_yaml;
  }
}

// Tests that a coupled mode's numbers are set only where the loader would read them the
// same: a gain beside participation and shape, a component of a vector the mode does not
// have, and any number of modes from a modal_file (no key in the YAML) go to the loader.
TEST(StructureNumbers, LeavesCouplingTheLoaderRefusesToIt) {
  const Scenario coupled = LoadScenario(DataPath("sweeps/coupled_two_modes.yaml"), {});
  Scenario with_gain = coupled;
  EXPECT_FALSE(SetStructureNumbers(&with_gain, {{"machine.modes[0].gain", "0.5"}}));
  Scenario gain = LoadScenario(DataPath("sweeps/sdof_method1.yaml"), {});
  EXPECT_FALSE(SetStructureNumbers(&gain, {{"machine.modes[0].shape.y", "2"}}));  // a gain mode
  Scenario from_file = LoadScenario(kSourceDir + "/configs/scenarios/fe_modes.yaml", {});
  EXPECT_FALSE(SetStructureNumbers(&from_file, {{"machine.modes[0].frequency_hz", "24"}}));
  Scenario still = coupled;
  EXPECT_TRUE(SetStructureNumbers(&still, {{"machine.modes[1].shape.x", "2e-3"}}));
}

// Tests that a damping-block number is set only where the axis has that very block and
// entry: switching, adding or extending a block, and a ratio validate() refuses, go to the
// loader.
TEST(StructureNumbers, DampingBlockNumbersOnlyWhereTheBlockIs) {
  const Scenario modal = LoadScenario(DataPath("sweeps/damped_chain.yaml"), {});
  for (const Override& bad : std::vector<Override>{
           {"machine.damping.rayleigh.alpha", "1"},  // the other block
           {"machine.damping.modal[3]", "0.01"},     // no fourth entry
           {"machine.damping.modal[0]", "1.5"},      // validate(): in [0, 1)
           {"machine.axes.y.damping.modal[0]", "0.01"}}) {  // the other form
    Scenario scenario = modal;
    EXPECT_FALSE(SetStructureNumbers(&scenario, {bad})) << bad.key_path << "=" << bad.value_yaml;
  }
  const Scenario rayleigh = LoadScenario(DataPath("sweeps/rayleigh_chain.yaml"), {});
  Scenario scenario = rayleigh;
  EXPECT_FALSE(SetStructureNumbers(&scenario, {{"machine.damping.modal[0]", "0.01"}}));
  scenario = rayleigh;
  EXPECT_FALSE(SetStructureNumbers(&scenario, {{"machine.damping.rayleigh.beta", "-1"}}));
  // A dashpot beside the block: validate() refuses it, the loader locates it.
  scenario = rayleigh;
  EXPECT_FALSE(SetStructureNumbers(&scenario, {{"machine.elements[1].damping_n_s_m", "10"}}));
  const Scenario lumped = LoadScenario(kSourceDir + "/configs/scenarios/pocket_corner.yaml", {});
  scenario = lumped;
  EXPECT_FALSE(SetStructureNumbers(&scenario, {{"machine.axes.y.damping.modal[0]", "0.01"}}));
}

// The sweep at `path` (4 points, the third bad): each good point equals an independent
// run of it bit for bit (point 1 twice: the structure-number path reused), the bad one
// is refused at the sweep file's line 3 naming `key`.
void ExpectGoodPointsExactAndThirdLocated(const std::string& path, const std::string& key) {
  const Sweep sweep = LoadSweep(path, {});
  for (const std::uint64_t p : {0u, 1u, 2u, 3u, 1u}) {
    const PointOutcome outcome = RunPoint(sweep, {}, p);
    if (p == 2) {
      ASSERT_FALSE(outcome.ok());
      EXPECT_EQ(outcome.error.rfind(path + ":3:", 0), 0u) << outcome.error;
      EXPECT_NE(outcome.error.find(key), std::string::npos) << outcome.error;
      continue;
    }
    ASSERT_TRUE(outcome.ok()) << outcome.error;
    const auto alone =
        RunScenario(LoadScenario(sweep.base, MakePoint(sweep, p, {}).overrides)).metrics.Named();
    const auto x = outcome.metrics.Named();
    for (std::size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(std::memcmp(&x[i].second, &alone[i].second, sizeof(double)), 0)
          << "point " << p << " " << x[i].first;
    }
  }
}

// Tests a natural-period sweep with a bad value among good ones: the good points equal
// independent runs, the bad one reports its value's place in the sweep file.
TEST(StructureNumbers, SweepPointsStayExactAndErrorsLocated) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "sweep.yaml", "base: " + DataPath("sweeps/sdof_method1.yaml") +
                        "\ngrid:\n  machine.modes[0].frequency_hz: [20, 22.5, -5, 30]\n");
  ExpectGoodPointsExactAndThirdLocated(path, "frequency_hz");
}

// Tests a sweep over a modal damping ratio of a lumped axis with a bad value among good
// ones: the good points equal independent runs bit for bit, the bad one reports its
// value's place in the sweep file.
TEST(StructureNumbers, DampingSweepPointsStayExactAndErrorsLocated) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "sweep.yaml", "base: " + DataPath("sweeps/damped_chain.yaml") +
                        "\ngrid:\n  machine.damping.modal[0]: [0.0, 0.02, 1.2, 0.08]\n");
  ExpectGoodPointsExactAndThirdLocated(path, "damping.modal[0]");
}

}  // namespace
}  // namespace shapebench::bench
