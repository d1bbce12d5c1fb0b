// A bounded, ordered worker pool: results computed on several threads, consumed on the
// calling thread in order, so output does not depend on the thread count.
#pragma once

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

namespace shapebench {

// Results that wait for an earlier item, handed over while they wait: a sweep writes them
// ahead of its order (bench/sweep/rows_ahead.h), so that an item finished behind a slow
// one is not lost when the process ends before the slow one does. `take` gets each such
// result once, on a thread of RunOrdered's own, when it has waited `after`, and every
// result left unconsumed when a cancelled run ends (on the calling thread).
template <typename Result>
struct Spill {
  std::chrono::milliseconds after{100};
  std::function<void(std::uint64_t, const Result&)> take;
};

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
//
// Items are claimed in chunks and a chunk's results are handed over under one lock: a
// point of a fast sweep takes about 10 us, and a lock, a map node and a wake-up for each
// one were a few percent of two jobs' time. A chunk is guided (a quarter of what is left
// per job, one at the end) and lasts about kChunkTarget_s by the thread's last items (slow
// items go one at a time, so a signal still stops the run within 0.2 ms or one item). Every item
// claimed is computed, as before: the items before a cancelled one all complete. The
// results wait in a ring of `window` slots (item k in slot k % window), so nothing is
// allocated a point on the way from a worker to the consumer.
template <typename Result>
struct OrderedRun {
  using Work = std::function<Result(std::uint64_t)>;
  static constexpr std::chrono::milliseconds kPoll{20};
  static constexpr std::uint64_t kMaxChunk = 16;
  static constexpr double kChunkTarget_s = 2e-4;
  // A thread's chunk size for its next claim, from how long its last items took.
  struct Pace {
    std::uint64_t chunk = 1;  // the first claim: one item, timed
    void Timed(std::uint64_t size, std::chrono::steady_clock::duration took) {
      const double per_item_s = std::chrono::duration<double>(took).count() / static_cast<double>(size);
      const double fits = per_item_s > 0.0 ? kChunkTarget_s / per_item_s : static_cast<double>(kMaxChunk);
      chunk = fits >= static_cast<double>(kMaxChunk) ? kMaxChunk : std::max<std::uint64_t>(1, static_cast<std::uint64_t>(fits));
    }
  };

  std::uint64_t count = 0;
  std::uint64_t window = 0;
  std::uint64_t jobs = 1;
  std::uint64_t batch = 1;  // the consumer wakes for `batch` results in order
  const Work* work = nullptr;
  std::function<bool()> cancelled;
  std::mutex mutex;
  std::condition_variable ready_changed;
  std::condition_variable consumed_changed;
  std::vector<std::optional<Result>> ready;  // the ring: item k, consumed <= k < consumed + window
  std::uint64_t next = 0;
  std::uint64_t consumed = 0;
  int running = 0;    // worker threads not yet returned
  int held_back = 0;  // workers waiting for the consumer (the window)
  bool stop = false;
  bool consumer_waiting = false;
  std::exception_ptr failure;
  Pace consumer_pace;                    // the calling thread's, across its calls of Take
  std::vector<Result> consumer_computed;  // its chunk's results before they are published
  // With a Spill: when each slot's result was published, and whether it was handed over.
  const Spill<Result>* spill = nullptr;
  std::vector<std::chrono::steady_clock::time_point> published_at;
  std::vector<char> spilled;
  bool ended = false;  // the spilling thread stops
  std::condition_variable spill_changed;

