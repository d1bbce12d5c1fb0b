#include "bench/sweep/sweep_mpi.h"

#include <cstdlib>
#include <iostream>
#include <string>

#include "bench/sweep/distribute.h"

#ifdef SHAPEBENCH_HAVE_MPI
// Only MPI's C API: never its deprecated C++ bindings (warnings, another library).
#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <fcntl.h>
#include <mpi.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <deque>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "bench/sweep/run_identity.h"
#include "bench/sweep/sweep_mpi_messages.h"
#include "bench/sweep/sweep_mpi_worker.h"
#endif

namespace shapebench::bench {

bool LaunchedByMpiLauncher() {
  const char* switch_value = std::getenv("SHAPEBENCH_MPI");
  if (switch_value != nullptr && std::string(switch_value) == "0") return false;
  // Open MPI's mpirun, PMIx launchers (srun --mpi=pmix, prterun), MPICH's hydra.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

#ifndef SHAPEBENCH_HAVE_MPI

class MpiRun::Impl {};

MpiRun::MpiRun() {
  if (LaunchedByMpiLauncher()) {
    std::cerr << "warning: started by an MPI launcher, but this shapebench was built without MPI "
                 "(install libopenmpi-dev and build again): every rank runs the whole command\n";
  }
}
MpiRun::~MpiRun() = default;
int MpiRun::Finish(int code) { return code; }

#else

namespace {

using namespace mpi;  // the messages (sweep_mpi_messages.h) and the Worker

// What SHAPEBENCH_MPI_STATS=1 prints after each distribution (docs/scaling.md).
struct Stats {
  std::uint64_t rows = 0;
  std::uint64_t messages = 0;
  std::uint64_t bytes = 0;
  double writer_s = 0.0;  // rank 0's main thread consuming rows and decoding messages
};

// Rank 0's side of one distribution (Distributor::Coordinate).
class Coordinator {
 public:
  Coordinator(int ranks, std::uint64_t first, std::uint64_t end, int jobs, const EncodedWork& work,
              const EncodedConsume& consume, const DistributionHooks& hooks)
      : ranks_(ranks), jobs_(std::max(jobs, 1)), next_(first), written_(first), end_(end), work_(work),
        consume_(consume), hooks_(hooks), slots_(static_cast<std::size_t>(ranks), 0),
        outstanding_(static_cast<std::size_t>(ranks), 0) {}

  // Returns whether every point was consumed and every rank took part (then each is told
  // the distribution ended); stops early when `cancelled`.
  bool Run(const std::function<bool()>& cancelled) {
    std::vector<std::thread> threads;
    for (int i = 0; i < jobs_; ++i) threads.emplace_back([this] { LocalThread(); });
    try {
      while (!Failed()) {
        Poll();
        TopUp();
        Consume();
        SpillWaiting(false);
        if (cancelled && cancelled()) break;
        if (written_ == end_ && hellos_ == ranks_ - 1) break;
        std::unique_lock<std::mutex> lock(mutex_);
        ready_changed_.wait_for(lock, kPoll, [&] { return failure_ || ready_.count(written_) > 0; });
      }
    } catch (...) {
      StopLocal(&threads);
      throw;
    }
    SpillWaiting(false);  // before the local threads' points in progress end
    StopLocal(&threads);
    if (failure_) std::rethrow_exception(failure_);
    Consume();  // what the local threads completed before they stopped
    const bool complete = written_ == end_ && hellos_ == ranks_ - 1;
    if (!complete) SpillWaiting(true);  // what waits behind a point that will not come
    if (complete) {
      for (int rank = 1; rank < ranks_; ++rank) Send("", rank, kStop);
    }
    return complete;
  }

  const Stats& stats() const { return stats_; }

 private:
  bool Failed() {
    std::lock_guard<std::mutex> lock(mutex_);
    return failure_ != nullptr;
  }

  // The next chunk [*begin, *begin + *count) under mutex_; false when none may start now:
  // all handed out, stopping, more than a window of points ahead of the writer, or not
  // every rank has said hello yet. (The last costs one round trip at the start; then the
  // first chunks are sized for every thread of the run, and every rank gets its share.)
  bool TakeChunk(std::uint64_t* begin, std::uint64_t* count) {
    if (hellos_ < ranks_ - 1) return false;
    std::uint64_t threads = static_cast<std::uint64_t>(jobs_);
    for (const int slots : slots_) threads += static_cast<std::uint64_t>(slots);
    const std::uint64_t window = std::max<std::uint64_t>(4096, 4 * kMaxChunk * threads);
    // Known points (read from disk: work_ returns them at once) go straight to ready_.
    while (hooks_.known && !stop_ && next_ < end_ && next_ < written_ + window && hooks_.known(next_)) {
      ready_.emplace(next_, Waiting{work_(next_), std::chrono::steady_clock::now(), true});
      ++next_;
      ready_changed_.notify_one();
    }
    if (stop_ || next_ >= end_ || next_ >= written_ + window) return false;
    *begin = next_;
    *count = std::clamp<std::uint64_t>((end_ - next_) / (4 * threads), 1, kMaxChunk);
    *count = std::min(*count, end_ - next_);
    for (std::uint64_t i = 1; hooks_.known && i < *count; ++i) {
      if (hooks_.known(next_ + i)) *count = i;  // a chunk ends before a known point
    }
    next_ += *count;
    return true;
  }

  // Results that waited hooks_.spill_after behind an earlier point (every one: `all`),
  // each handed once to hooks_.spill; at most every kSpillPoll unless `all`.
  void SpillWaiting(bool all) {
    if (!hooks_.spill) return;
    const auto now = std::chrono::steady_clock::now();
    if (!all && now - last_spill_ < kSpillPoll) return;
    last_spill_ = now;
    std::vector<std::pair<std::uint64_t, std::string>> waiting;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& [k, result] : ready_) {
        if (result.spilled || (!all && now - result.at < hooks_.spill_after)) continue;
        result.spilled = true;
        waiting.emplace_back(k, result.bytes);
      }
    }
    for (const auto& [k, bytes] : waiting) hooks_.spill(k, bytes);
  }

  void LocalThread() {
    while (true) {
      std::uint64_t begin = 0;
      std::uint64_t count = 0;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        while (!TakeChunk(&begin, &count)) {
          if (stop_ || next_ >= end_) return;
          work_changed_.wait(lock);
        }
      }
      std::vector<std::string> results;
      try {
        for (std::uint64_t k = begin; k < begin + count && !stop_; ++k) results.push_back(work_(k));
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!failure_) failure_ = std::current_exception();
        stop_ = true;
        ready_changed_.notify_all();
        work_changed_.notify_all();
        return;
      }
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto now = std::chrono::steady_clock::now();
        for (std::size_t i = 0; i < results.size(); ++i) ready_.emplace(begin + i, Waiting{std::move(results[i]), now, false});
      }
      ready_changed_.notify_one();
    }
  }

  void StopLocal(std::vector<std::thread>* threads) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    work_changed_.notify_all();
    for (std::thread& thread : *threads) thread.join();
  }

  // Takes every message that has arrived: hellos and results.
  void Poll() {
    std::string bytes;
    int tag = 0;
    int source = 0;
    while (ReceiveAny(MPI_ANY_SOURCE, &bytes, &tag, &source)) {
      const auto start = std::chrono::steady_clock::now();
      std::size_t at = 0;
      if (tag == kHello) {
        const int slots = static_cast<int>(std::clamp<std::uint64_t>(GetU64(bytes, &at), 1, 4096));
        {
          std::lock_guard<std::mutex> lock(mutex_);  // TakeChunk reads these on the local threads
          slots_[static_cast<std::size_t>(source)] = slots;
          ++hellos_;
        }
        work_changed_.notify_all();
      } else if (tag == kResult) {
        const std::uint64_t begin = GetU64(bytes, &at);
        const std::uint64_t count = GetU64(bytes, &at);
        std::vector<std::string> rows;
        for (std::uint64_t i = 0; i < count; ++i) {
          const std::uint64_t size = GetU64(bytes, &at);
          if (at + size > bytes.size()) throw std::runtime_error("MPI: a result arrived cut short");
          rows.push_back(bytes.substr(at, size));
          at += size;
        }
        std::lock_guard<std::mutex> lock(mutex_);
        const auto now = std::chrono::steady_clock::now();
        for (std::uint64_t i = 0; i < count; ++i) ready_.emplace(begin + i, Waiting{std::move(rows[i]), now, false});
        --outstanding_[static_cast<std::size_t>(source)];
      } else {
        throw std::runtime_error("MPI: rank " + std::to_string(source) + " sent an unexpected message");
      }
      ++stats_.messages;
      stats_.bytes += bytes.size();
      stats_.writer_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  }

  // Gives every rank that said hello chunks until it holds one more than its threads (so
  // none waits for a round trip).
  void TopUp() {
    for (int rank = 1; rank < ranks_; ++rank) {
      const std::size_t r = static_cast<std::size_t>(rank);
      while (slots_[r] > 0 && outstanding_[r] < slots_[r] + 1) {
        std::uint64_t begin = 0;
        std::uint64_t count = 0;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          if (!TakeChunk(&begin, &count)) return;
        }
        std::string chunk;
        PutU64(&chunk, begin);
        PutU64(&chunk, count);
        Send(chunk, rank, kChunk);
        ++outstanding_[r];
      }
    }
  }

  // Hands the results that are next in order to consume_, on this (the calling) thread.
  void Consume() {
    const auto start = std::chrono::steady_clock::now();
    bool any = false;
    while (true) {
      std::string bytes;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const auto it = ready_.find(written_);
        if (it == ready_.end()) break;
        bytes = std::move(it->second.bytes);
        ready_.erase(it);
      }
      consume_(written_, std::move(bytes));
      any = true;
      ++stats_.rows;
      std::lock_guard<std::mutex> lock(mutex_);
      ++written_;
    }
    if (any) work_changed_.notify_all();  // the window moved
    stats_.writer_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }

  const int ranks_;
  const int jobs_;
  std::uint64_t next_;
  std::uint64_t written_;
  const std::uint64_t end_;
  const EncodedWork& work_;
  const EncodedConsume& consume_;
  const DistributionHooks& hooks_;
  std::vector<int> slots_;        // each rank's threads (0: no hello yet); written under mutex_
  std::vector<int> outstanding_;  // each rank's chunks not yet returned
  int hellos_ = 0;  // written under mutex_
  std::mutex mutex_;
  std::condition_variable ready_changed_;
  std::condition_variable work_changed_;
  // A result waiting to be consumed: since when, and whether hooks_.spill has it.
  struct Waiting {
    std::string bytes;
    std::chrono::steady_clock::time_point at;
    bool spilled = false;
  };
  static constexpr std::chrono::milliseconds kSpillPoll{20};
  std::map<std::uint64_t, Waiting> ready_;
  std::chrono::steady_clock::time_point last_spill_{};
  std::atomic<bool> stop_{false};  // read between a chunk's points without the lock
  std::exception_ptr failure_;
  Stats stats_;
};

}  // namespace

