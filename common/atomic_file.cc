#include "common/atomic_file.h"

#include "common/fd_stream.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace shapebench {
namespace {

constexpr std::size_t kMaxTempNameBytes = 255;

std::runtime_error WriteFailure(const std::string& path, const std::string& what) {
  return std::runtime_error("cannot write " + path + ": " + what);
}

// An existing target that is not a regular file or a directory: a device (/dev/null,
// /dev/full), a FIFO (`--junit >(cat)`), a socket. Renaming over it would replace the
// device node (as root) or fail for want of rights in /dev: it is written in place.
bool IsStreamTarget(const std::string& path) {
  struct stat info {};
  return stat(path.c_str(), &info) == 0 && !S_ISREG(info.st_mode) && !S_ISDIR(info.st_mode);
}

// Closes a descriptor on every way out; Close() reports close(2)'s error (NFS, full disk).
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) close(fd_);
  }
  Descriptor(const Descriptor&) = delete;
  Descriptor& operator=(const Descriptor&) = delete;
  int get() const { return fd_; }
  int Close() {
    const int result = close(fd_);
    fd_ = -1;
    return result == 0 ? 0 : errno;
  }

 private:
  int fd_;
};

// `write` on a stream to the open file `fd`; errors name `shown` with their errno.
void WriteThrough(int fd, const std::string& shown, const std::function<void(std::ostream&)>& write) {
  Descriptor file(fd);
  int error = 0;
  {
    FdStreamBuf buffer(file.get());
    std::ostream out(&buffer);
    write(out);
    out.flush();
    error = buffer.error();
  }
  if (error != 0) throw WriteError(shown, error);
  if (const int close_error = file.Close()) throw WriteError(shown, close_error);
}

// mkstemp creates 0600; finished files get the usual 0666 & ~umask.
mode_t FileMode() {
  static const mode_t mode = [] {
    const mode_t mask = umask(0);
    umask(mask);
    return static_cast<mode_t>(0666 & ~mask);
  }();
  return mode;
}

// The PID in a temporary name this file makes (".NAME.tmp.<pid>.XXXXXX", ".tmp.<pid>.XXXXXX"),
// or 0 when `name` is not one.
pid_t TempNameOwner(const std::string& name) {
  const std::size_t marker = name.rfind(".tmp.");
  if (name.empty() || name[0] != '.' || marker == std::string::npos) return 0;
  const std::size_t digits = marker + 5;
  const std::size_t dot = name.find('.', digits);
  if (dot == std::string::npos || dot == digits || dot - digits > 9 || name.size() != dot + 7) return 0;
  for (std::size_t i = digits; i < dot; ++i) {
    if (name[i] < '0' || name[i] > '9') return 0;
  }
  for (std::size_t i = dot + 1; i < name.size(); ++i) {
    if (std::isalnum(static_cast<unsigned char>(name[i])) == 0) return 0;
  }
  return static_cast<pid_t>(std::stol(name.substr(digits, dot - digits)));
}

std::atomic<std::uint64_t> sync_count{0};

// fsync of a file or directory; false (errno set) when it fails.
bool SyncPath(const std::string& path, int flags) {
  const int fd = open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return false;
  const bool synced = SyncFile(fd);
  const int saved = errno;
  close(fd);
  errno = saved;
  return synced;
}

// create_directories, its failure as "cannot write DIR: CAUSE" (a file in the way: "Not a
// directory", "File exists").
void CreateDirectories(const std::string& dir, const std::string& shown) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (!ec && !std::filesystem::is_directory(dir, ec)) ec = std::make_error_code(std::errc::not_a_directory);
  if (ec) throw WriteFailure(shown, ec.message());
}

std::string DirectoryOf(const std::string& path) {
  const std::filesystem::path target(path);
  return target.has_parent_path() ? target.parent_path().string() : ".";
}

}  // namespace

bool SyncFile(int fd) {
  sync_count.fetch_add(1, std::memory_order_relaxed);
  return fsync(fd) == 0;
}

std::uint64_t SyncCount() { return sync_count.load(std::memory_order_relaxed); }

std::string TempNamePattern(const std::string& final_path) {
  const std::filesystem::path target(final_path);
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
  // ".NAME.tmp.<pid>.XXXXXX" says what the file was for and who writes it (so a later write
  // can tell a stale one); when that would not fit NAME_MAX (255 bytes on Linux file
  // systems), a short hidden name in the same directory (rename stays within one file system).
  const std::string pid = std::to_string(getpid());
  std::string temp_name = "." + target.filename().string() + ".tmp." + pid + ".XXXXXX";
  if (temp_name.size() > kMaxTempNameBytes) temp_name = ".tmp." + pid + ".XXXXXX";
  return (dir / temp_name).string();
}