  bool is_cancelled() const { return cancelled && cancelled(); }
  bool has(std::uint64_t k) const { return ready[k % ready.size()].has_value(); }
  // Under the lock: a batch in order from `consumed` on (or the end).
  bool run_ready() const {
    std::uint64_t n = 0;
    while (n < batch && consumed + n < count && has(consumed + n)) ++n;
    return n >= batch || consumed + n >= count;
  }
  // Under the lock: an item nobody has taken, within the window.
  bool free_item() const { return !stop && next < count && next < consumed + window && !is_cancelled(); }
  // Under the lock, with free_item(): claims the next chunk, returns its first item.
  std::uint64_t Claim(const Pace& pace, std::uint64_t* size) {
    const std::uint64_t guided = (count - next) / (4 * jobs);
    *size = std::min({std::max<std::uint64_t>(guided, 1), pace.chunk, consumed + window - next});
    const std::uint64_t first = next;
    next += *size;
    return first;
  }
  // Without the lock: the items of a claimed chunk into *results, every one (a claimed
  // item has started: a cancelled run still completes it).
  void Compute(std::uint64_t first, std::uint64_t size, Pace* pace, std::vector<Result>* results) {
    results->clear();
    const auto start = std::chrono::steady_clock::now();
    for (std::uint64_t i = 0; i < size; ++i) results->push_back((*work)(first + i));
    pace->Timed(size, std::chrono::steady_clock::now() - start);
  }
  // Under the lock: the computed results into the ring.
  void Publish(std::uint64_t first, std::vector<Result>* results) {
    const auto now = spill != nullptr ? std::chrono::steady_clock::now() : std::chrono::steady_clock::time_point{};
    for (std::uint64_t i = 0; i < results->size(); ++i) {
      const std::size_t slot = (first + i) % ready.size();
      ready[slot].emplace(std::move((*results)[i]));
      if (spill != nullptr) {
        published_at[slot] = now;
        spilled[slot] = 0;
      }
    }
  }

  // Under the lock: copies of the results not consumed that have waited at least `age`
  // and were not handed over yet, marked as handed over.
  void CollectWaiting(std::chrono::steady_clock::duration age, std::vector<std::pair<std::uint64_t, Result>>* out) {
    const auto now = std::chrono::steady_clock::now();
    for (std::uint64_t j = consumed; j < next; ++j) {
      const std::size_t slot = j % ready.size();
      if (!ready[slot].has_value() || spilled[slot] != 0 || now - published_at[slot] < age) continue;
      spilled[slot] = 1;
      out->emplace_back(j, *ready[slot]);
    }
  }

  // The spilling thread: every kPoll, the results that have waited spill->after.
  void SpillLoop() {
    std::vector<std::pair<std::uint64_t, Result>> waiting;
    std::unique_lock<std::mutex> lock(mutex);
    while (true) {
      spill_changed.wait_for(lock, kPoll, [&] { return ended; });
      if (ended || failure) return;
      CollectWaiting(spill->after, &waiting);
      if (waiting.empty()) continue;
      lock.unlock();
      try {
        for (const auto& [k, result] : waiting) spill->take(k, result);
      } catch (...) {
        lock.lock();
        if (!failure) failure = std::current_exception();
        stop = true;
        consumed_changed.notify_all();
        ready_changed.notify_all();
        return;
      }
      waiting.clear();
      lock.lock();
    }
  }

