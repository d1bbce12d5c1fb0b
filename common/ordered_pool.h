// A bounded, ordered worker pool: results computed on several threads, consumed on the
// calling thread in order, so output does not depend on the thread count.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

namespace shapebench {

// Runs work(k) for k = 0..count-1 on `jobs` threads and hands each result to consume(k,
// result) on the calling thread, in order of k. Workers stay at most `window` items
// ahead of the consumer, so memory does not grow with `count`. An exception from work or
// consume stops the workers and is rethrown here. When `cancelled` (polled) turns true,
// workers take no new items, the ones in progress finish, and the consumer takes every
// result that is complete and in order, then returns. Returns how many were consumed.
template <typename Result>
std::uint64_t RunOrdered(std::uint64_t count, int jobs,
                         const std::function<Result(std::uint64_t)>& work,
                         const std::function<void(std::uint64_t, Result&&)>& consume,
                         std::uint64_t window = 0,
                         const std::function<bool()>& cancelled = {}) {
  if (count == 0) return 0;
  if (jobs < 1) jobs = 1;
  if (static_cast<std::uint64_t>(jobs) > count) jobs = static_cast<int>(count);
  if (window == 0) window = 64 * static_cast<std::uint64_t>(jobs);
  constexpr auto kPoll = std::chrono::milliseconds(20);
  auto is_cancelled = [&] { return cancelled && cancelled(); };
  std::mutex mutex;
  std::condition_variable ready_changed;
  std::condition_variable consumed_changed;
  std::map<std::uint64_t, Result> ready;
  std::uint64_t next = 0;
  std::uint64_t consumed = 0;
  int running = jobs;  // worker threads not yet returned
  bool stop = false;
  std::exception_ptr failure;

  auto work_loop = [&] {
    while (true) {
      std::uint64_t k = 0;
      {
        std::unique_lock<std::mutex> lock(mutex);
        if (stop || next >= count || is_cancelled()) return;
        k = next++;
        while (!consumed_changed.wait_for(lock, kPoll, [&] { return stop || k < consumed + window; })) {
          if (is_cancelled()) return;
        }
        if (stop) return;
      }
      try {
        Result result = work(k);
        std::lock_guard<std::mutex> lock(mutex);
        ready.emplace(k, std::move(result));
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
        consumed_changed.notify_all();
      }
      ready_changed.notify_one();
    }
  };
  auto worker = [&] {
    work_loop();
    {
      std::lock_guard<std::mutex> lock(mutex);
      --running;
    }
    ready_changed.notify_all();
  };
  std::vector<std::thread> threads;
  for (int i = 0; i < jobs; ++i) threads.emplace_back(worker);
  auto finish = [&] {
    {
      std::lock_guard<std::mutex> lock(mutex);
      stop = true;
    }
    consumed_changed.notify_all();
    for (auto& thread : threads) thread.join();
  };
  std::uint64_t done = 0;
  try {
    for (std::uint64_t k = 0; k < count; ++k) {
      Result result;
      {
        std::unique_lock<std::mutex> lock(mutex);
        // Cancelled: what is ready in order is still taken; a gap no worker will fill ends it.
        auto settled = [&] { return failure || ready.count(k) > 0 || running == 0; };
        while (!ready_changed.wait_for(lock, kPoll, settled)) {
        }
        if (failure) break;
        auto it = ready.find(k);
        if (it == ready.end()) break;  // cancelled: nobody computes k
        result = std::move(it->second);
        ready.erase(it);
      }
      consume(k, std::move(result));
      done = k + 1;
      {
        std::lock_guard<std::mutex> lock(mutex);
        consumed = k + 1;
      }
      consumed_changed.notify_all();
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
  if (failure) std::rethrow_exception(failure);
  return done;
}

}  // namespace shapebench
