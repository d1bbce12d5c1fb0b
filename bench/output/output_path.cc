#include "bench/output/output_path.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "common/atomic_file.h"
#include "common/shown_text.h"

namespace shapebench::bench {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void Fail(const std::string& option, const std::string& path, const std::string& cause) {
  throw std::runtime_error(option + " " + ClippedForMessage(path) + ": cannot write there: " + cause);
}

// A newline or another control character in an output path is a slip (a pasted line, an
// unquoted variable): refused before anything is written rather than made into a file name.
void RequirePrintable(const std::string& option, const std::string& path) {
  for (const char c : path) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) Fail(option, path, "the path holds a control character (a newline?)");
  }
}

// Creates and removes a temporary directory in `dir`; the errno text on failure, else "".
std::string ProbeDirectory(const fs::path& dir) {
  std::string name = (dir / ".shapebench-probe-XXXXXX").string();
  std::vector<char> buffer(name.begin(), name.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr) return std::strerror(errno);
  rmdir(buffer.data());
  return "";
}

// The nearest ancestor of `path` (itself included) that exists; `path` when none is found.
fs::path NearestExisting(const fs::path& path) {
  fs::path current = path;
  std::error_code ec;
  while (!current.empty()) {
    if (fs::exists(fs::symlink_status(current, ec)) && !ec) return current;
    const fs::path parent = current.parent_path();
    if (parent == current) break;
    current = parent;
  }
  return fs::path(".");  // a relative path's ancestors end in the working directory
}

}  // namespace

void RequireWritableOutputDir(const std::string& option, const std::string& path) {
  if (path.empty()) Fail(option, path, "empty path");
  RequirePrintable(option, path);
  // As given (relative stays relative), so that messages show the user's own path.
  fs::path target = fs::path(path).lexically_normal();
  if (target.filename().empty() && target.has_parent_path()) target = target.parent_path();  // "out/"
  const fs::path existing = NearestExisting(target);
  std::error_code ec;
  const fs::file_status status = fs::status(existing, ec);
  if (ec) Fail(option, path, existing.string() + ": " + ec.message());
  if (!fs::is_directory(status)) {
    Fail(option, path,
         existing == target ? "it exists and is not a directory"
                            : existing.string() + " is not a directory");
  }
  const std::string cause = ProbeDirectory(existing);
  if (!cause.empty()) Fail(option, path, (existing == target ? "" : existing.string() + ": ") + cause);
}

void RequireWritableOutputFile(const std::string& option, const std::string& path) {
  if (path.empty()) Fail(option, path, "empty path");
  RequirePrintable(option, path);
  // Standard output (or another descriptor of this process) is written through a copy of
  // the descriptor (common/atomic_file.h): open for writing is all it needs.
  if (const int own = ProcessDescriptorOf(path); own >= 0) {
    const int flags = fcntl(own, F_GETFL);
    if (flags < 0) Fail(option, path, std::strerror(errno));
    if ((flags & O_ACCMODE) == O_RDONLY) Fail(option, path, "the descriptor is open for reading only");
    return;
  }
  const fs::path target(path);
  std::error_code ec;
  const fs::file_status target_status = fs::status(target, ec);
  if (fs::is_directory(target_status)) Fail(option, path, "it is a directory");
  // A device or FIFO (/dev/stdout, `--report >(cat)`) is written in place, not renamed
  // over (common/atomic_file.h): its own write permission counts, not its directory's
  // (/dev is not writable but by root).
  if (!ec && fs::exists(target_status) && !fs::is_regular_file(target_status)) {
    if (access(path.c_str(), W_OK) != 0) Fail(option, path, std::strerror(errno));
    return;
  }
  const fs::path parent = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const fs::file_status status = fs::status(parent, ec);
  if (ec || !fs::exists(status)) {
    Fail(option, path, parent.string() + ": " + (ec ? ec.message() : std::strerror(ENOENT)));
  }
  if (!fs::is_directory(status)) Fail(option, path, parent.string() + " is not a directory");
  const std::string cause = ProbeDirectory(parent);
  if (!cause.empty()) Fail(option, path, parent.string() + ": " + cause);
}

}  // namespace shapebench::bench
