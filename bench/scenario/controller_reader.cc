#include "bench/scenario/controller_reader.h"

#include <string>
#include <utility>
#include <vector>

#include "bench/config/field_reader.h"
#include "bench/scenario/pattern_defaults.h"
#include "controller/program_builder.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {
namespace {

using controller::PatternMode;
using controller::PostInterpType;

// The value that leaves a design number to the machine (bench/scenario/pattern_defaults.h).
constexpr char kMachine[] = "machine";

bool IsMachine(const NodeReader& node) { return node.IsScalar() && node.node().Scalar() == kMachine; }


std::vector<double> ReadFrequencyList(const NodeReader& list, const char* noun, const char* example) {
  std::vector<double> values;
  for (const NodeReader& f : list.Elements()) values.push_back(f.AsNumber());
  if (values.empty()) throw list.Error(std::string("expected at least one ") + noun + ", e.g. " + example);
  if (values.size() > kMaxDesignFrequencies) {
    throw list.Error("at most " + std::to_string(kMaxDesignFrequencies) + " design frequencies (got " +
                     std::to_string(values.size()) +
                     "): each multiplies the number of impulses of the shaper");
  }
  return values;
}

// frequency_hz, frequencies_hz, design_damping_ratio and damping_ratios: numbers, or
// `machine` (frequency_hz also when not given: the machine's lowest participating mode).
void ReadDesignModes(const NodeReader& pattern, controller::PatternConfig* config) {
  const auto frequency = pattern.Child("frequency_hz");
  const auto frequencies = pattern.Child("frequencies_hz");
  if (frequencies && frequency) {
    throw frequencies->Error("give one of frequency_hz (one mode) and frequencies_hz (several "
                             "modes, one shaper each, convolved)");
  }
  if (frequency && IsMachine(*frequency)) {
    config->frequency_from_machine = true;
  } else if (frequency) {
    pattern.Read("frequency_hz", &config->frequency_hz);
  } else if (!frequencies) {
    config->frequency_from_machine = true;  // not given: the machine's
  }
  if (frequencies && IsMachine(*frequencies)) {
    config->frequencies_from_machine = true;
  } else if (frequencies) {
    config->frequencies_hz = ReadFrequencyList(*frequencies, "frequency", "[25, 60]");
  }
  const auto damping = pattern.Child("design_damping_ratio");
  if (damping && IsMachine(*damping)) {
    config->damping_from_machine = true;
  } else {
    pattern.Read("design_damping_ratio", &config->design_damping_ratio);
  }
  if (const auto ratios = pattern.Child("damping_ratios")) {
    if (damping) {
      throw ratios->Error("give one of design_damping_ratio (every mode) and damping_ratios (one "
                          "per frequency of frequencies_hz)");
    }
    if (!frequencies) {
      throw ratios->Error("damping_ratios go with frequencies_hz (one ratio per frequency); for "
                          "one mode give design_damping_ratio");
    }
    config->damping_ratios = ReadFrequencyList(*ratios, "damping ratio", "[0.02, 0.04]");
  }
}

}  // namespace

controller::PatternConfig ReadPattern(const NodeReader& pattern,
                                      const std::vector<std::string>& extra_keys) {
  std::vector<std::string> allowed = {"method", "mode", "frequency_hz", "frequencies_hz",
                                      "design_damping_ratio", "damping_ratios", "vibration_tolerance", "impulse_count",
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
  ReadDesignModes(pattern, &config);
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
