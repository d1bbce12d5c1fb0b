// Machine models: validation, plants and modal analysis against hand-derived closed forms.
#include "common/math_constants.h"
#include "model/machine.h"

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "common/validation_error.h"

namespace shapebench::model {
namespace {


double Omega(double hz) { return kTwoPi * hz; }

// Both roots (ascending) of m1 m2 L^2 - (m1 k2 + m2 (k1 + k2)) L + k1 k2 = 0, L = w^2: the
// characteristic equation of the chain ground -k1- m1 -k2- m2.
std::pair<double, double> ChainOmegaSquared(double m1, double m2, double k1, double k2) {
  const double a = m1 * m2;
  const double b = -(m1 * k2 + m2 * (k1 + k2));
  const double c = k1 * k2;
  const double root = std::sqrt(b * b - 4.0 * a * c);
  return {(-b - root) / (2.0 * a), (-b + root) / (2.0 * a)};
}

MachineConfig Lumped(LumpedMachineConfig config) { return MachineConfig{std::move(config)}; }

// Base-excited chain: driven -k1- m1 -k2- m2, tool on m2, relative to ground.
LumpedMachineConfig BaseExcitedChain(double m1, double m2, double k1, double k2) {
  LumpedMachineConfig config;
  config.bodies = {{"m1", m1}, {"m2", m2}};
  config.elements = {{"k1", "driven", "m1", k1, 0.0}, {"k2", "m1", "m2", k2, 0.0}};
  config.output_body = "m2";
  return config;
}

// Tests that the modal plant's static gain is -sum(gain / w^2) and that the analysis
// reports the modes sorted by frequency with their signed shares.
TEST(ModalMachine, StaticGainAndParticipation) {
  ModalMachineConfig config;
  config.modes = {{70.0, 0.05, -0.4}, {25.0, 0.02, 1.0}, {140.0, 0.01, 0.3}};
  MachineConfig machine;
  machine.form = config;
  double sum = 0.0;
  for (const ModalMode& mode : config.modes)
    sum += mode.gain / std::pow(Omega(mode.frequency_hz), 2);

  const LinearPlant plant = BuildPlant(machine);
  ASSERT_EQ(plant.num_states(), 6);
  EXPECT_NEAR(plant.StaticGain()(0, 0), -sum, 1e-12 * std::abs(sum));
  EXPECT_DOUBLE_EQ(plant.max_frequency_rad_s, Omega(140.0));

  const ModalAnalysis analysis = AnalyzeModes(machine);
  EXPECT_NEAR(analysis.static_deflection_per_accel_s2, std::abs(sum), 1e-15);
  ASSERT_EQ(analysis.modes.size(), 3u);
  EXPECT_EQ(analysis.modes[0].frequency_hz, 25.0);
  EXPECT_EQ(analysis.modes[1].frequency_hz, 70.0);
  EXPECT_EQ(analysis.modes[2].frequency_hz, 140.0);
  EXPECT_EQ(analysis.modes[1].damping_ratio, 0.05);
  EXPECT_NEAR(analysis.modes[1].participation, -0.4 / std::pow(Omega(70.0), 2) / sum, 1e-14);
}

struct ValidationCase {
  std::string name;
  std::function<void(MachineConfig&)> spoil;
  std::string field;
};

void PrintTo(const ValidationCase& c, std::ostream* os) { *os << c.name; }

MachineConfig ValidLumped() {
  LumpedMachineConfig config;
  config.bodies = {{"bed", 5000.0}, {"column", 2000.0}};
  config.elements = {{"mounts", "bed", "ground", 1e9, 1e5},
                     {"guides", "column", "driven", 5e7, 1e3}};
  config.driven_relative_to = "bed";
  config.output_body = "column";
  config.output_relative_to = "bed";
  return Lumped(config);
}

LumpedMachineConfig& L(MachineConfig& m) { return std::get<LumpedMachineConfig>(m.form); }
ModalMachineConfig& Modal(MachineConfig& m) { return std::get<ModalMachineConfig>(m.form); }

class MachineValidation : public testing::TestWithParam<ValidationCase> {};

// Tests that each invalid value is rejected with a ValidationError naming its field.
TEST_P(MachineValidation, NamesTheField) {
  const ValidationCase& c = GetParam();
  MachineConfig machine = c.field.rfind("modes", 0) == 0 ? MachineConfig{} : ValidLumped();
  ASSERT_NO_THROW(machine.validate());
  c.spoil(machine);
  try {
    machine.validate();
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), c.field) << e.what();
    EXPECT_FALSE(e.message().empty());
  }
  EXPECT_THROW(BuildPlant(machine), ValidationError);
}

