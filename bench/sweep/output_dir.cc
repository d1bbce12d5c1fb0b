#include "bench/sweep/output_dir.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace shapebench::bench {
namespace {

// Opens `path` for reading without blocking and checks that it is a regular file.
int OpenRegular(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error(path + ": cannot read: " + std::strerror(errno));
  struct stat info {};
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd);
    throw std::runtime_error(path + ": not a regular file (a FIFO, device or directory); "
                             "remove it or choose another directory");
  }
  return fd;
}

// What the lock file says about its holder ("pid 1234"), or "" when it says nothing.
std::string Holder(int fd) {
  char text[32] = {};
  const ssize_t size = pread(fd, text, sizeof text - 1, 0);
  std::string pid(text, size > 0 ? static_cast<std::size_t>(size) : 0);
  while (!pid.empty() && (pid.back() == '\n' || pid.back() == ' ')) pid.pop_back();
  if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos) return "";
  return "pid " + pid;
}

}  // namespace

OutputDirLock::OutputDirLock(const std::string& dir) {
  const std::string path = dir + "/" + kOutputLockFile;
  fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    throw std::runtime_error("cannot lock " + dir + ": " + path + ": " + std::strerror(errno));
  }
  struct stat info {};
  if (fstat(fd_, &info) != 0 || !S_ISREG(info.st_mode)) {
    close(fd_);
    throw std::runtime_error("cannot lock " + dir + ": " + path + " is not a regular file");
  }
  if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    const std::string holder = Holder(fd_);
    close(fd_);
    if (error == EWOULDBLOCK) {
      throw std::runtime_error(dir + " is in use by another shapebench" +
                               (holder.empty() ? std::string() : " (" + holder + ")") +
                               " writing there; wait for it to finish or choose another --out");
    }
    throw std::runtime_error("cannot lock " + dir + ": " + std::strerror(error));
  }
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) != 0 || pwrite(fd_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const int error = errno;
    close(fd_);
    throw std::runtime_error("cannot lock " + dir + ": " + path + ": " + std::strerror(error));
  }
}

OutputDirLock::~OutputDirLock() { close(fd_); }  // closing drops the lock

void RequireRegularFile(const std::string& path) { close(OpenRegular(path)); }

std::string ReadRegularFile(const std::string& path, std::uint64_t max_bytes) {
  const int fd = OpenRegular(path);
  std::string text;
  char buffer[65536];
  for (;;) {
    const ssize_t size = read(fd, buffer, sizeof buffer);
    if (size < 0 && errno == EINTR) continue;
    if (size < 0) {
      const int error = errno;
      close(fd);
      throw std::runtime_error(path + ": cannot read: " + std::strerror(error));
    }
    if (size == 0) break;
    text.append(buffer, static_cast<std::size_t>(size));
    if (text.size() > max_bytes) {
      close(fd);
      throw std::runtime_error(path + ": larger than " + std::to_string(max_bytes) +
                               " bytes; not a file shapebench wrote");
    }
  }
  close(fd);
  return text;
}

}  // namespace shapebench::bench
