// Numbers in the text people read (the `run` table, `check` lines) in engineering units:
// lengths in um below 1 mm and in mm below 1 m, times in ms below 1 s. JSON and CSV keep
// SI (bench/scenario/metrics.h): this is for display only.
#pragma once

#include <string>
#include <string_view>

namespace shapebench::bench {

// `value` (SI, in `unit` as in MetricTable: "m", "s", "Hz", "1", "count", ...) as
// "7.99855 um", "12.5 ms", "25 Hz" or "0.726" (units "1" and "count" print no unit), to
// `digits` significant digits. The prefix is chosen per value by its magnitude; zero and
// infinities keep the SI unit ("0 m"); NaN is "n/a".
std::string EngineeringText(double value, std::string_view unit, int digits = 6);

}  // namespace shapebench::bench
