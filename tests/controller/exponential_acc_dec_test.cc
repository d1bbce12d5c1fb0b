// Oracle: the closed-form response of a first-order lag to a velocity ramp.
#include "controller/exponential_acc_dec.h"

#include <cmath>

#include <gtest/gtest.h>

namespace shapebench::controller {
namespace {

// Tests that the lag's samples follow y(t) = r (t - tau (1 - e^{-t/tau})) for a ramp
// input u = r t, exactly at the ticks (the discretisation is exact for linear input).
TEST(ExponentialAccDecTest, MatchesTheClosedFormRampResponse) {
  const double tau = 1.0 / 30.0;
  const double r = 2.0;
  CommandTrajectory ramp;
  ramp.period_s = 1e-3;
  for (int k = 0; k <= 100; ++k) ramp.velocity_m_s.push_back(r * k * 1e-3);
  ramp.velocity_m_s.push_back(0.0);  // ends at rest (a sharp stop, irrelevant before)
  const CommandTrajectory out = ApplyExponentialAccDec(ramp, tau);
  for (int k = 0; k <= 100; ++k) {
    const double t = k * 1e-3;
    ASSERT_NEAR(out.velocity_m_s[k], r * (t - tau * (1 - std::exp(-t / tau))), 1e-14) << k;
  }
}

// Tests that no motion is lost: the filtered move covers the input distance to 1e-12 m,
// and ends at rest.
TEST(ExponentialAccDecTest, ConservesTheDistance) {
  CommandTrajectory in;
  in.period_s = 1e-3;
  in.velocity_m_s = {0.0};
  for (int k = 1; k < 400; ++k) in.velocity_m_s.push_back(0.1 + 0.05 * std::sin(k * 0.1));
  in.velocity_m_s.push_back(0.0);
  const CommandTrajectory out = ApplyExponentialAccDec(in, 0.05);
  EXPECT_NEAR(out.Positions().back(), in.Positions().back(), 1e-12);
  EXPECT_EQ(out.velocity_m_s.back(), 0.0);
  EXPECT_GT(out.num_ticks(), in.num_ticks());
}

}  // namespace
}  // namespace shapebench::controller
