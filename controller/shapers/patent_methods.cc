// The patent's methods 1-4, JP2551868B2 (seed 004) paras. 36-49, as registry entries:
// their steps and checks are controller/vibration_suppression_pattern.h. Each is
// designed for an undamped mode; with several frequencies the methods' jerk impulses
// are convolved like the library's (and lose para. 50's steps).
#include <string>

#include "common/format.h"
#include "controller/shaper_registry.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {
namespace {

using Steps = std::function<StepPattern(const PatternConfig& config, double period_s)>;

ShaperEntry PatentMethod(int number, const std::string& paragraphs, const std::string& description,
                         Steps steps) {
  const std::string key = std::to_string(number);
  ShaperEntry entry = ShaperEntry::Named(key, "Method " + key + " (JP2551868B2 " + paragraphs + ")", description,
                                         ShaperKind::kPatentStep, 10 * number);
  // One mode's impulses: the jerks of the steps as set (para. 61), rounded like the
  // stepped realization's.
  entry.design = [steps](const PatternConfig& config, double frequency_hz) {
    return PatternImpulses(WithStepResolution(steps(config, 1.0 / frequency_hz), config.step_resolution_s));
  };
  entry.steps = std::move(steps);
  return entry;
}

}  // namespace

std::vector<ShaperEntry> BuiltInShapers_patent_methods() {
  ShaperEntry method1 = PatentMethod(1, "para. 38", "a/2 for T/2, then a",
                                     [](const PatternConfig&, double period_s) { return Method1Steps(period_s); });
  ShaperEntry method2 = PatentMethod(2, "para. 40", "a for T/6, 0 for T/6, then a",
                                     [](const PatternConfig&, double period_s) { return Method2Steps(period_s); });
  ShaperEntry method3 = PatentMethod(
      3, "paras. 43-44", "K1 a for t1, (1-K1) a for t1",
      [](const PatternConfig& config, double period_s) { return Method3Steps(config.k1, period_s); });
  method3.validate = ValidateMethod3;
  method3.parameters = {"k1"};
  method3.summary = [](const PatternConfig& config) {
    return "K1 a for t1, (1-K1) a for t1; k1 = " + FormatNumber(config.k1);
  };
  ShaperEntry method4 = PatentMethod(
      4, "para. 45", "a for t1, a2 for T/2 - 2 t1",
      [](const PatternConfig& config, double period_s) { return Method4Steps(config.t1_s, period_s); });
  method4.validate = ValidateMethod4;
  method4.parameters = {"t1_s"};
  method4.summary = [](const PatternConfig& config) {
    return "a for t1, a2 for T/2 - 2 t1; t1 = " + FormatNumber(config.t1_s) + " s";
  };
  return {method1, method2, method3, method4};
}

}  // namespace shapebench::controller