class MpiRun::Impl : public Distributor {
 public:
  Impl() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
    MPI_Comm host;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &host);
    MPI_Comm_size(host, &host_size_);
    MPI_Comm_free(&host);
    if (rank_ > 0) {
      // Rank 0 speaks for the run; the others' words would repeat its own.
      stderr_fd_ = dup(STDERR_FILENO);
      const int null = open("/dev/null", O_WRONLY);
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
      close(null);
    }
    SetDistributor(this);
  }

  std::uint64_t Coordinate(std::uint64_t first, std::uint64_t end, int jobs, const EncodedWork& work,
                           const EncodedConsume& consume, const std::function<bool()>& cancelled,
                           const DistributionHooks& hooks) override;
  void Serve(int jobs, const EncodedWork& work) override;
  void Agree(const std::string& identity) override;
  int ProcessesOnHost() const override { return host_size_; }
  bool coordinator() const override { return rank_ == 0; }
  int Finish(int code);

 private:
  bool Rendezvous(bool ready, const std::string& identity = "");
  std::vector<std::string> AllGather(const std::string& mine) const;
  [[noreturn]] void Fatal(const std::string& message, int code);

  int rank_ = 0;
  int size_ = 1;
  int host_size_ = 1;
  int stderr_fd_ = STDERR_FILENO;
  bool rendezvoused_ = false;
  bool everyone_ready_ = false;  // every rank reached its first distribution
  bool broken_ = false;          // rank 0: a distribution did not end cleanly
  bool quit_ = false;            // workers: rank 0 has no more distributions
  bool finished_ = false;
};

