// The shaper registry: every value of `controller.pattern.method` is the key of one entry
// here, and every listing of the shapers (the YAML reader's choices, error messages, the
// `pattern` report, sensitivity labels, docs/shapers.md) reads the registry.
//
// Every shaper is an impulse sequence (times >= 0, amplitudes summing to 1) that the
// controller applies like the patent's patterns: convolved with the steady acceleration
// of each acc/dec phase (stepped, linear_acc_dec.h) or as a post-interpolation profile
// table (profile_table.h), in both cases put on the period grid without losing its zeros
// (grid_realization.h). With several design frequencies (`frequencies_hz`) a shaper is
// designed once per frequency and the designs are convolved.
//
// Adding a built-in shaper is adding one file controller/shapers/NAME.cc (NAME a C
// identifier) that defines, in namespace shapebench::controller,
//   std::vector<ShaperEntry> BuiltInShapers_NAME();
// returning its entries, plus its test. controller/CMakeLists.txt generates the one
// function that calls every such file's (a self-registering object in a static library
// would be dropped by the linker when nothing references its file). Shapers outside
// controller/shapers/ (a test's, another program's) call RegisterShaper.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "controller/grid_realization.h"
#include "controller/impulse.h"
#include "controller/pattern_config.h"
#include "controller/vibration_suppression_pattern.h"

namespace shapebench::controller {

enum class ShaperKind {
  kNone,        // no shaping: the acceleration steps straight to a
  kPatentStep,  // JP2551868B2 (seed 004) paras. 36-49: two acceleration steps per mode
  kImpulse,     // a library shaper: an impulse sequence designed per mode
  kCustom,      // the impulses the config gives, as given (not per mode)
};

struct ShaperEntry {
  std::string key;          // the YAML name: controller.pattern.method
  std::string name;         // display name
  std::string description;  // one line, no '|' (a cell of docs/shapers.md)
  ShaperKind kind = ShaperKind::kImpulse;
  // Listing order: ascending rank, equal ranks in registration order. The built-ins use
  // 0..999 (none 0, methods 1-4 10..40, the library 100.., custom 900).
  int rank = 1000;
  // The impulse sequence (amplitudes summing to 1, times ascending from 0). kImpulse and
  // kPatentStep: for one mode of natural frequency `frequency_hz`, reading the config's
  // design_damping_ratio, vibration_tolerance, k1, ... as it needs. kNone and kCustom:
  // the whole sequence (frequency_hz is then the first design frequency).
  std::function<std::vector<Impulse>(const PatternConfig& config, double frequency_hz)> design;
  // kPatentStep only: para. 49's two steps for one mode of period `period_s`, exact
  // (MakeStepPattern rounds them to step_resolution_s).
  std::function<StepPattern(const PatternConfig& config, double period_s)> steps;
  // Optional: the checks of what this shaper reads beyond the keys every shaper shares
  // (PatternConfig::validate), throwing ValidationError naming the field.
  std::function<void(const PatternConfig& config)> validate;
  // The PatternConfig keys the design reads besides the frequencies and the damping
  // ratio, e.g. {"k1"}: sensitivity curves put their values in the labels.
  std::vector<std::string> parameters;
  // Optional: what the `pattern` report prints after the key, in parentheses (""
  // prints the key alone); unset: the description.
  std::function<std::string(const PatternConfig& config)> summary;

  // An entry with its names, kind and rank; the caller sets its design (or steps).
  static ShaperEntry Named(std::string key, std::string name, std::string description, ShaperKind kind,
                           int rank) {
    ShaperEntry entry;
    entry.key = std::move(key);
    entry.name = std::move(name);
    entry.description = std::move(description);
    entry.kind = kind;
    entry.rank = rank;
    return entry;
  }
};

// Adds a shaper (e.g. a test's) to the registry; throws std::invalid_argument when the
// key is empty or taken, the description is empty or has a '|' or a line break, or the
// design (kPatentStep: the steps) is missing. Register before anything runs concurrently.
void RegisterShaper(ShaperEntry entry);

// Every entry, in listing order (the pointers stay valid).
std::vector<const ShaperEntry*> Shapers();
// Their keys, and the keys of the built-ins only (controller/shapers/), in listing order.
std::vector<std::string> ShaperKeys();
std::vector<std::string> BuiltInShaperKeys();

// The entry of `key`; throws ValidationError("method") listing the keys when there is none.
const ShaperEntry& FindShaper(const std::string& key);

// The pattern of the acc/dec phases for `config` (valid, PatternConfig::validate): the
// patent's two steps for methods 1-4 at one frequency; otherwise the general impulse
// sequence of ShaperImpulses. Method none or mode off: no shaping.
StepPattern MakeStepPattern(const PatternConfig& config);

// The shaper's impulse sequence for a shaped phase start (per unit step; mode is
// ignored): times ascending from the first impulse, amplitudes summing to 1; the designs
// for several frequencies convolved. Method none: the unshaped step {0, 1}.
std::vector<Impulse> ShaperImpulses(const PatternConfig& config);

// The design point(s) the grid realization keeps for this pattern: its design
// frequencies with design_damping_ratio (methods 1-4: undamped).
GridDesign ShaperGridDesign(const PatternConfig& config);

}  // namespace shapebench::controller
