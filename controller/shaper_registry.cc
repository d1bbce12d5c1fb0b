// The shaper registry; see the header.
#include "controller/shaper_registry.h"

#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/validation_error.h"

namespace shapebench::controller {

// Every controller/shapers/NAME.cc's BuiltInShapers_NAME(), concatenated; defined in the
// file controller/CMakeLists.txt generates.
std::vector<ShaperEntry> AllBuiltInShapers();

namespace {

struct Registry {
  std::mutex mutex;
  std::deque<ShaperEntry> entries;          // a deque: the addresses stay valid
  std::vector<const ShaperEntry*> ordered;  // by rank
  std::vector<std::string> built_in_keys;
};

void Check(const ShaperEntry& entry, const Registry& registry) {
  const std::string what = "shaper '" + entry.key + "': ";
  if (entry.key.empty()) throw std::invalid_argument("a shaper needs a key");
  for (const ShaperEntry* other : registry.ordered) {
    if (other->key == entry.key) throw std::invalid_argument(what + "the key is taken");
  }
  if (entry.description.empty() || entry.description.find_first_of("|\n\r") != std::string::npos) {
    throw std::invalid_argument(what + "needs a one-line description without '|'");
  }
  if (!entry.design) throw std::invalid_argument(what + "needs a design");
  if (entry.kind == ShaperKind::kPatentStep && !entry.steps) {
    throw std::invalid_argument(what + "a patent step method needs its steps");
  }
}

// Adds `entry` after every entry of lower or equal rank; the caller holds the lock.
void Add(Registry& registry, ShaperEntry entry) {
  Check(entry, registry);
  registry.entries.push_back(std::move(entry));
  const ShaperEntry* added = &registry.entries.back();
  auto at = registry.ordered.begin();
  while (at != registry.ordered.end() && (*at)->rank <= added->rank) ++at;
  registry.ordered.insert(at, added);
}

// Built on first use, so that a registration from a static initializer (a test's) finds
// the built-ins already there whatever the order of initialization.
Registry& TheRegistry() {
  static Registry* const registry = [] {
    auto* r = new Registry;  // never destroyed: usable from other static destructors
    for (ShaperEntry& entry : AllBuiltInShapers()) Add(*r, std::move(entry));
    for (const ShaperEntry* entry : r->ordered) r->built_in_keys.push_back(entry->key);
    return r;
  }();
  return *registry;
}

}  // namespace

void RegisterShaper(ShaperEntry entry) {
  Registry& registry = TheRegistry();
  std::lock_guard<std::mutex> lock(registry.mutex);
  Add(registry, std::move(entry));
}

std::vector<const ShaperEntry*> Shapers() {
  Registry& registry = TheRegistry();
  std::lock_guard<std::mutex> lock(registry.mutex);
  return registry.ordered;
}

std::vector<std::string> ShaperKeys() {
  std::vector<std::string> keys;
  for (const ShaperEntry* entry : Shapers()) keys.push_back(entry->key);
  return keys;
}

std::vector<std::string> BuiltInShaperKeys() { return TheRegistry().built_in_keys; }

const ShaperEntry& FindShaper(const std::string& key) {
  {
    // Every command generation asks: no copies, no strings built on the way.
    Registry& registry = TheRegistry();
    std::lock_guard<std::mutex> lock(registry.mutex);
    for (const ShaperEntry* entry : registry.ordered) {
      if (entry->key == key) return *entry;
    }
  }
  std::string keys;
  for (const ShaperEntry* entry : Shapers()) keys += (keys.empty() ? "" : ", ") + entry->key;
  throw ValidationError("method", "is not a shaper of the registry (got '" + key + "'); allowed: " + keys);
}

StepPattern MakeStepPattern(const PatternConfig& config) {
  StepPattern pattern;
  const ShaperEntry& entry = FindShaper(config.method);
  if (entry.kind == ShaperKind::kNone || config.mode == PatternMode::kOff) return pattern;
  const std::vector<double> frequencies = config.DesignFrequencies();
  if (entry.kind == ShaperKind::kPatentStep && frequencies.size() == 1) {
    pattern = WithStepResolution(entry.steps(config, 1.0 / frequencies.front()), config.step_resolution_s);
  } else {
    // The library (or the patent's methods convolved for several modes): the general
    // impulse sequence, applied by convolution (linear_acc_dec.h).
    pattern.impulses = ShaperImpulses(config);
  }
  pattern.at_start = config.mode == PatternMode::kStart || config.mode == PatternMode::kBoth;
  pattern.at_end = config.mode == PatternMode::kEnd || config.mode == PatternMode::kBoth;
  return pattern;
}

std::vector<Impulse> ShaperImpulses(const PatternConfig& config) {
  const ShaperEntry& entry = FindShaper(config.method);
  const std::vector<double> frequencies = config.DesignFrequencies();
  if (entry.kind == ShaperKind::kNone || entry.kind == ShaperKind::kCustom) {
    return entry.design(config, frequencies.front());
  }
  std::vector<Impulse> result = {{0.0, 1.0}};
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    // A damping ratio per mode: each design reads its own (ForMode).
    result = ConvolveImpulses(result, config.damping_ratios.empty()
                                          ? entry.design(config, frequencies[i])
                                          : entry.design(config.ForMode(i), frequencies[i]));
  }
  return result;
}

GridDesign ShaperGridDesign(const PatternConfig& config) {
  const bool patent = FindShaper(config.method).kind == ShaperKind::kPatentStep;
  GridDesign design(config.DesignFrequencies(), patent ? 0.0 : config.design_damping_ratio);
  if (!patent) design.damping_ratios = config.damping_ratios;
  return design;
}

}  // namespace shapebench::controller
