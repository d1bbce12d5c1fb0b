#include "bench/config/controller_reader.h"

#include <string>
#include <utility>
#include <vector>

#include "controller/program_builder.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {
namespace {

using controller::PatternMode;
using controller::PostInterpType;

}  // namespace

controller::PatternConfig ReadPattern(const NodeReader& pattern,
                                      const std::vector<std::string>& extra_keys) {
  std::vector<std::string> allowed = {"method", "mode", "frequency_hz", "frequencies_hz",
                                      "design_damping_ratio", "vibration_tolerance", "impulses",
                                      "k1", "t1_s", "step_resolution_s", "realization"};
  allowed.insert(allowed.end(), extra_keys.begin(), extra_keys.end());
  pattern.ExpectMap(allowed);
  controller::PatternConfig config;
  // Written as YAML ints (1) or strings ("1"): both read as the scalar's text.
  // Any key of the shaper registry, in its order (e.g. "expected one of none|1|2|...").
  std::vector<std::pair<std::string, std::string>> methods;
  for (const std::string& key : controller::ShaperKeys()) methods.emplace_back(key, key);
  pattern.Read<std::string>("method", methods, &config.method);
  pattern.Read<PatternMode>("mode",
                            {{"off", PatternMode::kOff},
                             {"start", PatternMode::kStart},
                             {"end", PatternMode::kEnd},
                             {"both", PatternMode::kBoth}},
                            &config.mode);
  pattern.Read("frequency_hz", &config.frequency_hz);
  if (auto frequencies = pattern.Child("frequencies_hz")) {
    if (pattern.Has("frequency_hz")) {
      throw frequencies->Error("give one of frequency_hz (one mode) and frequencies_hz (several "
                               "modes, one shaper each, convolved)");
    }
    for (const NodeReader& f : frequencies->Elements()) config.frequencies_hz.push_back(f.AsNumber());
    if (config.frequencies_hz.empty()) {
      throw frequencies->Error("expected at least one frequency, e.g. [25, 60]");
    }
    // Guard rail (docs/reliability.md): the convolved shaper has the product of the shapers' impulse
    // counts (4^10 for ten ZVDDs: minutes and gigabytes to realize).
    constexpr std::size_t kMaxFrequencies = 8;
    if (config.frequencies_hz.size() > kMaxFrequencies) {
      throw frequencies->Error("at most " + std::to_string(kMaxFrequencies) + " design frequencies (got " +
                               std::to_string(config.frequencies_hz.size()) +
                               "): each multiplies the number of impulses of the shaper");
    }
  }
  pattern.Read("design_damping_ratio", &config.design_damping_ratio);
  pattern.Read("vibration_tolerance", &config.vibration_tolerance);
  if (auto impulses = pattern.Child("impulses")) {
    for (const NodeReader& impulse : impulses->Elements()) {
      impulse.ExpectMap({"amplitude", "time_s"});
      for (const char* key : {"amplitude", "time_s"}) {
        if (!impulse.Has(key)) throw impulse.Error(std::string("missing '") + key + "'");
      }
      controller::Impulse value;
      impulse.Read("amplitude", &value.amplitude);
      impulse.Read("time_s", &value.time_s);
      config.impulses.push_back(value);
    }
  }
  pattern.Read("k1", &config.k1);
  pattern.Read("t1_s", &config.t1_s);
  pattern.Read("step_resolution_s", &config.step_resolution_s);
  pattern.Read<controller::PatternRealization>(
      "realization",
      {{"stepped", controller::PatternRealization::kStepped},
       {"profile_table", controller::PatternRealization::kProfileTable}},
      &config.realization);
  return config;
}

