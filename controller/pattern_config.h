// `controller.pattern`: which shaper shapes the acc/dec phases, for which mode(s), and how
// it reaches the command. The shapers themselves (the patent's methods 1-4 and the
// library) are entries of the shaper registry (controller/shaper_registry.h), named by
// `method`.
#pragma once

#include <string>
#include <vector>

#include "controller/impulse.h"

namespace shapebench::controller {

// Para. 49 of JP2551868B2 (seed 004), mode 0..3: off, start of acc/dec only, end only, both.
enum class PatternMode { kOff, kStart, kEnd, kBoth };
// How the pattern reaches the command (seed 004): `stepped`, acceleration steps of the
// pre-interpolation linear acc/dec (paras. 36-50); `profile_table`, the pattern's jerk
// impulses as a post-interpolation profile table convolved with the move pulses
// (paras. 52-61). A table shapes every speed change at both ends (mode both).
enum class PatternRealization { kStepped, kProfileTable };

// The key of the shaper that does not shape (controller/shapers/none.cc).
inline constexpr char kNoShaping[] = "none";

struct PatternConfig {
  // The shaper: the key of a registry entry ("none", "1".."4", "zv", ...; ShaperKeys()).
  std::string method = kNoShaping;
  PatternMode mode = PatternMode::kBoth;
  double frequency_hz = 25.0;  // the natural frequency the pattern is designed for
  // Several modes at once: one shaper per frequency, convolved (ShaperImpulses). Empty:
  // the single mode `frequency_hz`.
  std::vector<double> frequencies_hz;
  // Library shapers: the damping ratio of the mode(s) they are designed for, in [0, 1).
  double design_damping_ratio = 0.0;
  // Several modes of their own damping: one ratio per design frequency (as many as
  // frequencies_hz), each in [0, 1); it replaces design_damping_ratio. Empty: every mode
  // is designed with design_damping_ratio.
  std::vector<double> damping_ratios;
  // What the scenario leaves to the machine (frequency_hz not given or `machine`,
  // `frequencies_hz: machine`, `design_damping_ratio: machine`). The controller designs
  // for the numbers above as they stand; the scenario loader first replaces them with
  // the machine's participating modes (bench/scenario/pattern_defaults.h).
  bool frequency_from_machine = false;
  bool frequencies_from_machine = false;
  bool damping_from_machine = false;
  double vibration_tolerance = 0.05;  // ei*: the residual allowed in each hump
  int impulse_count = 3;                  // mzv_n: the number of impulses, 3..16
  double impulse_spacing_periods = 0.375;  // mzv_n: their spacing in damped periods, (1/4, 1/2]
  std::vector<Impulse> impulses;      // custom: amplitudes summing to 1, times ascending
  double k1 = 0.675;           // method 3: 0.5 <= k1 <= 1
  double t1_s = 0.004;         // method 4: 0 <= t1 <= T/6
  // Resolution of the step times. The patent's ST parameters are set in 0.1 ms units
  // (0.0001 here); 0 keeps the exact design times. Default exact: rounding method 2's
  // T/6 = 6.667 ms to 6.7 ms already leaves about 1% residual vibration per step pair.
  double step_resolution_s = 0.0;
  PatternRealization realization = PatternRealization::kStepped;
  // Throws ValidationError naming the field: `method` when no registry entry has that
  // key (listing the keys), the common keys, then the entry's own checks.
  void validate() const;
  // The frequencies the pattern is designed for: frequencies_hz, else {frequency_hz}.
  std::vector<double> DesignFrequencies() const;
  // The damping ratio of each design frequency: damping_ratios, else design_damping_ratio
  // for every one.
  std::vector<double> DesignDampingRatios() const;
  // The pattern for design mode `i` alone (DesignFrequencies()[i] with its damping ratio),
  // the rest of the config kept: how a multi-mode shaper is designed mode by mode.
  PatternConfig ForMode(std::size_t i) const;
};

}  // namespace shapebench::controller
