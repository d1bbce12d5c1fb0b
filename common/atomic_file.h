// Output files appear complete or not at all: they are written under a temporary name in
// the same directory (so the final rename is atomic) and renamed when complete.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace shapebench {

// A temporary file next to `final_path`, removed unless Commit() renames it into place.
// For writers that need a file name (gnuplot); others use WriteFileAtomically.
class TempFile {
 public:
  explicit TempFile(const std::string& final_path);  // throws std::runtime_error
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return temp_path_; }
  void Commit();  // throws std::runtime_error

 private:
  std::string final_path_;
  std::string temp_path_;
  bool committed_ = false;
};

// Calls `write` on a stream to a TempFile, then commits it. Throws std::runtime_error
// naming `path` when anything fails.
void WriteFileAtomically(const std::string& path,
                         const std::function<void(std::ostream&)>& write);

}  // namespace shapebench