namespace {

controller::PostInterpConfig ReadPostInterp(const NodeReader& post_interp) {
  post_interp.ExpectMap({"type", "time_constant_s", "table", "moving_average_s",
                         "max_table_length", "distribution"});
  controller::PostInterpConfig config;
  post_interp.Read<PostInterpType>("type",
                                   {{"none", PostInterpType::kNone},
                                    {"exponential", PostInterpType::kExponential},
                                    {"profile_table", PostInterpType::kProfileTable}},
                                   &config.type);
  post_interp.Read("time_constant_s", &config.time_constant_s);
  if (auto table = post_interp.Child("table")) {
    for (const NodeReader& alpha : table->Elements()) config.table.push_back(alpha.AsNumber());
  }
  post_interp.Read("moving_average_s", &config.moving_average_s);
  post_interp.Read("max_table_length", &config.max_table_length);
  post_interp.Read<controller::Distribution>(
      "distribution",
      {{"per_axis", controller::Distribution::kPerAxis},
       {"tangential", controller::Distribution::kTangential}},
      &config.distribution);
  return config;
}

controller::ShortBlockConfig ReadShortBlock(const NodeReader& node) {
  node.ExpectMap({"mode", "ratio_line", "ratio_arc", "min_ratio_line", "min_ratio_arc", "scale",
                  "preset_feed_mm_min"});
  controller::ShortBlockConfig config;
  node.Read<controller::ShortBlockMode>("mode",
                                        {{"off", controller::ShortBlockMode::kOff},
                                         {"ratio", controller::ShortBlockMode::kRatio},
                                         {"length", controller::ShortBlockMode::kLength},
                                         {"scale", controller::ShortBlockMode::kScale},
                                         {"preset", controller::ShortBlockMode::kPreset}},
                                        &config.mode);
  node.Read("ratio_line", &config.ratio_line);
  node.Read("ratio_arc", &config.ratio_arc);
  node.Read("min_ratio_line", &config.min_ratio_line);
  node.Read("min_ratio_arc", &config.min_ratio_arc);
  node.Read("scale", &config.scale);
  node.Read("preset_feed_mm_min", &config.preset_feed_mm_min);
  return config;
}

controller::StrokeEndConfig ReadStrokeEnd(const NodeReader& node) {
  node.ExpectMap({"enabled", "look_ahead_blocks", "minute_feed_mm_min"});
  controller::StrokeEndConfig config;
  node.Read<bool>("enabled", {{"true", true}, {"false", false}}, &config.enabled);
  node.Read("look_ahead_blocks", &config.look_ahead_blocks);
  node.Read("minute_feed_mm_min", &config.minute_feed_mm_min);
  return config;
}

}  // namespace

controller::ControllerConfig ReadController(const NodeReader& controller) {
  controller.ExpectMap(
      {"period_s", "feed_mm_min", "accel_time_s", "rapid_feed_mm_min",
       "corner_velocity_change_mm_min", "pattern", "post_interp", "short_block", "stroke_end"});
  controller::ControllerConfig config;
  controller.Read("period_s", &config.period_s);
  controller.Read("feed_mm_min", &config.feed_mm_min);
  controller.Read("accel_time_s", &config.accel_time_s);
  controller.Read("rapid_feed_mm_min", &config.rapid_feed_mm_min);
  for (const char* key : {"feed_mm_min", "rapid_feed_mm_min"}) {
    const auto node = controller.Child(key);
    if (node && node->AsNumber() > controller::kMaxFeedMmMin) {
      throw node->Error("must be at most 1000000 (mm/min, 1 km/min), got " + node->node().Scalar());
    }
  }
  controller.Read("corner_velocity_change_mm_min", &config.corner_velocity_change_mm_min);
  if (auto pattern = controller.Child("pattern")) config.pattern = ReadPattern(*pattern);
  if (auto post_interp = controller.Child("post_interp")) {
    config.post_interp = ReadPostInterp(*post_interp);
  }
  if (auto short_block = controller.Child("short_block")) config.short_block = ReadShortBlock(*short_block);
  if (auto stroke_end = controller.Child("stroke_end")) config.stroke_end = ReadStrokeEnd(*stroke_end);
  return config;
}

controller::MoveConfig ReadMove(const NodeReader& move) {
  move.ExpectMap({"distance_mm", "axis"});
  controller::MoveConfig config;
  move.Read("distance_mm", &config.distance_mm);
  move.Read<int>("axis", {{"x", 0}, {"y", 1}, {"z", 2}}, &config.axis);
  return config;
}

}  // namespace shapebench::bench
