// ResolvePatternDefaults and what it reads of the machine (pattern_defaults.h).
#include "bench/scenario/pattern_defaults.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/validation_error.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {
namespace {

// Modes of different axes closer than this (relative) are one design frequency.
constexpr double kSameFrequency = 1e-9;

void Mark(std::vector<bool>* moved, int axis) { (*moved)[static_cast<std::size_t>(axis)] = true; }

// The participating mode whose frequency is nearest `frequency_hz` (in ratio).
const model::ModeInfo& Nearest(const std::vector<model::ModeInfo>& modes, double frequency_hz) {
  const model::ModeInfo* best = &modes.front();
  for (const model::ModeInfo& mode : modes) {
    if (std::abs(std::log(mode.frequency_hz / frequency_hz)) <
        std::abs(std::log(best->frequency_hz / frequency_hz))) {
      best = &mode;
    }
  }
  return *best;
}

ValidationError NoModes(const std::string& field, const DesignModes& modes) {
  return ValidationError(field, "is left to the machine, which has no mode taking part along the "
                                "moved axes (" + modes.axes + "; rigid there): give it as a number");
}

}  // namespace

std::vector<int> MovedAxes(const controller::Program& program, int fallback_axis) {
  std::vector<bool> moved(controller::kNumAxes, false);
  for (const controller::ProgramBlock& block : program.blocks) {
    if (block.kind == controller::MotionKind::kDwell) continue;
    for (int axis = 0; axis < controller::kNumAxes; ++axis) {
      if (block.end_m[axis] != block.start_m[axis]) Mark(&moved, axis);
    }
    if (block.kind == controller::MotionKind::kArcCw || block.kind == controller::MotionKind::kArcCcw) {
      // A full circle ends where it starts; its plane's axes move all the same.
      static constexpr int kPlaneAxes[3][2] = {{0, 1}, {2, 0}, {1, 2}};  // XY, ZX, YZ
      for (const int axis : kPlaneAxes[static_cast<int>(block.plane)]) Mark(&moved, axis);
    }
  }
  std::vector<int> axes;
  for (int axis = 0; axis < controller::kNumAxes; ++axis) {
    if (moved[static_cast<std::size_t>(axis)]) axes.push_back(axis);
  }
  if (axes.empty()) axes.push_back(fallback_axis);
  return axes;
}

DesignModes FindDesignModes(const model::MultiAxisMachineConfig& machine,
                            const controller::Program& program) {
  const model::MachineDynamics dynamics = model::AnalyzeMachine(machine);
  DesignModes result;
  std::vector<model::ModeInfo> found;
  for (const int axis : MovedAxes(program, machine.driven_axis)) {
    result.axes += (result.axes.empty() ? "" : ", ") + std::string(model::AxisName(axis));
    for (const model::AxisModes& modes : dynamics.axes) {
      if (modes.axis != axis) continue;
      for (const model::ModeInfo& mode : modes.analysis.modes) {
        if (std::abs(mode.participation) >= model::MachineDynamics::kParticipatingShare) found.push_back(mode);
      }
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const model::ModeInfo& a, const model::ModeInfo& b) {
    return a.frequency_hz < b.frequency_hz;
  });
  for (const model::ModeInfo& mode : found) {
    if (!result.modes.empty() &&
        mode.frequency_hz - result.modes.back().frequency_hz <= kSameFrequency * mode.frequency_hz) {
      continue;
    }
    result.modes.push_back(mode);
  }
  return result;
}

void ResolvePatternDefaults(const DesignModes& modes, controller::PatternConfig* pattern) {
  const controller::ShaperKind kind = controller::FindShaper(pattern->method).kind;
  const bool shapes_with_frequency =
      (kind == controller::ShaperKind::kPatentStep || kind == controller::ShaperKind::kImpulse) &&
      pattern->mode != controller::PatternMode::kOff;
  const std::vector<model::ModeInfo>& found = modes.modes;
  if (found.empty()) {
    if (pattern->frequencies_from_machine) throw NoModes("frequencies_hz", modes);
    if (pattern->damping_from_machine) throw NoModes("design_damping_ratio", modes);
    if (pattern->frequency_from_machine && shapes_with_frequency) throw NoModes("frequency_hz", modes);
    return;
  }
  if (pattern->frequencies_from_machine) {
    if (found.size() > kMaxDesignFrequencies) {
      throw ValidationError("frequencies_hz",
                            "the machine has " + std::to_string(found.size()) +
                                " participating modes along the moved axes (" + modes.axes +
                                "), more than the " + std::to_string(kMaxDesignFrequencies) +
                                " design frequencies allowed: list the ones to shape for");
    }
    pattern->frequencies_hz.clear();
    for (const model::ModeInfo& mode : found) pattern->frequencies_hz.push_back(mode.frequency_hz);
  } else if (pattern->frequency_from_machine) {
    pattern->frequency_hz = found.front().frequency_hz;
  }
  if (!pattern->damping_from_machine) return;
  // Each design frequency takes the damping of its mode (the nearest participating one
  // when the frequencies are given as numbers).
  const std::vector<double> frequencies = pattern->DesignFrequencies();
  if (pattern->frequencies_hz.empty()) {
    pattern->design_damping_ratio = Nearest(found, frequencies.front()).damping_ratio;
    return;
  }
  pattern->design_damping_ratio = 0.0;
  pattern->damping_ratios.clear();
  for (const double f : frequencies) pattern->damping_ratios.push_back(Nearest(found, f).damping_ratio);
}

}  // namespace shapebench::bench
