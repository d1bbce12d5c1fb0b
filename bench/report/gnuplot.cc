// RunGnuplot (bench/report/gnuplot.h).
#include "bench/report/gnuplot.h"

#include <pthread.h>
#include <signal.h>
#include <sys/wait.h>

#include <filesystem>
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

}  // namespace

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
  std::error_code ec;
  if (std::filesystem::file_size(temp.path(), ec) == 0 || ec) {
    throw std::runtime_error("cannot write " + path_png + ": gnuplot wrote nothing");
  }
  temp.Commit();
}

}  // namespace shapebench::bench
