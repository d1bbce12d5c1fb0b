#include "common/interrupt.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstring>

namespace shapebench {
namespace {

std::atomic<int> g_signal{0};
std::atomic<int> g_defer_depth{0};
static_assert(std::atomic<int>::is_always_lock_free, "the handler needs a lock-free atomic");

void WriteStderr(const char* text) {
  const ssize_t ignored = write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

extern "C" void HandleInterrupt(int signal) {
  // Only async-signal-safe calls here: atomics, write, _exit. The first signal is
  // recorded once: a second one, delivered to another thread while this handler runs,
  // finds it taken and ends the process.
  int none = 0;
  if (g_defer_depth.load() > 0 && g_signal.compare_exchange_strong(none, signal)) return;
  WriteStderr(signal == SIGINT ? "\nerror: interrupted by SIGINT\n" : "\nerror: interrupted by SIGTERM\n");
  _exit(128 + signal);
}

}  // namespace

void InstallInterruptHandlers() {
  struct sigaction action;
  std::memset(&action, 0, sizeof action);
  action.sa_handler = HandleInterrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // reads and writes in progress carry on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int PendingInterrupt() { return g_signal.load(); }

void ClearPendingInterrupt() { g_signal.store(0); }

DeferInterrupts::DeferInterrupts() { g_defer_depth.fetch_add(1); }

DeferInterrupts::~DeferInterrupts() { g_defer_depth.fetch_sub(1); }

InterruptedError::InterruptedError(int signal, const std::string& what)
    : std::runtime_error(what), signal_(signal) {}

std::string SignalName(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "signal " + std::to_string(signal);
}

void ThrowIfInterrupted(const std::string& state) {
  const int signal = PendingInterrupt();
  if (signal != 0) throw InterruptedError(signal, "interrupted by " + SignalName(signal) + ": " + state);
}

}  // namespace shapebench
