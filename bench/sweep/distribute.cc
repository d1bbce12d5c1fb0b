#include "bench/sweep/distribute.h"

#include <atomic>
#include <thread>

namespace shapebench::bench {
namespace {

std::atomic<Distributor*> current{nullptr};

}  // namespace

Distributor* CurrentDistributor() { return current.load(); }

void SetDistributor(Distributor* distributor) { current.store(distributor); }

int DefaultJobs() {
  const int threads = static_cast<int>(std::thread::hardware_concurrency());
  const int processes = CurrentDistributor() != nullptr ? CurrentDistributor()->ProcessesOnHost() : 1;
  return threads / processes > 0 ? threads / processes : 1;
}

}  // namespace shapebench::bench