const double kNan = std::nan("");

INSTANTIATE_TEST_SUITE_P(
    Grid, MachineValidation,
    testing::Values(
        ValidationCase{"NoModes", [](MachineConfig& m) { Modal(m).modes.clear(); }, "modes"},
        ValidationCase{"NegativeFrequency",
                       [](MachineConfig& m) { Modal(m).modes[0].frequency_hz = -1.0; },
                       "modes[0].frequency_hz"},
        ValidationCase{"InfiniteFrequency",
                       [](MachineConfig& m) { Modal(m).modes[0].frequency_hz = INFINITY; },
                       "modes[0].frequency_hz"},
        ValidationCase{"CriticalDamping",
                       [](MachineConfig& m) {
                         Modal(m).modes.push_back({});
                         Modal(m).modes[1].damping_ratio = 1.0;
                       },
                       "modes[1].damping_ratio"},
        ValidationCase{"NanGain", [](MachineConfig& m) { Modal(m).modes[0].gain = kNan; },
                       "modes[0].gain"},
        ValidationCase{"NoBodies", [](MachineConfig& m) { L(m).bodies.clear(); }, "bodies"},
        ValidationCase{"ZeroMass", [](MachineConfig& m) { L(m).bodies[1].mass_kg = 0.0; },
                       "bodies[1].mass_kg"},
        ValidationCase{"EmptyName", [](MachineConfig& m) { L(m).bodies[0].name = ""; },
                       "bodies[0].name"},
        ValidationCase{"ReservedName",
                       [](MachineConfig& m) {
                         L(m).bodies.push_back({"ground", 1.0});
                       },
                       "bodies[2].name"},
        ValidationCase{"DuplicateName",
                       [](MachineConfig& m) {
                         L(m).bodies.push_back({"bed", 1.0});
                       },
                       "bodies[2].name"},
        ValidationCase{"UnknownFrom", [](MachineConfig& m) { L(m).elements[0].from = "bad"; },
                       "elements[0].from"},
        ValidationCase{"UnknownTo", [](MachineConfig& m) { L(m).elements[1].to = "floor"; },
                       "elements[1].to"},
        ValidationCase{"SelfLoop", [](MachineConfig& m) { L(m).elements[0].to = "bed"; },
                       "elements[0].to"},
        ValidationCase{"NegativeStiffness",
                       [](MachineConfig& m) { L(m).elements[0].stiffness_n_m = -1.0; },
                       "elements[0].stiffness_n_m"},
        ValidationCase{"NegativeDamping",
                       [](MachineConfig& m) { L(m).elements[1].damping_n_s_m = -1.0; },
                       "elements[1].damping_n_s_m"},
        ValidationCase{"EmptyElement",
                       [](MachineConfig& m) {
                         L(m).elements.push_back({"nothing", "bed", "column", 0.0, 0.0});
                       },
                       "elements[2]"},
        ValidationCase{"DriveUnconnected", [](MachineConfig& m) { L(m).elements[1].to = "bed"; },
                       "elements"},
        ValidationCase{"UnknownDriveMount",
                       [](MachineConfig& m) { L(m).driven_relative_to = "table"; },
                       "driven_relative_to"},
        ValidationCase{"UnknownOutputBody", [](MachineConfig& m) { L(m).output_body = "ground"; },
                       "output.body"},
        ValidationCase{"UnknownOutputReference",
                       [](MachineConfig& m) { L(m).output_relative_to = "driven"; },
                       "output.relative_to"},
        ValidationCase{"OutputRelativeToItself",
                       [](MachineConfig& m) { L(m).output_relative_to = "column"; },
                       "output.relative_to"},
        ValidationCase{"UnrestrainedBody",
                       [](MachineConfig& m) {
                         // A body tied to the column by a damper only has no rest position.
                         L(m).bodies.push_back({"cover", 10.0});
                         L(m).elements.push_back({"felt", "cover", "column", 0.0, 50.0});
                       },
                       "bodies[2].name"}),
    [](const testing::TestParamInfo<ValidationCase>& info) { return info.param.name; });

