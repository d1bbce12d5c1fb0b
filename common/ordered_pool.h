// A bounded, ordered worker pool: results computed on several threads, consumed on the
// calling thread in order, so output does not depend on the thread count.
#pragma once

#include <algorithm>
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

// RunOrdered's one job: computed and consumed on the calling thread, in the same order,
// with no hand-off between threads (a wake-up an item otherwise).
template <typename Result, typename Cancelled>
std::uint64_t RunHere(std::uint64_t count, const std::function<Result(std::uint64_t)>& work,
                      const std::function<void(std::uint64_t, Result&&)>& consume, const Cancelled& is_cancelled) {
  std::uint64_t done = 0;
  for (std::uint64_t k = 0; k < count && !is_cancelled(); ++k) {
    consume(k, work(k));
    done = k + 1;
  }
  return done;
}

// RunOrdered's state with several jobs, shared by its workers and the calling thread.
template <typename Result>
struct OrderedRun {
  using Work = std::function<Result(std::uint64_t)>;
  static constexpr std::chrono::milliseconds kPoll{20};

  std::uint64_t count = 0;
  std::uint64_t window = 0;
  std::uint64_t batch = 1;  // the consumer wakes for `batch` results in order
  const Work* work = nullptr;
  std::function<bool()> cancelled;
  std::mutex mutex;
  std::condition_variable ready_changed;
  std::condition_variable consumed_changed;
  std::map<std::uint64_t, Result> ready;
  std::uint64_t next = 0;
  std::uint64_t consumed = 0;
  int running = 0;    // worker threads not yet returned
  int held_back = 0;  // workers waiting for the consumer (the window)
  bool stop = false;
  bool consumer_waiting = false;
  std::exception_ptr failure;

  bool is_cancelled() const { return cancelled && cancelled(); }
  // Under the lock: a batch in order from `consumed` on (or the end).
  bool run_ready() const {
    std::uint64_t n = 0;
    while (n < batch && ready.count(consumed + n) > 0) ++n;
    return n >= batch || consumed + n >= count;
  }
  // Under the lock: an item nobody has taken, within the window.
  bool free_item() const { return !stop && next < count && next < consumed + window && !is_cancelled(); }

  void WorkLoop() {
    while (true) {
      std::uint64_t k = 0;
      {
        std::unique_lock<std::mutex> lock(mutex);
        if (stop || next >= count || is_cancelled()) return;
        k = next++;
        if (!(k < consumed + window)) {
          ++held_back;
          if (consumer_waiting) ready_changed.notify_one();
          while (!consumed_changed.wait_for(lock, kPoll, [&] { return stop || k < consumed + window; })) {
            if (is_cancelled()) {
              --held_back;
              return;
            }
          }
          --held_back;
        }
        if (stop) return;
      }
      bool wake = true;
      try {
        Result result = (*work)(k);
        std::lock_guard<std::mutex> lock(mutex);
        ready.emplace(k, std::move(result));
        wake = consumer_waiting && run_ready();
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
        stop = true;
        consumed_changed.notify_all();
      }
      if (wake) ready_changed.notify_one();
    }
  }

  // The calling thread's: result k, computing free items itself while k is not ready (a
  // consumer that only waited would be a third thread on two cores, preempting the
  // workers). False when it will not come (a failure; cancelled with k not computed).
  bool Take(std::uint64_t k, Result* result) {
    std::unique_lock<std::mutex> lock(mutex);
    // Cancelled: what is ready in order is still taken; a gap no worker will fill ends it.
    auto settled = [&] {
      return failure || running == 0 || free_item() || (ready.count(k) > 0 && (held_back > 0 || run_ready()));
    };
    while (!failure) {
      auto it = ready.find(k);
      if (it != ready.end()) {
        *result = std::move(it->second);
        ready.erase(it);
        return true;
      }
      if (free_item()) {
        const std::uint64_t mine = next++;
        lock.unlock();
        Result computed = (*work)(mine);  // an exception reaches RunOrdered
        lock.lock();
        if (mine == k) {
          *result = std::move(computed);
          return true;
        }
        ready.emplace(mine, std::move(computed));
      } else if (running == 0) {
        return false;
      } else {
        consumer_waiting = true;
        while (!ready_changed.wait_for(lock, kPoll, settled)) {
        }
        consumer_waiting = false;
      }
    }
    return false;
  }
};

// Runs work(k) for k = 0..count-1 on `jobs` threads (the calling thread and jobs - 1
// workers) and hands each result to consume(k, result) on the calling thread, in order of
// k. Workers stay at most `window` items ahead of the consumer, so memory does not grow
// with `count`. An exception from work or consume stops the workers and is rethrown here.
// When `cancelled` (polled) turns true, workers take no new items, the ones in progress
// finish, and the consumer takes every result that is complete and in order, then returns.
// Returns how many were consumed.
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
  auto is_cancelled = [&] { return cancelled && cancelled(); };
  if (jobs == 1) return RunHere<Result>(count, work, consume, is_cancelled);
  OrderedRun<Result> run;
  run.count = count;
  run.window = window;
  run.batch = std::max<std::uint64_t>(1, std::min<std::uint64_t>(16, window / 2));
  run.work = &work;
  run.cancelled = cancelled;
  run.running = jobs - 1;
  auto worker = [&run] {
    run.WorkLoop();
    {
      std::lock_guard<std::mutex> lock(run.mutex);
      --run.running;
    }
    run.ready_changed.notify_all();
  };
  std::vector<std::thread> threads;
  for (int i = 0; i + 1 < jobs; ++i) threads.emplace_back(worker);
  auto finish = [&] {
    {
      std::lock_guard<std::mutex> lock(run.mutex);
      run.stop = true;
    }
    run.consumed_changed.notify_all();
    for (auto& thread : threads) thread.join();
  };
  std::uint64_t done = 0;
  try {
    for (std::uint64_t k = 0; k < count; ++k) {
      Result result;
      if (!run.Take(k, &result)) break;
      consume(k, std::move(result));
      done = k + 1;
      {
        std::lock_guard<std::mutex> lock(run.mutex);
        run.consumed = k + 1;
      }
      run.consumed_changed.notify_all();
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
  if (run.failure) std::rethrow_exception(run.failure);
  return done;
}

}  // namespace shapebench
