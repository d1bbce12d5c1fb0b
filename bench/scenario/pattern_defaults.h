// A pattern's design values left to the machine (controller/pattern_config.h: frequency_hz
// not given or `machine`, `frequencies_hz: machine`, `design_damping_ratio: machine`),
// taken from the machine's modes that take part in the moves the program makes.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "controller/pattern_config.h"
#include "controller/program.h"
#include "model/machine.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

// Guard rail (docs/reliability.md): the convolved shaper has the product of the shapers'
// impulse counts (4^10 for ten ZVDDs: minutes and gigabytes to realize), so a pattern is
// designed for at most this many frequencies, given or taken from the machine.
constexpr std::size_t kMaxDesignFrequencies = 8;

// The modes a pattern left to the machine is designed for.
struct DesignModes {
  // The participating modes of the moved axes, ascending frequency: a mode participates
  // when its static contribution |gain / w^2| is at least 1% of its axis' static
  // deflection (model::MachineDynamics::kParticipatingShare). A frequency found on
  // several axes appears once (the first axis' mode).
  std::vector<model::ModeInfo> modes;
  std::string axes;  // the moved axes, for messages: "y", "x, y"
};

// The axes the program moves: a block whose end differs from its start along an axis, an
// arc both axes of its plane. None (an empty program): `fallback_axis`.
std::vector<int> MovedAxes(const controller::Program& program, int fallback_axis);

// The participating modes of `machine` along the axes `program` moves.
DesignModes FindDesignModes(const model::MultiAxisMachineConfig& machine,
                            const controller::Program& program);

// Replaces what `pattern` leaves to the machine with `modes`:
//   frequency_hz            the lowest mode (methods 1-4: their natural period T = 1/f);
//   frequencies_hz: machine every mode, ascending (at most 8);
//   design_damping_ratio: machine  the damping ratio of the mode(s) designed for: with
//     frequencies_hz: machine one ratio per mode (damping_ratios); with frequencies given
//     as numbers, that of the participating mode nearest each.
// A machine without participating modes along the moved axes (rigid there) leaves a
// defaulted frequency_hz as it is (25 Hz) for a pattern that does not shape with it
// (none, custom, mode off) and is a ValidationError naming the field otherwise, as is any
// explicit `machine`.
void ResolvePatternDefaults(const DesignModes& modes, controller::PatternConfig* pattern);

}  // namespace shapebench::bench
