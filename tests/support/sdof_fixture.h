// A single undamped 25 Hz mode driven by the kinematic drive: the patent's analysis case.
#pragma once

#include <random>

#include "bench/scenario/scenario.h"

namespace shapebench::bench::testing {

inline Scenario SdofScenario(double frequency_hz = 25.0, double damping_ratio = 0.0,
                             model::IntegratorMethod method = model::IntegratorMethod::kExact) {
  Scenario s;
  model::ModalMachineConfig modal;
  modal.modes = {model::ModalMode{frequency_hz, damping_ratio, 1.0}};
  s.machine.axes[s.machine.driven_axis] = model::MachineConfig{modal};
  s.controller.period_s = 0.001;
  s.controller.feed_mm_min = 30000;  // 0.5 m/s
  s.controller.accel_time_s = 0.3;   // 1.667 m/s^2 = 0.17 G (para. 21)
  s.controller.pattern.frequency_hz = 25.0;
  s.move.distance_mm = 213;  // cruise of 126 ms: 3.15 natural periods, not a whole number
  s.integrator.method = method;
  s.integrator.rtol = 1e-10;
  return s;
}

// A random single-axis move of one mode (seeded by the caller's generator): the mode's
// frequency and damping, the period, feed, acc/dec time, the pattern's design frequency and
// the distance, both directions (trial's parity). For tests that compare two paths of a run.
inline Scenario RandomSdofMove(std::mt19937* random, int trial) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Scenario s = SdofScenario(5.0 + 75.0 * u(*random), trial % 3 == 0 ? 0.0 : 0.3 * u(*random) * u(*random));
  s.controller.period_s = trial % 4 == 0 ? 0.002 : 0.001;
  s.controller.feed_mm_min = 1000.0 + 19000.0 * u(*random);
  s.controller.accel_time_s = 0.01 + 0.2 * u(*random);
  s.controller.pattern.frequency_hz = 10.0 + 40.0 * u(*random);
  s.move.distance_mm = (trial % 2 == 0 ? 1.0 : -1.0) * (1.0 + 299.0 * u(*random));
  return s;
}

}  // namespace shapebench::bench::testing