// Tests that a body held only by dampers is rejected and the message names the body.
TEST(LumpedMachine, UnrestrainedBodyIsNamed) {
  MachineConfig machine = ValidLumped();
  L(machine).elements[0].stiffness_n_m = 0.0;  // the bed now floats on its damped mounts
  try {
    machine.validate();
    FAIL() << "no ValidationError";
  } catch (const ValidationError& e) {
    EXPECT_EQ(e.field(), "bodies[0].name");
    EXPECT_NE(e.message().find("\"bed\""), std::string::npos) << e.message();
    EXPECT_NE(e.message().find("not restrained"), std::string::npos) << e.message();
  }
}

// Tests that the two-mass chain's natural frequencies solve the closed-form quadratic, its
// static deflection is the hand-computed spring sum, and the shares add up to one.
TEST(LumpedMachine, TwoMassChainFrequenciesAndStatic) {
  const double m1 = 300.0, m2 = 120.0, k1 = 4e7, k2 = 9e6;
  const MachineConfig machine = Lumped(BaseExcitedChain(m1, m2, k1, k2));
  const auto [w1_sq, w2_sq] = ChainOmegaSquared(m1, m2, k1, k2);

  const ModalAnalysis analysis = AnalyzeModes(machine);
  ASSERT_EQ(analysis.modes.size(), 2u);
  EXPECT_NEAR(analysis.modes[0].frequency_hz, std::sqrt(w1_sq) / kTwoPi, 1e-10);
  EXPECT_NEAR(analysis.modes[1].frequency_hz, std::sqrt(w2_sq) / kTwoPi, 1e-10);
  // Spring 1 carries the inertia of both masses, spring 2 that of m2 only.
  const double static_m = (m1 + m2) / k1 + m2 / k2;
  EXPECT_NEAR(analysis.static_deflection_per_accel_s2, static_m, 1e-13 * static_m);
  EXPECT_NEAR(analysis.modes[0].participation + analysis.modes[1].participation, 1.0, 1e-12);
  EXPECT_EQ(analysis.modes[0].damping_ratio, 0.0);

  const LinearPlant plant = BuildPlant(machine);
  EXPECT_NEAR(plant.StaticGain()(0, 0), -static_m, 1e-13 * static_m);
  EXPECT_NEAR(plant.max_frequency_rad_s, std::sqrt(w2_sq), 1e-9 * std::sqrt(w2_sq));
  EXPECT_TRUE(plant.B_vel.isZero());  // no damper: the drive velocity loads nothing
}

// Tests damping ratios and participations on two uncoupled oscillators (each on its own
// spring and damper to the driven point), where the modes are exactly the bodies:
// zeta = c / (2 sqrt(k m)), and the output A relative to B splits as -m_a/k_a vs +m_b/k_b.
TEST(LumpedMachine, UncoupledOscillatorsDampingAndShares) {
  const double ma = 50.0, ka = 2e6, ca = 400.0;  // 31.8 Hz
  const double mb = 10.0, kb = 4e6, cb = 250.0;  // 100.7 Hz
  LumpedMachineConfig config;
  config.bodies = {{"a", ma}, {"b", mb}};
  config.elements = {{"ea", "a", "driven", ka, ca}, {"eb", "driven", "b", kb, cb}};
  config.output_body = "a";
  config.output_relative_to = "b";
  const ModalAnalysis analysis = AnalyzeModes(Lumped(config));

  const double static_a = -ma / ka, static_b = -mb / kb;
  const double total = static_a - static_b;
  EXPECT_NEAR(analysis.static_deflection_per_accel_s2, std::abs(total), 1e-15);
  ASSERT_EQ(analysis.modes.size(), 2u);
  EXPECT_NEAR(analysis.modes[0].frequency_hz, std::sqrt(ka / ma) / kTwoPi, 1e-10);
  EXPECT_NEAR(analysis.modes[1].frequency_hz, std::sqrt(kb / mb) / kTwoPi, 1e-10);
  EXPECT_NEAR(analysis.modes[0].damping_ratio, ca / (2.0 * std::sqrt(ka * ma)), 1e-12);
  EXPECT_NEAR(analysis.modes[1].damping_ratio, cb / (2.0 * std::sqrt(kb * mb)), 1e-12);
  EXPECT_NEAR(analysis.modes[0].participation, static_a / total, 1e-12);
  EXPECT_NEAR(analysis.modes[1].participation, -static_b / total, 1e-12);
}

