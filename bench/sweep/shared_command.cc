#include "bench/sweep/shared_command.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <utility>

namespace shapebench::bench {

// One key's slot: its own mutex, so that one thread generates while the others wait for
// this key only.
struct Slot {
  std::mutex mutex;
  std::shared_ptr<const SharedCommand> value;
};

struct SharedCommandCache::Impl {
  std::mutex mutex;  // guards slots, order and ticks
  std::map<std::pair<std::uint64_t, std::string>, std::shared_ptr<Slot>> slots;
  std::deque<std::pair<std::uint64_t, std::string>> order;  // oldest first
  std::size_t ticks = 0;
  std::atomic<std::uint64_t> generated{0};
};

SharedCommandCache::SharedCommandCache() : impl_(std::make_unique<Impl>()) {}
SharedCommandCache::~SharedCommandCache() = default;

SharedCommandCache& SharedCommandCache::Instance() {
  static SharedCommandCache cache;
  return cache;
}

bool SharedCommandCache::Enabled() {
  static const bool enabled = [] {
    const char* value = std::getenv("SHAPEBENCH_SHARE_COMMAND");
    return value == nullptr || std::strcmp(value, "0") != 0;
  }();
  return enabled;
}

std::uint64_t SharedCommandCache::generated() const { return impl_->generated.load(); }

std::shared_ptr<const SharedCommand> SharedCommandCache::Get(
    std::uint64_t sweep_id, const std::string& key,
    const std::function<controller::MultiAxisCommand(controller::Program* program)>& generate) {
  auto id = std::make_pair(sweep_id, key);
  std::shared_ptr<Slot> slot;
  {
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    std::shared_ptr<Slot>& held = impl_->slots[id];
    if (!held) held = std::make_shared<Slot>();
    slot = held;
  }
  const std::lock_guard<std::mutex> slot_lock(slot->mutex);
  if (slot->value) return slot->value;
  auto made = std::make_shared<SharedCommand>();
  try {
    made->command = generate(&made->program);
  } catch (...) {
    // Not kept: every point of this key reports its own error (and the empty slot goes,
    // so that a sweep of failing points holds nothing).
    const std::lock_guard<std::mutex> lock(impl_->mutex);
    const auto it = impl_->slots.find(id);
    if (it != impl_->slots.end() && it->second == slot) impl_->slots.erase(it);
    throw;
  }
  made->samples = SampleCommand(made->command);
  made->path.emplace(made->program);
  slot->value = made;
  ++impl_->generated;
  const std::lock_guard<std::mutex> lock(impl_->mutex);
  impl_->order.push_back(id);
  impl_->ticks += made->samples.n + 1;
  // The oldest go while over the budget; the newest stays whatever its size.
  while (impl_->ticks > kMaxTicks && impl_->order.size() > 1) {
    const auto oldest = impl_->order.front();
    impl_->order.pop_front();
    const auto it = impl_->slots.find(oldest);
    if (it != impl_->slots.end()) {
      // Its value is read under its own lock only by a thread that found the slot; that
      // thread keeps the shared_ptr it got, so dropping ours here is safe.
      if (it->second->value) impl_->ticks -= it->second->value->samples.n + 1;
      impl_->slots.erase(it);
    }
  }
  return made;
}

}  // namespace shapebench::bench
