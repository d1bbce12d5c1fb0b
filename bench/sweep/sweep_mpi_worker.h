// A rank other than 0 during one distribution of an MPI run (bench/sweep/sweep_mpi.h):
// its --jobs threads compute the chunks rank 0 sends, their results go back without
// blocking. Included by sweep_mpi.cc only, inside SHAPEBENCH_HAVE_MPI.
#pragma once

#include <signal.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdlib>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "bench/sweep/distribute.h"
#include "bench/sweep/sweep_mpi_messages.h"

namespace shapebench::bench::mpi {

// A rank other than 0 during one distribution (Distributor::Serve): chunks from rank 0 to
// its threads, their results back, until rank 0 says stop (or quit).
class Worker {
 public:
  Worker(int rank, int jobs, const EncodedWork& work) : jobs_(std::max(jobs, 1)), work_(work) {
    // SHAPEBENCH_TEST_MPI_DIE=R:K: rank R kills itself (SIGKILL) after K points; how the
    // tests (tests/bench/sweep_mpi_test.cc) lose a rank mid-run at a known place.
    const char* die = std::getenv("SHAPEBENCH_TEST_MPI_DIE");
    const std::string prefix = std::to_string(rank) + ":";
    if (die != nullptr && std::string(die).rfind(prefix, 0) == 0) {
      die_after_ = std::strtoull(die + prefix.size(), nullptr, 10);
    }
  }

  // Returns whether rank 0 said quit (no more distributions) instead of stop.
  bool Run() {
    std::string hello;
    PutU64(&hello, static_cast<std::uint64_t>(jobs_));
    Send(hello, 0, kHello);
    std::vector<std::thread> threads;
    for (int i = 0; i < jobs_; ++i) threads.emplace_back([this] { Compute(); });
    bool quit = false;
    bool stop = false;
    try {
      while (!stop) {
        std::string bytes;
        int tag = 0;
        int source = 0;
        while (!stop && ReceiveAny(0, &bytes, &tag, &source)) {
          std::lock_guard<std::mutex> lock(mutex_);
          if (tag == kChunk) {
            std::size_t at = 0;
            const std::uint64_t begin = GetU64(bytes, &at);
            chunks_.emplace_back(begin, GetU64(bytes, &at));
            chunk_added_.notify_one();
          }
          quit = tag == kQuit;
          stop = tag == kStop || tag == kQuit;
        }
        SendResults();
        std::unique_lock<std::mutex> lock(mutex_);
        if (failure_) std::rethrow_exception(failure_);
        if (!stop) result_added_.wait_for(lock, kPoll, [&] { return !results_.empty() || failure_; });
      }
    } catch (...) {
      End(&threads);
      throw;
    }
    End(&threads);
    while (!sending_.empty()) {  // rank 0 has them all when it says stop: they complete at once
      SendResults();
      if (!sending_.empty()) std::this_thread::sleep_for(kPoll);
    }
    return quit;
  }

 private:
  void Compute() {
    while (true) {
      std::pair<std::uint64_t, std::uint64_t> chunk;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        chunk_added_.wait(lock, [&] { return ended_ || !chunks_.empty(); });
        if (ended_) return;
        chunk = chunks_.front();
        chunks_.pop_front();
      }
      std::string message;
      PutU64(&message, chunk.first);
      PutU64(&message, chunk.second);
      try {
        for (std::uint64_t k = chunk.first; k < chunk.first + chunk.second; ++k) {
          const std::string result = work_(k);
          if (die_after_ > 0 && ++computed_ >= die_after_) raise(SIGKILL);
          PutU64(&message, result.size());
          message += result;
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (!failure_) failure_ = std::current_exception();
        result_added_.notify_all();
        return;
      }
      std::lock_guard<std::mutex> lock(mutex_);
      results_.push_back(std::move(message));
      result_added_.notify_one();
    }
  }

  // Sends the finished chunks without waiting (a blocking send of a message above MPI's
  // eager limit spins until rank 0, which polls, takes it) and completes the earlier sends.
  void SendResults() {
    while (true) {
      auto message = std::make_unique<std::string>();
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (results_.empty()) break;
        *message = std::move(results_.front());
        results_.pop_front();
      }
      MPI_Request request;
      MPI_Isend(message->data(), static_cast<int>(message->size()), MPI_BYTE, 0, kResult, MPI_COMM_WORLD,
                &request);
      sending_.emplace_back(request, std::move(message));
    }
    while (!sending_.empty()) {
      int done = 0;
      MPI_Test(&sending_.front().first, &done, MPI_STATUS_IGNORE);
      if (done == 0) return;
      sending_.pop_front();
    }
  }

  void End(std::vector<std::thread>* threads) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ended_ = true;
    }
    chunk_added_.notify_all();
    for (std::thread& thread : *threads) thread.join();
  }

  const int jobs_;
  const EncodedWork& work_;
  std::mutex mutex_;
  std::condition_variable chunk_added_;
  std::condition_variable result_added_;
  std::deque<std::pair<std::uint64_t, std::uint64_t>> chunks_;
  std::deque<std::string> results_;
  std::deque<std::pair<MPI_Request, std::unique_ptr<std::string>>> sending_;  // main thread only
  bool ended_ = false;
  std::exception_ptr failure_;
  std::uint64_t die_after_ = 0;
  std::atomic<std::uint64_t> computed_{0};
};

}  // namespace shapebench::bench::mpi
