// RunOrdered (common/ordered_pool.h): one job runs on the calling thread (no hand-off
// between threads a point); several hand their results over in order whatever the batch
// of wake-ups, with a window smaller and larger than the batch.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <set>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "common/ordered_pool.h"

namespace shapebench {
namespace {

// Tests that with one job every item is computed on the calling thread, each consumed
// right after it is computed.
TEST(OrderedPool, OneJobRunsOnTheCallingThread) {
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<std::uint64_t> events;  // 2k: computed k, 2k + 1: consumed k
  int elsewhere = 0;
  const std::uint64_t done = RunOrdered<std::uint64_t>(
      50, 1,
      [&](std::uint64_t k) {
        if (std::this_thread::get_id() != caller) ++elsewhere;
        events.push_back(2 * k);
        return k;
      },
      [&](std::uint64_t k, std::uint64_t&& value) {
        EXPECT_EQ(value, k);
        events.push_back(2 * k + 1);
      });
  EXPECT_EQ(done, 50u);
  EXPECT_EQ(elsewhere, 0);
  ASSERT_EQ(events.size(), 100u);
  for (std::uint64_t i = 0; i < events.size(); ++i) EXPECT_EQ(events[i], i);
}

// Tests that several jobs hand over every result in order, for windows below, at and above
// the consumer's batch (16), items of uneven cost, and a count that is no multiple of it.
TEST(OrderedPool, SeveralJobsInOrderForEveryWindow) {
  for (const std::uint64_t window : {1u, 2u, 5u, 16u, 32u, 100u}) {
    for (const int jobs : {2, 3}) {
      std::vector<std::uint64_t> seen;
      const std::uint64_t done = RunOrdered<std::uint64_t>(
          203, jobs,
          [](std::uint64_t k) {
            if (k % 13 == 0) std::this_thread::sleep_for(std::chrono::microseconds(300));
            return 3 * k;
          },
          [&](std::uint64_t k, std::uint64_t&& value) {
            EXPECT_EQ(value, 3 * k);
            seen.push_back(k);
          },
          window);
      EXPECT_EQ(done, 203u) << window << " " << jobs;
      ASSERT_EQ(seen.size(), 203u) << window << " " << jobs;
      for (std::uint64_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], k);
    }
  }
}

// Tests that with a Spill the results computed while an earlier item is still running
// are handed to it while they wait, each once: item 0 does not end until every other item
// has been handed over (60 s at most, so a failure cannot hang the test); then every
// result is still consumed, in order.
TEST(OrderedPool, ResultsWaitingBehindASlowItemAreSpilled) {
  for (const int jobs : {2, 3}) {
    std::mutex mutex;
    std::condition_variable changed;
    std::multiset<std::uint64_t> spilled;
    Spill<std::uint64_t> spill;
    spill.after = std::chrono::milliseconds(0);
    spill.take = [&](std::uint64_t k, const std::uint64_t& value) {
      EXPECT_EQ(value, 5 * k);
      std::lock_guard<std::mutex> lock(mutex);
      spilled.insert(k);
      changed.notify_all();
    };
    std::vector<std::uint64_t> seen;
    bool all_spilled_first = false;
    const std::uint64_t done = RunOrdered<std::uint64_t>(
        40, jobs,
        [&](std::uint64_t k) {
          if (k == 0) {
            std::unique_lock<std::mutex> lock(mutex);
            all_spilled_first = changed.wait_for(lock, std::chrono::seconds(60), [&] { return spilled.size() >= 39; });
          }
          return 5 * k;
        },
        [&](std::uint64_t k, std::uint64_t&& value) {
          EXPECT_EQ(value, 5 * k);
          seen.push_back(k);
        },
        0, {}, &spill);
    EXPECT_TRUE(all_spilled_first) << jobs;
    EXPECT_EQ(done, 40u);
    ASSERT_EQ(seen.size(), 40u);
    for (std::uint64_t k = 0; k < seen.size(); ++k) EXPECT_EQ(seen[k], k);
    std::lock_guard<std::mutex> lock(mutex);
    for (std::uint64_t k = 1; k < 40; ++k) EXPECT_EQ(spilled.count(k), 1u) << k << " with " << jobs << " jobs";
    EXPECT_EQ(spilled.count(0), 0u);
  }
}

}  // namespace
}  // namespace shapebench