namespace {

// Waits for a non-blocking collective, polling: MPI's blocking waits spin on a core.
void WaitPolled(MPI_Request* request) {
  int done = 0;
  while (MPI_Test(request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && done == 0) {
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace

// Every rank's bytes, in rank order.
std::vector<std::string> MpiRun::Impl::AllGather(const std::string& mine) const {
  int size = static_cast<int>(mine.size());
  std::vector<int> sizes(static_cast<std::size_t>(size_), 0);
  MPI_Request request;
  MPI_Iallgather(&size, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
  WaitPolled(&request);
  std::vector<int> offsets(sizes.size(), 0);
  for (std::size_t i = 1; i < sizes.size(); ++i) offsets[i] = offsets[i - 1] + sizes[i - 1];
  std::string all(static_cast<std::size_t>(offsets.back() + sizes.back()), '\0');
  MPI_Iallgatherv(mine.data(), size, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE, MPI_COMM_WORLD,
                  &request);
  WaitPolled(&request);
  std::vector<std::string> each;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    each.push_back(all.substr(static_cast<std::size_t>(offsets[i]), static_cast<std::size_t>(sizes[i])));
  }
  return each;
}

// Once per run, before a rank's first distribution (Agree, or the distribution itself) or
// at its end: whether every rank got there ready (a rank whose command failed first, e.g.
// on a file only it cannot read, says not ready, and nobody waits for it) with rank 0's
// identity (the same command, files, --set options and shapebench: run_identity.h).
bool MpiRun::Impl::Rendezvous(bool ready, const std::string& identity) {
  rendezvoused_ = true;
  std::vector<std::string> all = AllGather((ready ? "1" : "0") + identity);
  std::string not_ready;
  std::vector<int> differing;
  for (int rank = 0; rank < size_; ++rank) {
    std::string& bytes = all[static_cast<std::size_t>(rank)];
    if (bytes.empty() || bytes[0] != '1') not_ready += (not_ready.empty() ? "" : ", ") + std::to_string(rank);
    bytes.erase(0, 1);
    if (bytes != all[0]) differing.push_back(rank);
  }
  everyone_ready_ = not_ready.empty() && differing.empty();
  if (!everyone_ready_ && rank_ == 0 && ready) {
    if (not_ready.empty()) throw std::runtime_error(RankMismatchMessage(all, differing));
    throw std::runtime_error("MPI rank " + not_ready + " of " + std::to_string(size_) +
                             " failed before the points were handed out (its own error is not "
                             "shown: ranks other than 0 are quiet); run the command without mpirun to see it");
  }
  return everyone_ready_;
}

void MpiRun::Impl::Agree(const std::string& identity) {
  if (!rendezvoused_) Rendezvous(true, identity);
}

std::uint64_t MpiRun::Impl::Coordinate(std::uint64_t first, std::uint64_t end, int jobs,
                                       const EncodedWork& work, const EncodedConsume& consume,
                                       const std::function<bool()>& cancelled, const DistributionHooks& hooks) {
  if (!rendezvoused_) Rendezvous(true);
  if (!everyone_ready_ || broken_) throw std::runtime_error("MPI: the run cannot distribute points any more");
  broken_ = true;  // until the distribution ends cleanly
  Coordinator coordinator(size_, first, end, jobs, work, consume, hooks);
  const auto start = std::chrono::steady_clock::now();
  broken_ = !coordinator.Run(cancelled);
  const Stats& stats = coordinator.stats();
  const char* show = std::getenv("SHAPEBENCH_MPI_STATS");
  if (show != nullptr && std::string(show) == "1") {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "mpi: " << stats.rows << " points on " << size_ << " ranks in " << seconds << " s ("
              << stats.rows / seconds << " points/s); rank 0 busy " << stats.writer_s << " s ("
              << stats.rows / std::max(stats.writer_s, 1e-9) << " rows/s); " << stats.messages
              << " messages, " << stats.bytes << " bytes received\n";
  }
  return stats.rows;
}

void MpiRun::Impl::Serve(int jobs, const EncodedWork& work) {
  if (quit_) return;
  if (!rendezvoused_ && !Rendezvous(true)) quit_ = true;
  if (!everyone_ready_) quit_ = true;
  if (quit_) return;
  try {
    quit_ = Worker(rank_, jobs, work).Run();
  } catch (const std::exception& error) {
    Fatal(std::string("error: MPI rank ") + std::to_string(rank_) + ": " + error.what(), 1);
  }
}

void MpiRun::Impl::Fatal(const std::string& message, int code) {
  const std::string line = message + "\n";
  if (write(stderr_fd_, line.data(), line.size()) < 0) {
    // Nothing left to tell it to.
  }
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

int MpiRun::Impl::Finish(int code) {
  if (finished_) return rank_ == 0 ? code : 0;
  finished_ = true;
  std::cout.flush();
  std::cerr.flush();
  if (!rendezvoused_) {
    Rendezvous(false);  // no distribution from here: nobody waits for one
  } else if (rank_ == 0 && broken_) {
    // Ranks may be computing or sending: only ending them all stops the run. The rows
    // written are complete and flushed; the same command resumes.
    MPI_Abort(MPI_COMM_WORLD, code != 0 ? code : 1);
  } else if (rank_ == 0 && everyone_ready_) {
    for (int rank = 1; rank < size_; ++rank) Send("", rank, kQuit);
  } else if (everyone_ready_) {
    std::string bytes;
    int tag = 0;
    int source = 0;
    while (!quit_) {
      if (!ReceiveAny(0, &bytes, &tag, &source)) std::this_thread::sleep_for(kPoll);
      quit_ = quit_ || tag == kQuit;
    }
  }
  SetDistributor(nullptr);
  MPI_Finalize();
  return rank_ == 0 ? code : 0;
}

MpiRun::MpiRun() {
  if (LaunchedByMpiLauncher()) impl_ = std::make_unique<Impl>();
}

MpiRun::~MpiRun() { Finish(0); }

int MpiRun::Finish(int code) { return impl_ ? impl_->Finish(code) : code; }

#endif

}  // namespace shapebench::bench
