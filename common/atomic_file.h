// Output files appear complete or not at all: they are written under a temporary name in
// the same directory (so the final rename is atomic) and renamed when complete.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>

namespace shapebench {

// Whether a file is on the disk when it is called complete. kSynced (the default): the
// file and then its directory are synced (fsync), so it survives a crash of the machine.
// kUnsynced (`sweep --no-sync`): only handed to the kernel; still atomic (a killed
// process leaves it complete or absent, and files appear in the same order), but a crash
// of the machine or a power cut may lose or tear it. For scratch output (CI, a quick
// look), as pg_dump's --no-sync: each sync is a flush of the disk's cache.
enum class Durability { kSynced, kUnsynced };

// fsync(2) of an open file; false (errno set) when it fails. Counted by SyncCount.
bool SyncFile(int fd);
// How many syncs this process has made through this header: tests tell a synced write
// from an unsynced one by it.
std::uint64_t SyncCount();

// A temporary file next to `final_path`, removed unless Commit() renames it into place.
// For writers that need a file name (gnuplot); others use WriteFileAtomically. Refuses a
// `final_path` that is a device, FIFO or socket (the rename would replace it).
class TempFile {
 public:
  explicit TempFile(const std::string& final_path);  // throws std::runtime_error
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return temp_path_; }
  // Renames it into place, synced before and its directory after (kSynced); throws
  // std::runtime_error.
  void Commit(Durability durability = Durability::kSynced);

 private:
  std::string final_path_;
  std::string temp_path_;
  bool committed_ = false;
};

// The mkstemp pattern of a temporary file for `final_path`: ".NAME.tmp.<pid>.XXXXXX" in the
// same directory (".tmp.<pid>.XXXXXX" when that name would be too long).
std::string TempNamePattern(const std::string& final_path);

// Removes temporary files and directories in `dir` named as TempNamePattern names them whose
// process no longer exists (left by a SIGKILL or a crash). Errors are ignored.
void RemoveStaleTempFiles(const std::string& dir);

// The directory a command's outputs go to, appearing complete or not at all. When `final_dir`
// does not exist, the files are written into a temporary sibling (".NAME.tmp.<pid>.XXXXXX",
// same parent, so the rename is atomic) renamed into place by Commit() and removed with
// its contents otherwise. When it exists, path() is `final_dir` itself (each file is then
// replaced atomically on its own; a directory already in use is not moved aside).
class StagedDirectory {
 public:
  explicit StagedDirectory(const std::string& final_dir);  // throws std::runtime_error
  ~StagedDirectory();
  StagedDirectory(const StagedDirectory&) = delete;
  StagedDirectory& operator=(const StagedDirectory&) = delete;

  const std::string& path() const { return path_; }
  // `text` (a message) with path() written as the final directory.
  std::string Shown(const std::string& text) const;
  void Commit();  // throws std::runtime_error

 private:
  std::string final_dir_;
  std::string path_;
  bool staged_ = false;
};

// The descriptor `path` names when it names one of this process's own: /dev/stdout (1),
// /dev/stderr (2), /dev/fd/N, /proc/self/fd/N; -1 for any other path. Such a path is a
// symbolic link in /dev: renamed over, it would be replaced (as root), or refused (not).
int ProcessDescriptorOf(const std::string& path);

// Calls `write` on a stream to a TempFile, then commits it. An existing device or FIFO at
// `path` (/dev/full, a pipe) is written into instead, without atomicity (a stream has
// none); a descriptor of this process (ProcessDescriptorOf: /dev/stdout) through a copy
// of it, after what std::cout holds (the report follows the lines already printed, also
// when stdout is a file). Throws std::runtime_error "cannot write PATH: CAUSE", CAUSE the errno
// text of the call that failed ("No space left on device").
void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write,
                         Durability durability = Durability::kSynced);

}  // namespace shapebench
