#include "common/atomic_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace shapebench {
namespace {

constexpr std::size_t kMaxTempNameBytes = 255;

std::runtime_error WriteError(const std::string& path, const std::string& what) {
  return std::runtime_error("cannot write " + path + ": " + what);
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

}  // namespace

TempFile::TempFile(const std::string& final_path) : final_path_(final_path) {
  const std::filesystem::path target(final_path);
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
  // ".NAME.tmp.XXXXXX" says what the file was for; when that would not fit NAME_MAX (255
  // bytes on Linux file systems), a short hidden name in the same directory (rename stays
  // within one file system).
  std::string temp_name = "." + target.filename().string() + ".tmp.XXXXXX";
  if (temp_name.size() > kMaxTempNameBytes) temp_name = ".tmp." + std::to_string(getpid()) + ".XXXXXX";
  std::string pattern = (dir / temp_name).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = mkstemp(name.data());
  if (fd < 0) throw WriteError(final_path, std::strerror(errno));
  fchmod(fd, FileMode());
  close(fd);
  temp_path_ = name.data();
}

TempFile::~TempFile() {
  if (!committed_) std::remove(temp_path_.c_str());
}

void TempFile::Commit() {
  if (std::rename(temp_path_.c_str(), final_path_.c_str()) != 0) {
    throw WriteError(final_path_, std::strerror(errno));
  }
  committed_ = true;
}

void WriteFileAtomically(const std::string& path,
                         const std::function<void(std::ostream&)>& write) {
  TempFile temp(path);
  {
    std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
    if (!out) throw WriteError(path, "cannot open " + temp.path());
    write(out);
    out.flush();
    if (!out) throw WriteError(path, "write failed");
  }
  temp.Commit();
}

}  // namespace shapebench
