// RunGnuplot (bench/output/gnuplot.h).
#include "bench/output/gnuplot.h"

#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/atomic_file.h"

namespace shapebench::bench {
namespace {

// A gnuplot single-quoted string: only '' is special there (no backslash escapes, no
// backquote command substitution, no macros inside single quotes); newlines would end the
// command and a NUL would cut the string short when printed, so every control character
// becomes a space.
std::string QuotedText(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) {
    if (c == '\'') {
      quoted += "''";
    } else if (static_cast<unsigned char>(c) < 0x20 || c == '\x7f') {
      quoted += ' ';
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

// SIGPIPE blocked in this thread while writing to gnuplot, so a gnuplot that dies early
// is an error we report, not the end of the process; a pending SIGPIPE is discarded.
class SigpipeBlock {
 public:
  SigpipeBlock() {
    sigemptyset(&pipe_);
    sigaddset(&pipe_, SIGPIPE);
    pthread_sigmask(SIG_BLOCK, &pipe_, &saved_);
  }
  ~SigpipeBlock() {
    sigset_t pending;
    sigpending(&pending);
    if (sigismember(&pending, SIGPIPE) == 1) {
      const timespec zero{0, 0};
      sigtimedwait(&pipe_, nullptr, &zero);
    }
    pthread_sigmask(SIG_SETMASK, &saved_, nullptr);
  }

 private:
  sigset_t pipe_;
  sigset_t saved_;
};

// The PNG signature (ISO/IEC 15948) and the whole IEND chunk: length 0,
// type "IEND", its CRC. A PNG cut short (full disk, killed writer) lacks the tail.
constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
constexpr std::array<unsigned char, 12> kPngEnd = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xae, 0x42, 0x60, 0x82};

// The N bytes at `offset` of `fd` equal `expected`; *error is pread's errno when it fails.
template <std::size_t N>
bool ReadsAs(int fd, off_t offset, const std::array<unsigned char, N>& expected, int* error) {
  std::array<unsigned char, N> bytes{};
  std::size_t done = 0;
  while (done < N) {
    const ssize_t size = pread(fd, bytes.data() + done, N - done, offset + static_cast<off_t>(done));
    if (size < 0 && errno == EINTR) continue;
    if (size < 0) *error = errno;  // right at the failing call
    if (size <= 0) return false;
    done += static_cast<std::size_t>(size);
  }
  return bytes == expected;
}

// What PngDefect reports of the open file `fd` of `size` bytes; *error is set instead
// when reading it fails.
std::string DefectOf(int fd, off_t size, int* error) {
  if (size <= 0) return "gnuplot wrote nothing";
  if (size < static_cast<off_t>(kPngSignature.size() + kPngEnd.size()) ||
      !ReadsAs(fd, 0, kPngSignature, error)) {
    return "not a PNG (no PNG signature)";
  }
  if (!ReadsAs(fd, size - static_cast<off_t>(kPngEnd.size()), kPngEnd, error)) {
    return "the PNG is truncated (no IEND chunk at its end; is the disk full?)";
  }
  return "";
}

}  // namespace

std::string PngDefect(const std::string& path) {
  const int fd = open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) return std::string("cannot read it back: ") + std::strerror(errno);
  struct stat info {};
  int error = fstat(fd, &info) == 0 ? 0 : errno;
  const std::string defect = error == 0 ? DefectOf(fd, info.st_size, &error) : "";
  close(fd);
  if (error != 0) return std::string("cannot read it back: ") + std::strerror(error);
  return defect;
}

void CommitPng(TempFile& temp, const std::string& path_png) {
  const std::string defect = PngDefect(temp.path());
  if (!defect.empty()) throw std::runtime_error("cannot write " + path_png + ": " + defect);
  temp.Commit();
}

std::string GnuplotQuoted(const std::string& text) { return QuotedText(text); }

void RunGnuplot(const std::string& path_png,
                const std::function<void(std::FILE*, const std::string&)>& script) {
  // The output path goes to gnuplot quoted; a control character in it could not.
  for (const char c : path_png) {
    if (static_cast<unsigned char>(c) < 0x20 || c == '\x7f') {
      throw std::runtime_error("cannot write " + path_png +
                               ": a control character in the path (gnuplot cannot be given it)");
    }
  }
  TempFile temp(path_png);
  int status = 0;
  {
    SigpipeBlock block;
    std::FILE* gnuplot = popen("gnuplot", "w");
    if (gnuplot == nullptr) throw std::runtime_error("cannot write " + path_png + ": cannot start gnuplot");
    script(gnuplot, temp.path());
    status = pclose(gnuplot);
  }
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    throw std::runtime_error("cannot write " + path_png + ": gnuplot failed (exit " +
                             std::to_string(code) + (code == 127 ? ", is gnuplot installed?" : "") +
                             ")");
  }
  CommitPng(temp, path_png);
}

std::string RunGnuplotSvg(const std::string& what,
                          const std::function<void(std::FILE*, const std::string&)>& script) {
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  std::string name = ((ec ? std::filesystem::path("/tmp") : dir) / "shapebench-plot-XXXXXX.svg").string();
  const int fd = mkstemps(name.data(), 4);
  if (fd < 0) throw std::runtime_error("cannot draw " + what + ": " + std::strerror(errno));
  close(fd);
  int status = 0;
  {
    SigpipeBlock block;
    std::FILE* gnuplot = popen("gnuplot", "w");
    if (gnuplot == nullptr) {
      std::remove(name.c_str());
      throw std::runtime_error("cannot draw " + what + ": cannot start gnuplot");
    }
    script(gnuplot, name);
    status = pclose(gnuplot);
  }
  std::ifstream in(name, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  std::remove(name.c_str());
  const std::string svg = text.str();
  const std::size_t start = svg.find("<svg");
  const std::size_t end = svg.rfind("</svg>");
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0 || start == std::string::npos ||
      end == std::string::npos || end < start) {
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    throw std::runtime_error("cannot draw " + what + ": gnuplot failed (exit " + std::to_string(code) +
                             (code == 127 ? ", is gnuplot installed?" : "") + ")");
  }
  return svg.substr(start, end + 6 - start);
}

}  // namespace shapebench::bench
