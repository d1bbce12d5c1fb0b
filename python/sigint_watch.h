// Ctrl-C for a sweep run on a thread other than Python's main thread (docs/python.md,
// "Threads and the GIL"). Python handles signals on its main thread only: there
// PyErr_CheckSignals raises KeyboardInterrupt, elsewhere it sees nothing, and a sweep on a
// worker ran to its end (21 s in issue 32's trial) while the main thread had long stopped.
// A SigintWatch puts a SIGINT handler of its own in front of Python's: it counts the
// signal and hands it on, so Python's main thread still gets its KeyboardInterrupt.
#pragma once

#include <cstdint>

namespace shapebench::python {

class SigintWatch {
 public:
  // Installs the counting handler (the first watch of the process does) unless SIGINT is
  // ignored or left to the default action (then Ctrl-C does not stop a sweep, or ends the
  // process).
  SigintWatch();
  // The last watch restores the handler it found, unless another was installed since
  // (signal.signal() while a sweep ran): that one stays.
  ~SigintWatch();
  SigintWatch(const SigintWatch&) = delete;
  SigintWatch& operator=(const SigintWatch&) = delete;

  // Whether a SIGINT came since this watch began.
  bool Fired() const;

 private:
  std::uint64_t start_;
};

}  // namespace shapebench::python
