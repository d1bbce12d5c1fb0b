// Friction laws against their closed forms (docs/nonlinear.md), through the whole path a run
// takes: the lumped form, BuildMachinePlant, NonlinearCvodeIntegrator. A body hangs on a
// damped spring from the driven point and rubs on the ground through the element under
// test; under the kinematic drive the body's deflection y (relative to the driven point) is
// -F_spring / k, and at rest relative to the drive the spring carries exactly the friction.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "model/integrator.h"
#include "model/multi_axis_machine.h"
#include "model/nonlinear_integrator.h"
#include "tests/support/axes.h"

namespace shapebench::model {
namespace {

constexpr double kFrictionMassKg = 10.0;
constexpr double kFrictionCoulombN = 60.0;
constexpr double kStaticN = 100.0;
constexpr double kStribeckMS = 1.0e-3;
constexpr double kViscousNSM = 50.0;
constexpr double kSigma0NM = 1.0e7;
constexpr double kSigma1NSM = 2.0e3;

FrictionConfig Friction(FrictionModel model) {
  FrictionConfig f;
  f.model = model;
  f.coulomb_n = kFrictionCoulombN;
  f.static_n = kStaticN;
  f.stribeck_velocity_m_s = kStribeckMS;
  f.viscous_n_s_m = kViscousNSM;
  if (model == FrictionModel::kLuGre) {
    f.sigma0_n_m = kSigma0NM;
    f.sigma1_n_s_m = kSigma1NSM;
  }
  return f;
}

// The body on its spring and damper from the driven point, `friction` to the ground; Y.
NonlinearPlant BodyOnGround(const FrictionConfig& friction, double spring_n_m, double damper_n_s_m) {
  LumpedMachineConfig lumped;
  lumped.bodies = {{"body", kFrictionMassKg}};
  LumpedElement ground{"ways", "body", "ground"};
  ground.friction = friction;
  lumped.elements = {{"spring", "body", "driven", spring_n_m, damper_n_s_m}, ground};
  lumped.output_body = "body";
  MultiAxisMachineConfig machine;
  machine.axes[kY] = MachineConfig{lumped};
  const MachinePlant built = BuildMachinePlant(machine, DriveConfig{});
  return {built.plant, built.nonlinear, built.following_error_axis};
}

std::unique_ptr<PlantIntegrator> Integrator(const NonlinearPlant& plant, double period_s, int substeps = 1) {
  IntegratorConfig config;
  config.method = IntegratorMethod::kAuto;
  return MakePlantIntegrator(plant, config, period_s, substeps, 1.0, 1.0);
}

// Tests that steady sliding at a held drive speed v gives the Stribeck curve
// F_c + (F_s - F_c) exp(-(v/v_s)^2) + sigma2 v within 0.5%, from 1e-5 to 1 m/s, for LuGre
// (after its bristles settle: ten times F_s / (sigma0 v), at least 0.2 s) and for the
// event-based Stribeck law. The body starts sliding with the drive (Reset at speed v) on a
// stiff, critically damped spring (1e9 N/m, 2e5 N s/m): steady sliding is then stable (the
// curve's steepest fall, 3.4e4 N s/m, is far below the damper's 2e5), where a soft spring
// would stick and slip.
TEST(FrictionOracle, SteadySlidingFollowsTheStribeckCurve) {
  constexpr double kSpringNM = 1.0e9;
  for (FrictionModel model : {FrictionModel::kLuGre, FrictionModel::kStribeck}) {
    const NonlinearPlant plant = BodyOnGround(Friction(model), kSpringNM, 2.0e5);
    for (double v : {1e-5, 3e-5, 1e-4, 3e-4, 1e-3, 2e-3, 1e-2, 1e-1, 1.0}) {
      const double settle_s = std::max(0.2, 10.0 * kStaticN / (kSigma0NM * v));
      const double period_s = 0.01;
      auto integrator = Integrator(plant, period_s);
      integrator->Reset(Eigen::Vector3d(0.0, v, 0.0));
      const long ticks = std::lround(settle_s / period_s);
      std::vector<double> out(static_cast<std::size_t>(integrator->num_outputs()));
      const double zero[3] = {0.0, 0.0, 0.0};
      for (long k = 0; k < ticks; ++k) integrator->AdvancePeriod(zero, ticks - k, out.data());
      const double spring_n = -kSpringNM * out[kDeflectionRow + kY];
      const double expected = kFrictionCoulombN + (kStaticN - kFrictionCoulombN) * std::exp(-std::pow(v / kStribeckMS, 2)) +
                              kViscousNSM * v;
      EXPECT_NEAR(spring_n, expected, 0.005 * expected)
          << (model == FrictionModel::kLuGre ? "lugre" : "stribeck") << " at v = " << v << " m/s";
      EXPECT_DOUBLE_EQ(Friction(model).SteadyForce(v), expected);
    }
  }
}

// Tests LuGre's presliding: from rest, the drive creeping at 1 um/s loads the bristles, and
// the body's displacement x at friction force F (the spring's, quasi-static: the body's
// speed is creep / 11, so sigma1 z' and sigma2 w are 2e-4 N) follows the LuGre law under a
// force ramp. At a speed w far below v_s, dz/dx = 1 - sigma0 z / g with g = g(w) the Stribeck
// curve's value (here F_s less 4e-5 N), so x = -(g / sigma0) ln(1 - F / g) exactly; checked
// within 1% for every F up to 0.1 F_c. Its series, x = (F / sigma0)(1 + F / (2 g) + ...),
// puts F / sigma0 off by about F / (2 g): the linear presliding F / sigma0 holds within 1%
// only up to F of about 0.02 g, not up to 0.1 F_c (there it is 3% off, F_c < g). So F / sigma0
// is checked within 1% where the closed form itself is within 0.75% of it, and at the
// largest F the departure from F / sigma0 is checked to be the log's, F / (2 g) within 10%.
TEST(FrictionOracle, LuGrePreslidingIsTheBristleDeflection) {
  // No damper: the spring alone carries the friction force (the bristles' sigma1 damps).
  constexpr double kSpringNM = 1.0e6;
  const NonlinearPlant plant = BodyOnGround(Friction(FrictionModel::kLuGre), kSpringNM, 0.0);
  const double period_s = 0.001;
  const double creep_m_s = 1e-6;
  // The Stribeck curve at the creep speed (the body is slower: g is closer still to F_s).
  const double g = kFrictionCoulombN + (kStaticN - kFrictionCoulombN) * std::exp(-std::pow(creep_m_s / kStribeckMS, 2));
  auto integrator = Integrator(plant, period_s);
  integrator->Reset(Eigen::Vector3d::Zero());
  std::vector<double> out(static_cast<std::size_t>(integrator->num_outputs()));
  // One tick of acceleration to the creep speed: u(t) = creep (t - period / 2) after it.
  const double start[3] = {0.0, creep_m_s / period_s, 0.0};
  integrator->AdvancePeriod(start, 1, out.data());
  const double zero[3] = {0.0, 0.0, 0.0};
  const long ticks = 8000;  // 8 s: F reaches 0.11 F_c
  int checked = 0;
  int linear = 0;
  double last_force = 0.0;
  double last_departure = 0.0;
  for (long k = 2; k <= ticks; ++k) {
    integrator->AdvancePeriod(zero, ticks - k + 1, out.data());
    if (k % 500 != 0) continue;
    const double t = static_cast<double>(k) * period_s;
    const double y = out[kDeflectionRow + kY];
    const double force = -kSpringNM * y;
    const double x = creep_m_s * (t - 0.5 * period_s) + y;  // the body's own displacement
    if (force > 0.1 * kFrictionCoulombN) break;
    const double closed = -(g / kSigma0NM) * std::log(1.0 - force / g);
    EXPECT_NEAR(x, closed, 0.01 * closed) << "F = " << force << " N";
    const double linear_m = force / kSigma0NM;
    if (std::abs(closed - linear_m) <= 0.0075 * linear_m) {
      EXPECT_NEAR(x, linear_m, 0.01 * linear_m) << "F = " << force;
      ++linear;
    }
    last_force = force;
    last_departure = (x - linear_m) / linear_m;
    ++checked;
  }
  EXPECT_GE(checked, 10);
  EXPECT_GE(linear, 2);
  // Near 0.1 F_c: F / sigma0 is off by the log's F / (2 g), about 3%, beyond 1%.
  EXPECT_GT(last_force, 0.09 * kFrictionCoulombN);
  EXPECT_NEAR(last_departure, last_force / (2.0 * g), 0.1 * last_force / (2.0 * g));
  EXPECT_GT(last_departure, 0.01);
}

// ---- Stick-slip at low feed: the body pulled through its spring by the drive at speed V ----

// A run from rest: one tick of acceleration to V, then V held; per output substep the time,
// the spring's force F = -k y and the body's displacement x = u + y (u the driven point's).
struct Dragged {
  std::vector<double> time_s;
  std::vector<double> force_n;
  std::vector<double> body_m;
};

Dragged Drag(const NonlinearPlant& plant, double spring_n_m, double speed_m_s, double duration_s, int substeps) {
  const double period_s = 0.001;
  auto integrator = Integrator(plant, period_s, substeps);
  integrator->Reset(Eigen::Vector3d::Zero());
  std::vector<double> out(static_cast<std::size_t>(integrator->num_outputs() * substeps));
  const double start[3] = {0.0, speed_m_s / period_s, 0.0};
  const double zero[3] = {0.0, 0.0, 0.0};
  const long ticks = std::lround(duration_s / period_s);
  Dragged run;
  for (long k = 1; k <= ticks; ++k) {
    integrator->AdvancePeriod(k == 1 ? start : zero, k == 1 ? 1 : ticks - k + 1, out.data());
    for (int j = 0; j < substeps; ++j) {
      const double t = (static_cast<double>(k - 1) + static_cast<double>(j + 1) / substeps) * period_s;
      const double u = k == 1 ? 0.5 * speed_m_s / period_s * t * t : speed_m_s * (t - 0.5 * period_s);
      const double y = out[static_cast<std::size_t>(j * integrator->num_outputs() + kDeflectionRow + kY)];
      run.time_s.push_back(t);
      run.force_n.push_back(-spring_n_m * y);
      run.body_m.push_back(u + y);
    }
  }
  return run;
}

// The slip phases of a run: [first, last] sample indices over which the body moves (a stuck
// body keeps its position to rounding, 1e-18 m here; slipping it moves 1e-7 m a sample).
std::vector<std::pair<std::size_t, std::size_t>> Slips(const Dragged& run) {
  std::vector<std::pair<std::size_t, std::size_t>> slips;
  bool moving = false;
  for (std::size_t i = 1; i < run.body_m.size(); ++i) {
    const bool now = std::abs(run.body_m[i] - run.body_m[i - 1]) > 1e-12;
    if (now && !moving) slips.emplace_back(i, i);
    if (now) slips.back().second = i;
    moving = now;
  }
  return slips;
}

// Tests the stick-slip cycle of Coulomb friction with stiction (F_s > F_c, no damping)
// against its closed form. A slip starts from rest at F = F_s; then m u'' + k u = -F_c for
// the body less the drive, so the body's speed is V (1 - cos wt) + (F_s - F_c) w/k sin wt
// and it stops again at w t_slip = 2 (pi - atan((F_s - F_c) w / (k V))), the force at
// F_c - R at its lowest, R = sqrt((F_s - F_c)^2 + (k V / w)^2), and at F_end = F_c +
// (F_s - F_c) cos 2a - (k V / w) sin 2a (a that atan) when the body sticks; stuck, F climbs
// at k V back to F_s. In the low-speed limit the drop is 2 (F_s - F_c) and the slip half a
// period of the undamped oscillator, pi / w (here 4e-5 and 0.8% from the exact values).
// Bounds: the force's sawtooth 1e-3 of the drop (its top is sampled within k V dt = 1e-3 N
// of F_s); the slip's and the cycle's durations 0.5% (a slip's ends are located to a
// sample, 25 us of 31.7 ms); pi / w 1.5% (0.8% its own, the rest sampling).
TEST(FrictionOracle, StickSlipAtLowFeedFollowsTheClosedForm) {
  constexpr double kSpringNM = 1.0e5;  // w = 100 rad/s on the 10 kg body
  constexpr double kSpeedMS = 5.0e-4;
  FrictionConfig friction;
  friction.model = FrictionModel::kCoulomb;
  friction.coulomb_n = kFrictionCoulombN;
  friction.static_n = kStaticN;
  const NonlinearPlant plant = BodyOnGround(friction, kSpringNM, 0.0);
  const int substeps = 40;
  const Dragged run = Drag(plant, kSpringNM, kSpeedMS, 6.0, substeps);
  const auto slips = Slips(run);
  ASSERT_GE(slips.size(), 3u) << "the body must stop and slip again repeatedly";

  const double w = std::sqrt(kSpringNM / kFrictionMassKg);
  const double excess = kStaticN - kFrictionCoulombN;
  const double drift = kSpringNM * kSpeedMS / w;
  const double a = std::atan(excess * w / (kSpringNM * kSpeedMS));
  const double slip_s = 2.0 * (M_PI - a) / w;
  const double lowest = kFrictionCoulombN - std::hypot(excess, drift);
  const double end = kFrictionCoulombN + excess * std::cos(2.0 * a) - drift * std::sin(2.0 * a);
  const double cycle_s = slip_s + (kStaticN - end) / (kSpringNM * kSpeedMS);
  const double dt = run.time_s[1] - run.time_s[0];
  for (std::size_t s = 0; s + 1 < slips.size(); ++s) {
    const auto [first, last] = slips[s];
    // The force before the slip (the stuck body's F at breakaway) and its lowest in the slip.
    const double top = run.force_n[first - 1];
    double bottom = top;
    for (std::size_t i = first; i <= last + 1; ++i) bottom = std::min(bottom, run.force_n[i]);
    EXPECT_NEAR(top, kStaticN, 1e-3 * 2.0 * excess) << "slip " << s;
    EXPECT_NEAR(top - bottom, kStaticN - lowest, 1e-3 * 2.0 * excess) << "slip " << s;
    EXPECT_NEAR(top - bottom, 2.0 * excess, 1e-3 * 2.0 * excess) << "slip " << s << ": the low-speed limit";
    EXPECT_NEAR(run.force_n[last + 1], end, 1e-3 * 2.0 * excess) << "slip " << s << ": where it sticks";
    // From the last stuck sample before the slip to the first stuck one after it.
    EXPECT_NEAR(static_cast<double>(last + 2 - first) * dt, slip_s, 0.005 * slip_s) << "slip " << s;
    EXPECT_NEAR(static_cast<double>(last + 2 - first) * dt, M_PI / w, 0.015 * M_PI / w) << "slip " << s;
    const double between = run.time_s[slips[s + 1].first] - run.time_s[first];
    EXPECT_NEAR(between, cycle_s, 0.005 * cycle_s) << "slip " << s;
  }
}

// Tests Stribeck friction (F_s > F_c falling to F_c above v_s) on a damped spring (damping
// ratio 0.2): dragged at half of v_s the body sticks and slips (its speed back to 0 again
// and again, each slip starting where the holding force, spring and damper, reaches F_s:
// the spring at F_s - c V, within 1e-3 of F_s - F_c); at 100
// v_s it slides steadily after the first breakaway (never stuck again) with the spring
// carrying the Stribeck curve's force there, F_c + (F_s - F_c) exp(-(V/v_s)^2) (the damper
// carries nothing at steady sliding), within 0.5% as the steady-sliding oracle above.
TEST(FrictionOracle, StribeckSticksAndSlipsAtLowFeedAndSlidesAtHighFeed) {
  constexpr double kSpringNM = 1.0e5;
  const double damper_n_s_m = 2.0 * 0.2 * std::sqrt(kSpringNM * kFrictionMassKg);
  FrictionConfig friction = Friction(FrictionModel::kStribeck);
  friction.viscous_n_s_m = 0.0;
  const NonlinearPlant plant = BodyOnGround(friction, kSpringNM, damper_n_s_m);

  const double slow_m_s = 0.5 * kStribeckMS;
  const Dragged low = Drag(plant, kSpringNM, slow_m_s, 6.0, 10);
  const auto low_slips = Slips(low);
  ASSERT_GE(low_slips.size(), 3u) << "stick-slip at half of v_s";
  for (const auto& [first, last] : low_slips) {
    // Stuck, the damper carries c V of the holding force: the spring breaks away at F_s - c V.
    EXPECT_NEAR(low.force_n[first - 1], kStaticN - damper_n_s_m * slow_m_s, 1e-3 * (kStaticN - kFrictionCoulombN));
    double bottom = kStaticN;
    for (std::size_t i = first; i <= last; ++i) bottom = std::min(bottom, low.force_n[i]);
    EXPECT_LT(bottom, kFrictionCoulombN) << "a sawtooth: the force falls below F_c in the slip";
  }

  const double fast_m_s = 100.0 * kStribeckMS;
  const Dragged high = Drag(plant, kSpringNM, fast_m_s, 1.0, 10);
  const auto high_slips = Slips(high);
  ASSERT_EQ(high_slips.size(), 1u) << "one breakaway, then steady sliding";
  EXPECT_EQ(high_slips[0].second, high.body_m.size() - 1);
  const double expected = kFrictionCoulombN + (kStaticN - kFrictionCoulombN) * std::exp(-std::pow(fast_m_s / kStribeckMS, 2));
  EXPECT_NEAR(high.force_n.back(), expected, 0.005 * expected);
}

}  // namespace
}  // namespace shapebench::model
