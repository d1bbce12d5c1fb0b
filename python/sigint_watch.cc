// SIGINT counted before Python's handler (python/sigint_watch.h).
#include "python/sigint_watch.h"

#include <signal.h>

#include <atomic>
#include <mutex>

namespace shapebench::python {
namespace {

std::atomic<std::uint64_t> g_count{0};
std::mutex g_mutex;  // guards g_watches, g_previous and the installation
int g_watches = 0;
bool g_installed = false;
struct sigaction g_previous;

// Async-signal-safe: a lock-free increment and the previous handler's own call.
void CountAndChain(int signal, siginfo_t* info, void* context) {
  g_count.fetch_add(1, std::memory_order_relaxed);
  if ((g_previous.sa_flags & SA_SIGINFO) != 0) {
    g_previous.sa_sigaction(signal, info, context);
  } else if (g_previous.sa_handler != SIG_DFL && g_previous.sa_handler != SIG_IGN) {
    g_previous.sa_handler(signal);
  }
}

bool OursInstalled() {
  struct sigaction current {};
  return sigaction(SIGINT, nullptr, &current) == 0 && (current.sa_flags & SA_SIGINFO) != 0 &&
         current.sa_sigaction == CountAndChain;
}

}  // namespace

SigintWatch::SigintWatch() {
  const std::lock_guard<std::mutex> lock(g_mutex);
  if (g_watches++ == 0) {
    struct sigaction previous {};
    sigaction(SIGINT, nullptr, &previous);
    const bool handled = (previous.sa_flags & SA_SIGINFO) != 0 ||
                         (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN);
    if (handled) {
      g_previous = previous;
      struct sigaction ours {};
      ours.sa_sigaction = CountAndChain;
      ours.sa_flags = SA_SIGINFO | (previous.sa_flags & SA_RESTART);
      ours.sa_mask = previous.sa_mask;
      g_installed = sigaction(SIGINT, &ours, nullptr) == 0;
    }
  }
  start_ = g_count.load();
}

SigintWatch::~SigintWatch() {
  const std::lock_guard<std::mutex> lock(g_mutex);
  if (--g_watches == 0 && g_installed) {
    if (OursInstalled()) sigaction(SIGINT, &g_previous, nullptr);
    g_installed = false;
  }
}

bool SigintWatch::Fired() const { return g_count.load() != start_; }

}  // namespace shapebench::python