  void WorkLoop() {
    std::vector<Result> results;
    Pace pace;
    while (true) {
      std::uint64_t first = 0;
      std::uint64_t size = 0;
      {
        std::unique_lock<std::mutex> lock(mutex);
        if (stop || next >= count || is_cancelled()) return;
        if (!(next < consumed + window)) {
          ++held_back;
          if (consumer_waiting) ready_changed.notify_one();
          while (!consumed_changed.wait_for(lock, kPoll, [&] { return stop || next >= count || next < consumed + window; })) {
            if (is_cancelled()) {
              --held_back;
              return;
            }
          }
          --held_back;
          if (stop || next >= count || is_cancelled()) return;
        }
        first = Claim(pace, &size);
      }
      bool wake = true;
      try {
        Compute(first, size, &pace, &results);
        std::lock_guard<std::mutex> lock(mutex);
        Publish(first, &results);
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

  // The calling thread's: the results in order from item k on that are ready, at least
  // one, into *out (emptied first); it computes free chunks itself while k is not ready (a
  // consumer that only waited would be a third thread on two cores, preempting the
  // workers). Empty when k will not come (a failure; cancelled with k not computed).
  void Take(std::uint64_t k, std::vector<Result>* out) {
    out->clear();
    std::unique_lock<std::mutex> lock(mutex);
    // Cancelled: what is ready in order is still taken; a gap no worker will fill ends it.
    auto settled = [&] {
      return failure || running == 0 || free_item() || (has(k) && (held_back > 0 || run_ready()));
    };
    while (!failure) {
      if (has(k)) {
        for (std::uint64_t j = k; j < count && has(j); ++j) {
          std::optional<Result>& slot = ready[j % ready.size()];
          out->push_back(std::move(*slot));
          slot.reset();
        }
        return;
      }
      if (free_item()) {
        std::uint64_t size = 0;
        const std::uint64_t first = Claim(consumer_pace, &size);
        lock.unlock();
        Compute(first, size, &consumer_pace, &consumer_computed);  // an exception reaches RunOrdered
        lock.lock();
        Publish(first, &consumer_computed);
      } else if (running == 0) {
        return;
      } else {
        consumer_waiting = true;
        while (!ready_changed.wait_for(lock, kPoll, settled)) {
        }
        consumer_waiting = false;
      }
    }
  }
};

// Runs work(k) for k = 0..count-1 on `jobs` threads (the calling thread and jobs - 1
// workers) and hands each result to consume(k, result) on the calling thread, in order of
// k. Workers stay at most `window` items ahead of the consumer, so memory does not grow
// with `count`. An exception from work or consume stops the workers and is rethrown here.
// When `cancelled` (polled) turns true, workers take no new items, the ones in progress
// finish, and the consumer takes every result that is complete and in order, then returns.
// With a `spill` (several jobs), results waiting for an earlier item are handed to it too
// (Spill). Returns how many were consumed.
template <typename Result>
std::uint64_t RunOrdered(std::uint64_t count, int jobs,
                         const std::function<Result(std::uint64_t)>& work,
                         const std::function<void(std::uint64_t, Result&&)>& consume,
                         std::uint64_t window = 0,
                         const std::function<bool()>& cancelled = {},
                         const Spill<Result>* spill = nullptr) {
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
  run.jobs = static_cast<std::uint64_t>(jobs);
  run.ready.resize(std::min(window, count));
  run.work = &work;
  run.cancelled = cancelled;
  run.running = jobs - 1;
  if (spill != nullptr && spill->take) {
    run.spill = spill;
    run.published_at.resize(run.ready.size());
    run.spilled.assign(run.ready.size(), 0);
  }
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
  if (run.spill != nullptr) threads.emplace_back([&run] { run.SpillLoop(); });
  auto finish = [&] {
    {
      std::lock_guard<std::mutex> lock(run.mutex);
      run.stop = true;
      run.ended = true;
    }
    run.consumed_changed.notify_all();
    run.spill_changed.notify_all();
    for (auto& thread : threads) thread.join();
  };
  std::uint64_t done = 0;
  try {
    std::vector<Result> results;
    while (done < count) {
      run.Take(done, &results);
      if (results.empty()) break;
      for (Result& result : results) {
        consume(done, std::move(result));
        ++done;
      }
      {
        std::lock_guard<std::mutex> lock(run.mutex);
        run.consumed = done;
      }
      run.consumed_changed.notify_all();
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
  if (run.failure) std::rethrow_exception(run.failure);
  if (run.spill != nullptr && done < count) {  // cancelled: what waits behind a gap
    std::vector<std::pair<std::uint64_t, Result>> left;
    run.CollectWaiting(std::chrono::steady_clock::duration::zero(), &left);
    for (const auto& [k, result] : left) spill->take(k, result);
  }
  return done;
}

}  // namespace shapebench
