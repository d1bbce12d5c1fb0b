// The files of a sweep's output directory (bench/sweep/sweep_runner.h) handled with care:
// one writer at a time, and nothing read that is not a regular file of bounded size.
#pragma once

#include <cstdint>
#include <string>

namespace shapebench::bench {

// The lock file of an output directory; it holds its holder's PID as text.
inline constexpr const char* kOutputLockFile = ".shapebench.lock";

// An exclusive flock(2) on DIR/.shapebench.lock, held while this object lives. Two
// sweeps (or a sweep and a merge) writing one directory would interleave their rows;
// the second is refused instead. The kernel drops the lock when the process ends, even
// on SIGKILL, so a stale lock file is harmless. The file is never removed: removing it
// would let a third process lock a new file while the second holds the old one.
class OutputDirLock {
 public:
  // Throws std::runtime_error naming the directory (and the holder's PID when another
  // process holds the lock).
  explicit OutputDirLock(const std::string& dir);
  ~OutputDirLock();
  OutputDirLock(const OutputDirLock&) = delete;
  OutputDirLock& operator=(const OutputDirLock&) = delete;

 private:
  int fd_ = -1;
};

// Throws std::runtime_error unless `path` (symbolic links followed) is a regular file: a
// FIFO would block the reader forever, a device such as /dev/zero never ends. Opened
// with O_NONBLOCK to look, so a FIFO without a writer does not block the check itself.
void RequireRegularFile(const std::string& path);

// The whole of a regular file of at most `max_bytes` bytes (std::runtime_error otherwise).
std::string ReadRegularFile(const std::string& path, std::uint64_t max_bytes);

}  // namespace shapebench::bench
