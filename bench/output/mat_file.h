// MAT files (MATLAB's format, which scipy.io.loadmat and Octave read too): run --out's
// trace.mat and a sweep's results.mat (docs/views.md#matlab-files). Variables are written one
// at a time, so a writer holds one column in memory, not the table. Version 5 written
// directly as libmatio writes it (bench/output/mat5_bytes.h), version 7.3 through libmatio.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "bench/run/run_result.h"
#include "common/atomic_file.h"

namespace shapebench::bench {

// One MAT file, written under a temporary name and renamed into place by Commit(). MAT
// version 5 (what every MATLAB and scipy read), or version 7.3 (HDF5) when the largest
// variable would exceed version 5's 2 GiB per variable.
class MatFile {
 public:
  MatFile(const std::string& path, std::uint64_t largest_variable_bytes);  // throws std::runtime_error
  ~MatFile();
  MatFile(const MatFile&) = delete;
  MatFile& operator=(const MatFile&) = delete;

  // An N x 1 double column; NaN stays NaN.
  void WriteColumn(const std::string& name, const std::vector<double>& values);
  // An N x 1 cell array of char row vectors.
  void WriteStrings(const std::string& name, const std::vector<std::string_view>& values);
  void Commit(Durability durability = Durability::kSynced);  // TempFile::Commit's

 private:
  void Write(const char* bytes, std::size_t size);  // version 5
  void Name(const std::string& name);  // throws when a variable has the name already

  std::string path_;
  TempFile temp_;
  void* mat_ = nullptr;         // mat_t*, version 7.3
  std::FILE* file_ = nullptr;   // version 5
  std::set<std::string> names_;
};

// A column name as a MATLAB variable name: letters, digits and '_' (every other character
// becomes '_', runs of them one), starting with a letter ("x_" prepended otherwise), at most
// 63 characters ("machine.modes[0].frequency_hz" -> "machine_modes_0_frequency_hz").
std::string MatlabName(const std::string& column);

// trace.mat: one N x 1 double variable per trace.csv column (TraceColumns(), the same rows:
// decimated with the same stride to at most `max_rows`), `block` as a double too.
void WriteTraceMat(const std::string& path, const Trace& trace, long max_rows);

// results.mat from a complete results.csv, one variable at a time (the file read once for
// all its columns while they fit 256 MB, in passes of fewer columns beyond): a column whose every non-empty field is a number becomes an N x 1 double (an empty
// field NaN), any other an N x 1 cell of strings; each variable named MatlabName(header),
// and `columns`, a cell of the header's names as written, in order.
void WriteResultsMat(const std::string& results_csv, const std::string& path,
                     Durability durability = Durability::kSynced);

}  // namespace shapebench::bench
