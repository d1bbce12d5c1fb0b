// What the loader refuses before a run (bench/scenario/scenario_loader.h): a plant whose
// model is not finite, a run longer than limits: allow (its simulated time, ticks or
// memory), and the limits a G-code file is parsed under. Also the run's minimum length,
// computed without generating its command.
#pragma once

#include <optional>
#include <string>

#include "bench/config/config_document.h"
#include "bench/scenario/scenario.h"
#include "controller/gcode_parser.h"

namespace shapebench::bench {

// Throws ValidationError ("machine": a state-space model or static gain that is not
// finite; "integrator": a method that cannot integrate the plant).
void CheckPlantFinite(const Scenario& scenario);

// Whether a run of `seconds` stays within limits: (time, ticks, memory).
bool RunLengthWithinLimits(const Scenario& scenario, double seconds);

// Guard rail: a run known to be longer than limits: allow is refused before any command
// is generated (a giant move, a low design frequency, a long filter would otherwise take
// the machine's memory and time): a ConfigError at the limit that binds.
void CheckRunLength(const ConfigDocument& document, const Scenario& scenario);

// The limits a G-code file is parsed under: its path's time within the run's (the binding
// one of max_simulated_s, max_ticks and max_memory_mb), its blocks within the memory budget
// and the ticks (every block takes at least one interpolation period).
controller::GcodeLimits ParseLimits(const Scenario& scenario);

// A lower bound of the simulated time of a run (seconds), computed without generating the
// command: the path at its programmed feeds (or, if longer, from rest to rest at twice the
// acc/dec's acceleration), dwells, the pattern's duration, the post-interpolation filter's
// length, and the residual window (three periods of the lowest mode). `breakdown`, when
// given, receives the parts in words. The loader refuses a scenario whose bound exceeds
// limits.max_simulated_s or limits.max_ticks periods (a ConfigError naming the scenario).
double MinimumRunSeconds(const Scenario& scenario, std::string* breakdown = nullptr);
// Its two parts: the motion (program and controller: the structure does not change it) and
// the residual window (three periods of the lowest mode).
double MinimumMotionSeconds(const Scenario& scenario, std::string* breakdown = nullptr);
double ResidualWindowSeconds(const Scenario& scenario);

// What LoadScenario checks of a scenario's machine once it is read, without its sources:
// the machine's validate(), a finite state-space model, the run length within limits:.
// True when all hold. A sweep point that changes only numbers of the structure on a loaded
// scenario (structure_numbers.h) asks this; on false the point is loaded from its sources,
// which locates the error.
// `motion_s`: MinimumMotionSeconds of the scenario when known (a sweep's points that
// change only the structure share it).
bool MachineChecksPass(const Scenario& scenario, std::optional<double> motion_s = std::nullopt);

}  // namespace shapebench::bench