void RemoveStaleTempFiles(const std::string& dir) {
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const pid_t owner = TempNameOwner(it->path().filename().string());
    // ESRCH only: EPERM means the process lives (under another user).
    if (owner <= 0 || kill(owner, 0) == 0 || errno != ESRCH) continue;
    std::error_code ignored;
    const auto status = it->symlink_status(ignored);
    if (std::filesystem::is_directory(status)) {
      std::filesystem::remove_all(it->path(), ignored);
    } else if (std::filesystem::is_regular_file(status)) {
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

TempFile::TempFile(const std::string& final_path) : final_path_(final_path) {
  // Left by a process killed while writing (SIGKILL runs no destructor).
  RemoveStaleTempFiles(DirectoryOf(final_path));
  const std::string pattern = TempNamePattern(final_path);
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  // A device or FIFO in its place would be replaced by the rename (WriteFileAtomically
  // writes those in place; gnuplot's PNGs are files).
  if (IsStreamTarget(final_path) || ProcessDescriptorOf(final_path) >= 0) {
    throw WriteFailure(final_path, "not a regular file (a device, FIFO, socket or standard output)");
  }
  const int fd = mkstemp(name.data());
  if (fd < 0) throw WriteError(final_path, errno);
  fchmod(fd, FileMode());
  close(fd);
  temp_path_ = name.data();
}

TempFile::~TempFile() {
  if (!committed_) std::remove(temp_path_.c_str());
}

void TempFile::Commit(Durability durability) {
  // On disk before the name says complete: a crash or full disk after the rename must not
  // leave a short file under the final name; the directory synced so the rename persists.
  const bool synced = durability == Durability::kSynced;
  if (synced && !SyncPath(temp_path_, O_RDONLY)) throw WriteError(final_path_, errno);
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) throw WriteError(final_path_, errno);
  committed_ = true;
  if (synced && !SyncPath(DirectoryOf(final_path_), O_RDONLY | O_DIRECTORY)) {
    throw WriteFailure(final_path_, std::string("syncing its directory: ") + std::strerror(errno));
  }
}

StagedDirectory::StagedDirectory(const std::string& final_dir)
    : final_dir_(final_dir), path_(final_dir) {
  std::error_code ec;
  if (std::filesystem::exists(final_dir, ec) || ec) {
    CreateDirectories(final_dir, final_dir);  // throws when it is not a directory
    return;
  }
  // A trailing slash would leave an empty file name for the sibling.
  const std::filesystem::path target = std::filesystem::path(final_dir).lexically_normal();
  const std::string name = target.filename().empty() ? target.parent_path().string() : target.string();
  const std::string parent = DirectoryOf(name);
  CreateDirectories(parent, final_dir);
  RemoveStaleTempFiles(parent);
  const std::string pattern = TempNamePattern(name);
  std::vector<char> dir(pattern.begin(), pattern.end());
  dir.push_back('\0');
  if (mkdtemp(dir.data()) == nullptr) throw WriteError(final_dir, errno);
  // mkdtemp creates 0700; a finished directory gets the usual 0777 & ~umask.
  chmod(dir.data(), FileMode() | ((FileMode() & 0444) >> 2));
  path_ = dir.data();
  final_dir_ = name;
  staged_ = true;
}

StagedDirectory::~StagedDirectory() {
  if (!staged_) return;
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string StagedDirectory::Shown(const std::string& text) const {
  if (!staged_) return text;
  std::string shown = text;
  for (std::size_t at = shown.find(path_); at != std::string::npos; at = shown.find(path_, at + final_dir_.size())) {
    shown.replace(at, path_.size(), final_dir_);
  }
  return shown;
}

void StagedDirectory::Commit() {
  if (!staged_) return;
  // rename(2) refuses a non-empty target: a directory made meanwhile by another is kept.
  if (std::rename(path_.c_str(), final_dir_.c_str()) != 0) throw WriteError(final_dir_, errno);
  staged_ = false;
  path_ = final_dir_;
  if (!SyncPath(DirectoryOf(final_dir_), O_RDONLY | O_DIRECTORY)) {
    throw WriteFailure(final_dir_, std::string("syncing its directory: ") + std::strerror(errno));
  }
}

int ProcessDescriptorOf(const std::string& path) {
  const std::string normal = std::filesystem::path(path).lexically_normal().string();
  if (normal == "/dev/stdout") return STDOUT_FILENO;
  if (normal == "/dev/stderr") return STDERR_FILENO;
  for (const char* prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    const std::string digits = normal.rfind(prefix, 0) == 0 ? normal.substr(std::strlen(prefix)) : "";
    if (!digits.empty() && digits.size() <= 6 && digits.find_first_not_of("0123456789") == std::string::npos) {
      return std::atoi(digits.c_str());
    }
  }
  return -1;
}

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         Durability durability) {
  if (const int own = ProcessDescriptorOf(path); own >= 0) {
    if (own == STDOUT_FILENO) std::cout.flush();  // its lines first, at the descriptor's offset
    const int fd = fcntl(own, F_DUPFD_CLOEXEC, 0);
    if (fd < 0) throw WriteError(path, errno);
    WriteThrough(fd, path, write);
    return;
  }
  if (IsStreamTarget(path)) {
    const int fd = open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw WriteError(path, errno);
    WriteThrough(fd, path, write);
    return;
  }
  TempFile temp(path);
  const int fd = open(temp.path().c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) throw WriteError(path, errno);
  WriteThrough(fd, path, write);  // errors name `path`, not the temporary name
  temp.Commit(durability);
}

}  // namespace shapebench
