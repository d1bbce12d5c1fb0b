#include "common/fd_stream.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace shapebench {
namespace {

constexpr std::size_t kBufferBytes = 64 * 1024;

int OpenForReading(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw ReadError(path, errno);
  const int flags = fcntl(fd, F_GETFL);
  if (flags >= 0) fcntl(fd, F_SETFL, flags & ~O_NONBLOCK);
  return fd;
}

}  // namespace

std::runtime_error ReadError(const std::string& path, int error) {
  return std::runtime_error("cannot read " + path + ": " + std::strerror(error));
}

std::runtime_error WriteError(const std::string& path, int error) {
  return std::runtime_error("cannot write " + path + ": " + std::strerror(error));
}

FdStreamBuf::FdStreamBuf(int fd, bool line_buffered) : fd_(fd), line_buffered_(line_buffered) {}

FdStreamBuf::~FdStreamBuf() { WriteBuffered(); }

FdStreamBuf::int_type FdStreamBuf::underflow() {
  if (gptr() < egptr()) return traits_type::to_int_type(*gptr());
  if (error_ != 0) return traits_type::eof();
  in_.resize(kBufferBytes);
  for (;;) {
    const ssize_t size = read(fd_, in_.data(), in_.size());
    if (size < 0 && errno == EINTR) continue;
    if (size < 0) {
      error_ = errno;  // right at the failing call
      return traits_type::eof();
    }
    if (size == 0) return traits_type::eof();
    setg(in_.data(), in_.data(), in_.data() + size);
    return traits_type::to_int_type(*gptr());
  }
}

bool FdStreamBuf::WriteAll(const char* data, std::size_t size) {
  while (error_ == 0 && size > 0) {
    const ssize_t written = write(fd_, data, size);
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) {
      error_ = errno;  // right at the failing call
      break;
    }
    data += written;
    size -= static_cast<std::size_t>(written);
  }
  return error_ == 0;
}

bool FdStreamBuf::WriteBuffered() {
  if (line_buffered_) {  // no put area: the line so far is in out_
    const bool written = WriteAll(out_.data(), out_.size());
    out_.clear();
    return written;
  }
  if (pbase() == nullptr) return error_ == 0;
  const bool written = WriteAll(pbase(), static_cast<std::size_t>(pptr() - pbase()));
  setp(out_.data(), out_.data() + out_.size());
  return written;
}

FdStreamBuf::int_type FdStreamBuf::overflow(int_type c) {
  if (traits_type::eq_int_type(c, traits_type::eof())) return WriteBuffered() ? traits_type::not_eof(c) : c;
  const char ch = traits_type::to_char_type(c);
  if (line_buffered_) {
    // Every character comes here (no put area), so a line is written as it ends.
    out_.push_back(ch);
    if ((ch == '\n' || out_.size() >= kBufferBytes) && !WriteBuffered()) return traits_type::eof();
    return c;
  }
  if (out_.empty()) {
    out_.resize(kBufferBytes);
    setp(out_.data(), out_.data() + out_.size());
  } else if (!WriteBuffered()) {
    return traits_type::eof();
  }
  *pptr() = ch;
  pbump(1);
  return c;
}

std::streamsize FdStreamBuf::xsputn(const char* text, std::streamsize size) {
  if (!line_buffered_) return std::streambuf::xsputn(text, size);
  out_.insert(out_.end(), text, text + size);
  const bool line_ends = std::memchr(text, '\n', static_cast<std::size_t>(size)) != nullptr;
  if ((line_ends || out_.size() >= kBufferBytes) && !WriteBuffered()) return 0;
  return size;
}

int FdStreamBuf::sync() { return WriteBuffered() ? 0 : -1; }

InputFile::InputFile(const std::string& path)
    : path_(path), fd_(OpenForReading(path)), buffer_(fd_), stream_(&buffer_) {}

InputFile::~InputFile() { close(fd_); }

void InputFile::ThrowIfFailed() const {
  if (buffer_.error() != 0) throw ReadError(path_, buffer_.error());
}

}  // namespace shapebench
