// SIGINT and SIGTERM: an interrupted command leaves complete files only.
//
// Files are written only inside deferred sections (DeferInterrupts): the output of `run`,
// `sensitivity`, `check --junit`, `merge`, and a whole sweep. A signal outside one ends
// the process at once with 128 + the signal (130 SIGINT, 143 SIGTERM) after a line on
// stderr: nothing is on disk half-written then. Inside one, the signal is recorded; the
// code finishes what it is writing (a sweep stops taking points, writes the rows that
// are complete and in order, flushes results.csv.partial) and then throws
// InterruptedError, which the CLI reports and exits with 128 + the signal. A second
// signal ends the process at once wherever it is (a sweep's partial file may then end in
// a torn row, which a resumed sweep cuts off and runs again).
#pragma once

#include <stdexcept>
#include <string>

namespace shapebench {

// Installs the handlers for SIGINT and SIGTERM (the CLI does, once, at start).
void InstallInterruptHandlers();

// The signal received inside a deferred section (SIGINT, SIGTERM), 0 when none.
int PendingInterrupt();

// For tests: forget a recorded signal.
void ClearPendingInterrupt();

// A deferred section: while one exists, a first signal is recorded instead of ending the
// process. Sections nest.
class DeferInterrupts {
 public:
  DeferInterrupts();
  ~DeferInterrupts();
  DeferInterrupts(const DeferInterrupts&) = delete;
  DeferInterrupts& operator=(const DeferInterrupts&) = delete;
};

// What the code throws after it has finished writing because a signal came.
class InterruptedError : public std::runtime_error {
 public:
  InterruptedError(int signal, const std::string& what);
  int signal() const { return signal_; }
  int exit_code() const { return 128 + signal_; }

 private:
  int signal_;
};

// "SIGINT", "SIGTERM", or "signal N".
std::string SignalName(int signal);

// Throws InterruptedError("interrupted by SIGxxx: " + state) when a signal is pending.
void ThrowIfInterrupted(const std::string& state);

}  // namespace shapebench
