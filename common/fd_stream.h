// Streams on file descriptors that keep the cause of a failure. A std::ofstream or
// std::ifstream says only that it failed (and reads a failed read(2) as the end of the
// file); errno read afterwards may be anything. These keep the errno of the read(2) or
// write(2) that failed ("No space left on device", "Is a directory"), so that every I/O
// error names its file and its cause.
#pragma once

#include <istream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <vector>

namespace shapebench {

// "cannot read PATH: CAUSE" and "cannot write PATH: CAUSE", CAUSE the text of errno `error`.
std::runtime_error ReadError(const std::string& path, int error);
std::runtime_error WriteError(const std::string& path, int error);

// A buffered std::streambuf reading or writing a file descriptor it does not own.
// error() is the errno of the first read(2) or write(2) that failed (0: none); after it
// the buffer reads end of file and writes nothing. `line_buffered` writes at every '\n'
// (a terminal, as stdio does).
class FdStreamBuf : public std::streambuf {
 public:
  explicit FdStreamBuf(int fd, bool line_buffered = false);
  ~FdStreamBuf() override;  // writes what is buffered; a failure stays unreported
  FdStreamBuf(const FdStreamBuf&) = delete;
  FdStreamBuf& operator=(const FdStreamBuf&) = delete;

  int error() const { return error_; }

 protected:
  int_type underflow() override;
  int_type overflow(int_type c) override;
  std::streamsize xsputn(const char* text, std::streamsize size) override;
  int sync() override;

 private:
  bool WriteAll(const char* data, std::size_t size);
  bool WriteBuffered();

  int fd_;
  bool line_buffered_;
  int error_ = 0;
  std::vector<char> in_;
  std::vector<char> out_;
};

// A file opened for reading as a std::istream. Opening never waits (a FIFO without a
// writer reads as empty).
class InputFile {
 public:
  explicit InputFile(const std::string& path);  // throws ReadError
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  std::istream& stream() { return stream_; }
  // Throws ReadError when a read failed (the stream then looked ended).
  void ThrowIfFailed() const;

 private:
  std::string path_;
  int fd_;
  FdStreamBuf buffer_;
  std::istream stream_;
};

}  // namespace shapebench
