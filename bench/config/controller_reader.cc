#include "bench/config/controller_reader.h"

#include <string>
#include <utility>
#include <vector>

#include "bench/config/field_reader.h"
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
                                      "design_damping_ratio", "vibration_tolerance", "impulse_count",
                                      "impulse_spacing_periods", "impulses", "k1", "t1_s",
                                      "step_resolution_s", "realization"};
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
  pattern.Read("impulse_count", &config.impulse_count);
  pattern.Read("impulse_spacing_periods", &config.impulse_spacing_periods);
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

void ReadSection(const NodeReader& node, controller::PatternConfig* config) { *config = ReadPattern(node); }

controller::ControllerConfig ReadController(const NodeReader& controller) {
  controller::ControllerConfig config;
  ReadFields(controller, &config);
  for (const char* key : {"feed_mm_min", "rapid_feed_mm_min"}) {
    const auto node = controller.Child(key);
    if (node && node->AsNumber() > controller::kMaxFeedMmMin) {
      throw node->Error("must be at most 1000000 (mm/min, 1 km/min), got " + node->node().Scalar());
    }
  }
  return config;
}

controller::MoveConfig ReadMove(const NodeReader& move) {
  controller::MoveConfig config;
  ReadFields(move, &config);
  return config;
}

}  // namespace shapebench::bench
