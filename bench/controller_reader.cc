#include "bench/controller_reader.h"

namespace shapebench::bench {
namespace {

using controller::PatternMethod;
using controller::PatternMode;
using controller::PostInterpType;

controller::PatternConfig ReadPattern(const NodeReader& pattern) {
  pattern.ExpectMap({"method", "mode", "frequency_hz", "k1", "t1_s", "step_resolution_s"});
  controller::PatternConfig config;
  // Written as YAML ints (1) or strings ("1"): both read as the scalar's text.
  pattern.Read<PatternMethod>("method",
                              {{"none", PatternMethod::kNone},
                               {"1", PatternMethod::kMethod1},
                               {"2", PatternMethod::kMethod2},
                               {"3", PatternMethod::kMethod3},
                               {"4", PatternMethod::kMethod4}},
                              &config.method);
  pattern.Read<PatternMode>("mode",
                            {{"off", PatternMode::kOff},
                             {"start", PatternMode::kStart},
                             {"end", PatternMode::kEnd},
                             {"both", PatternMode::kBoth}},
                            &config.mode);
  pattern.Read("frequency_hz", &config.frequency_hz);
  pattern.Read("k1", &config.k1);
  pattern.Read("t1_s", &config.t1_s);
  pattern.Read("step_resolution_s", &config.step_resolution_s);
  return config;
}

controller::PostInterpConfig ReadPostInterp(const NodeReader& post_interp) {
  post_interp.ExpectMap({"type", "time_constant_s"});
  controller::PostInterpConfig config;
  post_interp.Read<PostInterpType>(
      "type", {{"none", PostInterpType::kNone}, {"exponential", PostInterpType::kExponential}},
      &config.type);
  post_interp.Read("time_constant_s", &config.time_constant_s);
  return config;
}

}  // namespace

controller::ControllerConfig ReadController(const NodeReader& controller) {
  controller.ExpectMap(
      {"period_s", "feed_mm_min", "accel_time_s", "pattern", "post_interp"});
  controller::ControllerConfig config;
  controller.Read("period_s", &config.period_s);
  controller.Read("feed_mm_min", &config.feed_mm_min);
  controller.Read("accel_time_s", &config.accel_time_s);
  if (auto pattern = controller.Child("pattern")) config.pattern = ReadPattern(*pattern);
  if (auto post_interp = controller.Child("post_interp")) {
    config.post_interp = ReadPostInterp(*post_interp);
  }
  return config;
}

controller::MoveConfig ReadMove(const NodeReader& move) {
  move.ExpectMap({"distance_mm"});
  controller::MoveConfig config;
  move.Read("distance_mm", &config.distance_mm);
  return config;
}

}  // namespace shapebench::bench
