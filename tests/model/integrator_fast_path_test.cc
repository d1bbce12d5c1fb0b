// The integrators' fast paths (docs/performance.md) against their plain step-by-step use:
// integrator.method auto, AdvancePeriod (the exact integrator's whole-period products;
// CVODE integrating across ticks where the input is held), SelectOutputs and
// OutputRowIsZero, CVODE memory reused across runs, the exact discretisation kept per thread.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "model/cvode_integrator.h"
#include "model/exact_integrator.h"
#include "model/integrator.h"
#include "model/machine.h"
#include "model/multi_axis_machine.h"

namespace shapebench::model {
namespace {

constexpr double kFastPathPeriodS = 0.001;

MachineConfig Modes(double frequency_hz, double zeta) {
  MachineConfig machine;
  machine.form = ModalMachineConfig{{{frequency_hz, zeta, 1.0}, {3.1 * frequency_hz, 0.05, -0.2}}};
  return machine;
}

MachineConfig SingleMode(double frequency_hz) {
  MachineConfig machine;
  machine.form = ModalMachineConfig{{{frequency_hz, 0.0, 1.0}}};
  return machine;
}

// A held acceleration per tick: runs (CVODE may integrate through them) and changes.
std::vector<double> Sequence() {
  std::vector<double> accel;
  auto hold = [&](double a, int ticks) { accel.insert(accel.end(), ticks, a); };
  hold(0.0, 2);
  hold(0.8, 20);
  hold(1.667, 60);
  hold(0.0, 45);
  hold(-1.667, 33);
  hold(0.0, 90);
  return accel;
}

// Runs `accel` tick by tick through SetInput and Step/Output: every output of every substep.
std::vector<double> Stepwise(PlantIntegrator& integrator, const std::vector<double>& accel) {
  std::vector<double> out;
  for (double a : accel) {
    integrator.SetInput(Eigen::VectorXd::Constant(1, a));
    for (int j = 0; j < integrator.substeps(); ++j) {
      integrator.Step();
      const Eigen::VectorXd y = integrator.Output();
      out.insert(out.end(), y.data(), y.data() + y.size());
    }
  }
  return out;
}

// The same through AdvancePeriod, with the master's promise of how long each input holds.
std::vector<double> Periodwise(PlantIntegrator& integrator, const std::vector<double>& accel) {
  std::vector<double> out;
  std::vector<double> buffer(static_cast<std::size_t>(integrator.substeps()) * integrator.output_width());
  for (std::size_t k = 0; k < accel.size(); ++k) {
    long same = 1;
    while (k + same < accel.size() && accel[k + same] == accel[k]) ++same;
    integrator.AdvancePeriod(&accel[k], same, buffer.data());
    out.insert(out.end(), buffer.begin(), buffer.end());
  }
  return out;
}

double MaxDifference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  return worst;
}

double MaxAbs(const std::vector<double>& a) {
  double worst = 0.0;
  for (double x : a) worst = std::max(worst, std::abs(x));
  return worst;
}

// Tests that method auto is the exact integrator for every plant there is (all linear), and
// that the other methods stay what they name.
TEST(IntegratorAuto, ResolvesToExactForLinearPlants) {
  const LinearPlant plant = BuildPlant(Modes(25.0, 0.02));
  EXPECT_EQ(ResolveMethod(IntegratorMethod::kAuto, plant), IntegratorMethod::kExact);
  EXPECT_EQ(ResolveMethod(IntegratorMethod::kCvode, plant), IntegratorMethod::kCvode);
  EXPECT_EQ(ResolveMethod(IntegratorMethod::kExact, plant), IntegratorMethod::kExact);
  IntegratorConfig config;
  config.method = IntegratorMethod::kAuto;
  auto integrator = MakeIntegrator(plant, config, kFastPathPeriodS, 4, 1.0);
  EXPECT_NE(dynamic_cast<ExactIntegrator*>(integrator.get()), nullptr);
  // A servo axis with a lumped structure is linear too.
  MultiAxisMachineConfig machine;
  DriveConfig servo;
  servo.type = DriveType::kServo;
  const MachinePlant servo_plant = BuildMachinePlant(machine, servo);
  EXPECT_EQ(ResolveMethod(IntegratorMethod::kAuto, servo_plant.plant), IntegratorMethod::kExact);
}

// Tests the exact integrator's whole-period products (a plant of at most 4 stepped states)
// against its own substep recursion: the same discretisation, so equal to rounding (1e-12
// of the largest output over 250 periods; a wrong power of phi or a missing forced term is
// off by far more), and the general (larger) plant bit for bit.
TEST(ExactIntegratorFastPath, PeriodProductsMatchTheSubstepRecursion) {
  for (const MachineConfig& machine : {SingleMode(25.0), Modes(25.0, 0.02)}) {
    const LinearPlant plant = BuildPlant(machine);
    ExactIntegrator stepwise(plant, kFastPathPeriodS, 5);
    ExactIntegrator periodwise(plant, kFastPathPeriodS, 5);
    const std::vector<double> a = Stepwise(stepwise, Sequence());
    const std::vector<double> b = Periodwise(periodwise, Sequence());
    EXPECT_LE(MaxDifference(a, b), 1e-12 * MaxAbs(a));
    EXPECT_GT(MaxAbs(a), 0.0);
    EXPECT_EQ(stepwise.Time(), periodwise.Time());
  }
  // Five modes: ten states, the general recursion in both.
  MachineConfig many;
  many.form = ModalMachineConfig{
      {{20.0, 0.01, 1.0}, {45.0, 0.02, 0.5}, {70.0, 0.0, -0.3}, {110.0, 0.03, 0.2}, {150.0, 0.0, 0.1}}};
  const LinearPlant plant = BuildPlant(many);
  ExactIntegrator stepwise(plant, kFastPathPeriodS, 5);
  ExactIntegrator periodwise(plant, kFastPathPeriodS, 5);
  EXPECT_EQ(Stepwise(stepwise, Sequence()), Periodwise(periodwise, Sequence()));
}

// Tests that the exact integrator steps only the states that reach an output (the drive
// velocity of a plant with B_vel = 0 does not) and that SelectOutputs and OutputRowIsZero
// agree with the full outputs.
TEST(ExactIntegratorFastPath, SteppedStatesAndSelectedRows) {
  const LinearPlant plant = BuildPlant(SingleMode(25.0));
  ExactIntegrator full(plant, kFastPathPeriodS, 4);
  EXPECT_EQ(full.num_stepped_states(), 2);  // q, q' (not the drive velocity)
  // A machine: one modelled axis (Y) of three; X and Z rows are 0 whatever the input.
  MultiAxisMachineConfig machine;
  const MachinePlant machine_plant = BuildMachinePlant(machine, DriveConfig{});
  IntegratorConfig config;
  config.method = IntegratorMethod::kExact;
  auto all = MakeIntegrator(machine_plant.plant, config, kFastPathPeriodS, 4, 1.0);
  auto some = MakeIntegrator(machine_plant.plant, config, kFastPathPeriodS, 4, 1.0);
  for (int row = 0; row < 6; ++row) {
    EXPECT_EQ(all->OutputRowIsZero(row), row % 3 != 1) << row;
  }
  some->SelectOutputs({kToolErrorRow + 1, kDeflectionRow + 1});
  EXPECT_EQ(some->output_width(), 2);
  std::vector<double> full_buffer(4 * 6);
  std::vector<double> some_buffer(4 * 2);
  for (double a : Sequence()) {
    const double input[3] = {0.0, a, 0.0};
    all->AdvancePeriod(input, 1, full_buffer.data());
    some->AdvancePeriod(input, 1, some_buffer.data());
    for (int j = 0; j < 4; ++j) {
      ASSERT_EQ(some_buffer[2 * j], full_buffer[6 * j + kToolErrorRow + 1]);
      ASSERT_EQ(some_buffer[2 * j + 1], full_buffer[6 * j + kDeflectionRow + 1]);
      ASSERT_EQ(full_buffer[6 * j], 0.0);
    }
  }
}

// Tests that the exact discretisation is computed once per thread for the same plant and
// period (the same object comes back), and again for another.
TEST(ExactIntegratorFastPath, DiscretisationIsKeptPerPlant) {
  const LinearPlant a = BuildPlant(SingleMode(25.0));
  const LinearPlant b = BuildPlant(SingleMode(26.0));
  const auto first = DiscretizeExactly(a, 2e-4);
  EXPECT_EQ(DiscretizeExactly(a, 2e-4).get(), first.get());
  EXPECT_NE(DiscretizeExactly(b, 2e-4).get(), first.get());
  EXPECT_NE(DiscretizeExactly(a, 1e-4).get(), first.get());
  EXPECT_NE(DiscretizeExactly(b, 2e-4)->phi, first->phi);
}

// Tests CVODE through AdvancePeriod, integrating across held ticks (the default), against
// the exact integrator: 1e-6 of the largest deflection at rtol 1e-8 (the bound the
// step-by-step use meets in cvode_integrator_test.cc); and that it does take fewer internal
// steps than stopping at every tick (what integrating across ticks is for).
TEST(CvodeFastPath, AcrossHeldTicksTracksTheExactSolution) {
  const LinearPlant plant = BuildPlant(Modes(25.0, 0.02));
  IntegratorConfig config;
  config.rtol = 1e-8;
  auto exact_config = config;
  exact_config.method = IntegratorMethod::kExact;
  auto exact = MakeIntegrator(plant, exact_config, kFastPathPeriodS, 4, 1.667);
  auto across = MakeIntegrator(plant, config, kFastPathPeriodS, 4, 1.667);
  config.tuning.input_mode = CvodeInputMode::kStopEveryTick;
  auto stopping = MakeIntegrator(plant, config, kFastPathPeriodS, 4, 1.667);
  const std::vector<double> reference = Stepwise(*exact, Sequence());
  const std::vector<double> a = Periodwise(*across, Sequence());
  const std::vector<double> b = Periodwise(*stopping, Sequence());
  EXPECT_LE(MaxDifference(a, reference), 1e-6 * MaxAbs(reference));
  EXPECT_LE(MaxDifference(b, reference), 1e-6 * MaxAbs(reference));
  EXPECT_LT(across->Stats().steps, stopping->Stats().steps);
  EXPECT_EQ(across->Stats().reinits, stopping->Stats().reinits);  // only where a changes
}

// Tests that CVODE's memory taken from the thread's pool (used by a previous integrator)
// gives the same outputs and counters, bit for bit, as fresh memory, for Adams and BDF.
TEST(CvodeFastPath, ReusedMemoryGivesTheSameRun) {
  const LinearPlant plant = BuildPlant(Modes(25.0, 0.02));
  for (CvodeLmm lmm : {CvodeLmm::kAdams, CvodeLmm::kBdf}) {
    IntegratorConfig fresh_config;
    fresh_config.lmm = lmm;
    fresh_config.tuning.reuse_memory = false;
    CvodeIntegrator fresh(plant, fresh_config, kFastPathPeriodS, 4, 1.667);
    EXPECT_FALSE(fresh.reused_memory());
    const std::vector<double> reference = Periodwise(fresh, Sequence());
    IntegratorConfig pooled_config = fresh_config;
    pooled_config.tuning.reuse_memory = true;
    {
      // Leaves its memory in the pool, after a different run (other tolerances, inputs).
      IntegratorConfig other = pooled_config;
      other.rtol = 1e-5;
      CvodeIntegrator first(plant, other, kFastPathPeriodS, 4, 0.3);
      Periodwise(first, std::vector<double>(50, 0.7));
    }
    CvodeIntegrator reused(plant, pooled_config, kFastPathPeriodS, 4, 1.667);
    EXPECT_TRUE(reused.reused_memory());
    EXPECT_EQ(Periodwise(reused, Sequence()), reference);
    EXPECT_EQ(reused.Stats().steps, fresh.Stats().steps);
    EXPECT_EQ(reused.Stats().rhs_evals, fresh.Stats().rhs_evals);
  }
}

// Tests that the vector kernels are part of what a pooled memory is taken for (CVODE's
// vectors get theirs when created), and that either gives the same run bit for bit: ours
// compute what SUNDIALS' do, in the same order (serial_vector_ops_test.cc).
TEST(CvodeFastPath, VectorKernelsGiveTheSameRun) {
  const LinearPlant plant = BuildPlant(Modes(25.0, 0.02));
  IntegratorConfig config;
  std::vector<double> ours;
  {
    CvodeIntegrator optimized(plant, config, kFastPathPeriodS, 4, 1.667);
    ours = Periodwise(optimized, Sequence());
  }
  config.tuning.optimized_vector_ops = false;
  CvodeIntegrator packaged(plant, config, kFastPathPeriodS, 4, 1.667);
  EXPECT_FALSE(packaged.reused_memory());  // the optimised one's memory is not taken
  EXPECT_EQ(Periodwise(packaged, Sequence()), ours);
}

// Tests that the Hermite output (the default) takes CVODE through the same internal steps
// as CVODE's own interpolation and gives the same outputs to within the tolerance's order:
// both are within about rtol of the state's amplitude of the step's polynomial (CVODE's
// interpolation of its Nordsieck history, the Hermite one below rtol / 10 by its bound), so
// they differ by at most ~2 rtol of the largest output; one in 1e5 is an output wrong in its
// fifth digit. On this vibrating run every substep is Hermite's.
TEST(CvodeFastPath, HermiteOutputMatchesCvodesInterpolation) {
  const LinearPlant plant = BuildPlant(Modes(25.0, 0.02));
  IntegratorConfig config;
  config.rtol = 1e-8;
  config.tuning.output = CvodeOutput::kCvodeInterpolation;
  CvodeIntegrator cvode_output(plant, config, kFastPathPeriodS, 4, 1.667);
  config.tuning.output = CvodeOutput::kHermite;
  CvodeIntegrator hermite(plant, config, kFastPathPeriodS, 4, 1.667);
  const std::vector<double> reference = Periodwise(cvode_output, Sequence());
  const std::vector<double> ours = Periodwise(hermite, Sequence());
  const double difference = MaxDifference(ours, reference) / MaxAbs(reference);
  std::printf("Hermite vs CVODE's interpolation: %.3g of the largest output\n", difference);
  EXPECT_LE(difference, 2e-8);
  EXPECT_GT(difference, 0.0);  // two interpolations, not one
  EXPECT_EQ(hermite.Stats().steps, cvode_output.Stats().steps);
  EXPECT_EQ(hermite.Stats().rhs_evals, cvode_output.Stats().rhs_evals);
  EXPECT_EQ(hermite.cvode_interpolated_substeps(), 0);
  EXPECT_EQ(cvode_output.cvode_interpolated_substeps(), 0);  // counts Hermite's fallbacks only
}

// Tests that a step too long for the Hermite bound (rho h above (rtol / 10 8! 2^8)^(1/8)) is
// left to CVODE's interpolation: an undamped mode pushed for exactly its period (40 ms at
// 25 Hz) is left at rest, so CVODE's steps then grow far beyond the bound, as in case 1's
// cruise; the outputs still track the exact solution to 1e-6 of the largest (the bound
// CvodeFastPath.AcrossHeldTicksTracksTheExactSolution holds).
TEST(CvodeFastPath, LongStepsFallBackToCvodesInterpolation) {
  const LinearPlant plant = BuildPlant(SingleMode(25.0));
  std::vector<double> accel(400, 0.0);
  std::fill(accel.begin() + 2, accel.begin() + 42, 1.667);
  IntegratorConfig config;
  config.rtol = 1e-8;
  config.method = IntegratorMethod::kExact;
  auto exact = MakeIntegrator(plant, config, kFastPathPeriodS, 4, 1.667);
  config.method = IntegratorMethod::kCvode;
  CvodeIntegrator hermite(plant, config, kFastPathPeriodS, 4, 1.667);
  const std::vector<double> reference = Stepwise(*exact, accel);
  const std::vector<double> ours = Periodwise(hermite, accel);
  EXPECT_LE(MaxDifference(ours, reference), 1e-6 * MaxAbs(reference));
  EXPECT_GT(hermite.cvode_interpolated_substeps(), 0);
  EXPECT_LT(hermite.cvode_interpolated_substeps(), static_cast<long>(4 * accel.size()));
}

// Tests that every CVODE choice benchmarks/ measures (tuning) still tracks the exact
// solution: the choices change the cost, not the answer, at the same rtol (1e-5 of the
// largest deflection here: the restarted and scalar-tolerance variants are a little less
// accurate at rtol 1e-8).
TEST(CvodeFastPath, EveryTuningChoiceTracksTheExactSolution) {
  const LinearPlant plant = BuildPlant(Modes(25.0, 0.02));
  IntegratorConfig exact_config;
  exact_config.method = IntegratorMethod::kExact;
  auto exact = MakeIntegrator(plant, exact_config, kFastPathPeriodS, 4, 1.667);
  const std::vector<double> reference = Stepwise(*exact, Sequence());
  std::vector<CvodeTuning> choices(10);
  choices[1].input_mode = CvodeInputMode::kRestartEveryTick;
  choices[2].jacobian = false;
  choices[3].per_state_atol = false;
  choices[4].reuse_memory = false;
  choices[5].fixed_point = true;
  choices[6].max_order = 5;
  choices[7].output = CvodeOutput::kCvodeInterpolation;
  choices[8].eta_max_fixed_step = 1.5;
  choices[9].optimized_vector_ops = false;
  for (std::size_t i = 0; i < choices.size(); ++i) {
    IntegratorConfig config;
    config.tuning = choices[i];
    auto cvode = MakeIntegrator(plant, config, kFastPathPeriodS, 4, 1.667);
    EXPECT_LE(MaxDifference(Periodwise(*cvode, Sequence()), reference), 1e-5 * MaxAbs(reference)) << i;
  }
}

// Tests that each integrator's capability query names the fast paths it offers, and only
// those: the exact integrator the in-period extremum and the tail at rest (deferred
// substeps where its block kernel runs: at most kMaxBlock stepped states), CVODE the held
// inputs in its continuous mode only; a fast path not offered throws instead of answering.
TEST(IntegratorCapabilities, EachIntegratorNamesItsFastPaths) {
  IntegratorConfig exact_config;
  exact_config.method = IntegratorMethod::kExact;
  const LinearPlant small = BuildPlant(Modes(25.0, 0.02));  // 4 stepped states
  MachineConfig many;
  many.form = ModalMachineConfig{{{20.0, 0.01, 1.0}, {45.0, 0.02, 0.5}, {70.0, 0.0, -0.3}}};
  const LinearPlant large = BuildPlant(many);  // 6 stepped states
  const IntegratorCapabilities exact = MakeIntegrator(small, exact_config, kFastPathPeriodS, 4, 1.0)->Capabilities();
  EXPECT_TRUE(exact.period_extremum && exact.advance_at_rest && exact.deferred_substeps);
  EXPECT_FALSE(exact.input_holds);
  const IntegratorCapabilities exact_large =
      MakeIntegrator(large, exact_config, kFastPathPeriodS, 4, 1.0)->Capabilities();
  EXPECT_TRUE(exact_large.period_extremum && exact_large.advance_at_rest);
  EXPECT_FALSE(exact_large.deferred_substeps);

  IntegratorConfig cvode_config;
  auto cvode = MakeIntegrator(small, cvode_config, kFastPathPeriodS, 4, 1.0);
  const IntegratorCapabilities continuous = cvode->Capabilities();
  EXPECT_TRUE(continuous.input_holds);
  EXPECT_FALSE(continuous.period_extremum || continuous.advance_at_rest || continuous.deferred_substeps);
  cvode_config.tuning.input_mode = CvodeInputMode::kStopEveryTick;
  EXPECT_FALSE(MakeIntegrator(small, cvode_config, kFastPathPeriodS, 4, 1.0)->Capabilities().input_holds);
  EXPECT_THROW(cvode->WatchExtremum(kDeflectionRow), std::logic_error);
  EXPECT_THROW(cvode->AdvanceAtRest(3), std::logic_error);
  std::vector<double> buffer(4 * 6);
  const double input = 0.0;
  EXPECT_THROW(cvode->AdvancePeriodToEnd(&input, buffer.data()), std::logic_error);
}

// Tests that the exact integrator's AdvanceAtRest (the state advanced by a power of the
// transition matrix, by squaring) lands where as many zero-input periods of AdvancePeriod
// do, to the rounding of ~60 matrix products (1e-12 of the state's largest component).
TEST(IntegratorCapabilities, AdvanceAtRestMatchesZeroInputPeriods) {
  IntegratorConfig config;
  config.method = IntegratorMethod::kExact;
  const LinearPlant plant = BuildPlant(Modes(25.0, 0.02));
  auto squared = MakeIntegrator(plant, config, kFastPathPeriodS, 4, 1.667);
  auto stepped = MakeIntegrator(plant, config, kFastPathPeriodS, 4, 1.667);
  Periodwise(*squared, Sequence());
  Periodwise(*stepped, Sequence());
  constexpr long kRestPeriods = 37;
  squared->AdvanceAtRest(kRestPeriods);
  Periodwise(*stepped, std::vector<double>(kRestPeriods, 0.0));
  const Eigen::VectorXd a = squared->PlantState();
  const Eigen::VectorXd b = stepped->PlantState();
  EXPECT_GT(a.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-12 * b.cwiseAbs().maxCoeff());
  EXPECT_EQ(squared->Time(), stepped->Time());
}

}  // namespace
}  // namespace shapebench::model
