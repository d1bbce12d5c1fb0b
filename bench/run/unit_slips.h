// Values a run accepts but that are almost surely a unit slip (issue 32 item 15): a period
// of 1 s meant as 1 ms, an acc/dec time of 200 s meant as 200 ms, a mode at 0.01 Hz. The
// run goes on (they are valid numbers); RunScenario adds a warning naming the key, the
// value and the likely slip. The thresholds are listed in docs/reliability.md and
// docs/scenario-reference.md.
#pragma once

#include <string>
#include <vector>

#include "bench/run/run_plan.h"
#include "bench/scenario/metrics.h"

namespace shapebench::bench {

// Above this an interpolation period is taken for milliseconds (CNCs use 0.1 to 10 ms).
inline constexpr double kUnitSlipPeriodS = 0.1;
// Above this an acc/dec time is taken for milliseconds (machine tools: tens of ms to ~1 s).
inline constexpr double kUnitSlipAccelTimeS = 10.0;
// Below this a structural mode is taken for a period in seconds (machine structures: ~5 Hz up).
inline constexpr double kUnitSlipModeHz = 1.0;
// Above this the static deflection is no machine tool's (they deflect micrometres).
inline constexpr double kUnitSlipStaticM = 0.01;

// The warnings for `plan`'s scenario and its metrics, in the order above; empty for a
// plausible scenario.
std::vector<std::string> UnitSlipWarnings(const RunPlan& plan, const Metrics& metrics);

}  // namespace shapebench::bench