// Tests that mounting the drive on a body puts the drive's reaction on it: with the drive
// between bed and column, accelerating the column by a pushes the bed back by m_col a / k_bed
// statically, the column lags the bed by m_col a / k_guide, and the modes are those of the
// chain ground -k_bed- bed -k_guide- column. Mounted on ground, the bed stays unloaded.
TEST(LumpedMachine, DriveOnBodyLoadsThatBody) {
  const double m_bed = 4000.0, m_col = 1500.0, k_bed = 6e8, k_guide = 4e7;
  LumpedMachineConfig config;
  config.bodies = {{"bed", m_bed}, {"column", m_col}};
  config.elements = {{"mounts", "bed", "ground", k_bed, 0.0},
                     {"guides", "column", "driven", k_guide, 0.0}};
  config.driven_relative_to = "bed";
  config.output_body = "bed";

  EXPECT_NEAR(BuildPlant(Lumped(config)).StaticGain()(0, 0), -m_col / k_bed, 1e-12 * m_col / k_bed);
  const auto [w1_sq, w2_sq] = ChainOmegaSquared(m_bed, m_col, k_bed, k_guide);
  const ModalAnalysis on_bed = AnalyzeModes(Lumped(config));
  EXPECT_NEAR(on_bed.modes[0].frequency_hz, std::sqrt(w1_sq) / kTwoPi, 1e-10);
  EXPECT_NEAR(on_bed.modes[1].frequency_hz, std::sqrt(w2_sq) / kTwoPi, 1e-10);

  config.output_body = "column";
  config.output_relative_to = "bed";
  EXPECT_NEAR(BuildPlant(Lumped(config)).StaticGain()(0, 0), -m_col / k_guide,
              1e-12 * m_col / k_guide);

  config.driven_relative_to = "ground";
  config.output_body = "bed";
  config.output_relative_to = "ground";
  EXPECT_NEAR(BuildPlant(Lumped(config)).StaticGain()(0, 0), 0.0, 1e-20);
  const ModalAnalysis on_ground = AnalyzeModes(Lumped(config));
  EXPECT_NEAR(on_ground.modes[0].frequency_hz, std::sqrt(k_guide / m_col) / kTwoPi, 1e-10);
  EXPECT_NEAR(on_ground.modes[1].frequency_hz, std::sqrt(k_bed / m_bed) / kTwoPi, 1e-10);
}

// Tests the velocity input: a damper to ground on a body the drive moves through a spring
// loads it with -c v (B_vel = -c/m), and the state order is positions then velocities.
TEST(LumpedMachine, DamperToGroundLoadsDriveVelocity) {
  const double m = 20.0, k = 8e5, c = 300.0;
  LumpedMachineConfig config;
  config.bodies = {{"table", m}};
  config.elements = {{"screw", "driven", "table", k, 0.0}, {"way", "table", "ground", 0.0, c}};
  config.output_body = "table";
  const LinearPlant plant = BuildPlant(Lumped(config));
  ASSERT_EQ(plant.num_states(), 2);
  EXPECT_EQ(plant.state_kinds[0], StateKind::kPosition);
  EXPECT_EQ(plant.state_kinds[1], StateKind::kVelocity);
  EXPECT_NEAR(plant.A(1, 0), -k / m, 1e-9);
  EXPECT_NEAR(plant.A(1, 1), -c / m, 1e-12);
  EXPECT_NEAR(plant.B_accel(1, 0), -1.0, 1e-15);
  EXPECT_NEAR(plant.B_vel(1, 0), -c / m, 1e-12);
  EXPECT_EQ(plant.C(0, 0), 1.0);
  EXPECT_EQ(plant.C(0, 1), 0.0);
}

}  // namespace
}  // namespace shapebench::model
