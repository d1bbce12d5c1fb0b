// MatFile, WriteTraceMat, WriteResultsMat (bench/output/mat_file.h).
#include "bench/output/mat_file.h"

#include <cctype>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <algorithm>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string_view>

#include <dlfcn.h>
#include <matio.h>

#include "bench/output/mat5_bytes.h"
#include "bench/output/report.h"
#include "common/csv.h"

namespace shapebench::bench {
namespace {

// Version 5 stores a variable's size in 32 bits (with its header): above this, version 7.3.
constexpr std::uint64_t kMat5VariableBytes = (std::uint64_t{1} << 31) - 4096;

mat_t* Mat(void* mat) { return static_cast<mat_t*>(mat); }

std::runtime_error MatFailure(const std::string& path, const std::string& what) {
  return std::runtime_error("cannot write " + path + ": " + what +
                            (errno != 0 ? std::string(" (") + std::strerror(errno) + ")" : std::string()));
}

// libmatio's functions, the library loaded when a file is to be version 7.3 (HDF5) and only
// then: linked, it brought HDF5 and libcurl's TLS stack (32 of the 75 shared libraries, half
// the dynamic loader's symbol lookups) into every start of every command.
struct Matio {
  decltype(&Mat_CreateVer) create_ver = nullptr;
  decltype(&Mat_Close) close = nullptr;
  decltype(&Mat_VarCreate) var_create = nullptr;
  decltype(&Mat_VarSetCell) var_set_cell = nullptr;
  decltype(&Mat_VarWrite) var_write = nullptr;
  decltype(&Mat_VarFree) var_free = nullptr;
};
Matio& Lib() {
  static Matio matio;
  return matio;
}
template <typename Function>
bool Resolve(void* library, const char* name, Function* function) {
  *function = reinterpret_cast<Function>(dlsym(library, name));
  return *function != nullptr;
}
// Loaded once (kept for the process); throws naming what is missing.
const Matio& LoadMatio(const std::string& path) {
  static const std::string failure = [] {
    void* library = dlopen(SHAPEBENCH_MATIO_SONAME, RTLD_NOW | RTLD_LOCAL);
    if (library == nullptr) return std::string(dlerror());
    Matio& m = Lib();
    if (!Resolve(library, "Mat_CreateVer", &m.create_ver) || !Resolve(library, "Mat_Close", &m.close) ||
        !Resolve(library, "Mat_VarCreate", &m.var_create) || !Resolve(library, "Mat_VarSetCell", &m.var_set_cell) ||
        !Resolve(library, "Mat_VarWrite", &m.var_write) || !Resolve(library, "Mat_VarFree", &m.var_free)) {
      return std::string(dlerror());
    }
    return std::string();
  }();
  if (!failure.empty()) {
    errno = 0;
    throw MatFailure(path, std::string("a MAT file of version 7.3 (a variable over 2 GiB) needs libmatio (") +
                               SHAPEBENCH_MATIO_SONAME + "): " + failure);
  }
  return Lib();
}

// A field of results.csv as a number: the whole text, or NaN when empty; false for text.
// What strtod reads (with no leading space): a plain decimal number goes through
// std::from_chars, which rounds the same text to the same double (both round correctly) at
// a tenth of the cost; anything else (a sign '+', hex, inf, nan, out of range) through strtod.
bool FieldNumber(std::string_view field, double* value) {
  if (field.empty()) {
    *value = std::numeric_limits<double>::quiet_NaN();
    return true;
  }
  const char* first = field.data();
  const char* last = first + field.size();
  const char lead = field.size() > 1 && field.front() == '-' ? field[1] : field.front();
  if ((lead >= '0' && lead <= '9') || lead == '.') {
    const std::from_chars_result read = std::from_chars(first, last, *value);
    if (read.ec == std::errc() && read.ptr == last) return true;
  }
  const std::string text(field);  // strtod wants a terminated string
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && !std::isspace(static_cast<unsigned char>(text.front()));
}

// results.csv opened for CsvReader (its records into one reused CsvFields: no allocation
// a field).
std::ifstream OpenResultsCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + " for results.mat");
  return in;
}

// Columns [first, first + count) of results.csv, read through once: each as numbers when
// every field is one, else as texts (back to back).
struct CsvColumn {
  bool numeric = true;
  std::vector<double> numbers;
  std::string text;               // the fields back to back
  std::vector<std::size_t> ends;  // where each ends in text
  std::vector<std::string_view> Texts() const {
    std::vector<std::string_view> out;
    out.reserve(ends.size());
    std::size_t begin = 0;
    for (const std::size_t end : ends) {
      out.push_back(std::string_view(text).substr(begin, end - begin));
      begin = end;
    }
    return out;
  }
};
// The texts of `columns` (of out, from `first` on) read again from every row: columns that
// turned to text after their first row, whose earlier fields were read as numbers only.
void ReadTurnedTexts(const std::string& path, std::size_t first, const std::vector<std::size_t>& columns,
                     std::vector<CsvColumn>* out) {
  for (const std::size_t j : columns) {
    (*out)[j].text.clear();
    (*out)[j].ends.clear();
  }
  std::ifstream in = OpenResultsCsv(path);
  CsvReader reader(in);
  CsvFields record;
  reader.Next(&record);  // the header
  while (reader.Next(&record)) {
    for (const std::size_t j : columns) {
      CsvColumn& into = (*out)[j];
      into.text.append(record[first + j]);
      into.ends.push_back(into.text.size());
    }
  }
}
std::vector<CsvColumn> ReadCsvColumns(const std::string& path, std::size_t first, std::size_t count) {
  std::vector<CsvColumn> out(count);
  std::vector<std::size_t> turned;
  std::ifstream in = OpenResultsCsv(path);
  CsvReader reader(in);
  CsvFields record;
  reader.Next(&record);  // the header
  for (std::size_t row = 0; reader.Next(&record); ++row) {
    for (std::size_t j = 0; j < count; ++j) {
      const std::string_view field = record[first + j];
      CsvColumn& into = out[j];
      double value = 0.0;
      if (into.numeric) {
        if (FieldNumber(field, &value)) {
          into.numbers.push_back(value);
          continue;
        }
        into.numeric = false;
        std::vector<double>().swap(into.numbers);
        if (row > 0) turned.push_back(j);
      }
      into.text.append(field);
      into.ends.push_back(into.text.size());
    }
  }
  if (!turned.empty()) ReadTurnedTexts(path, first, turned, &out);
  return out;
}

// How many columns a pass over results.csv holds: all of them while their text (with a
// string's overhead, about four times the file's share) fits kColumnBytes, else fewer, so
// that memory stays bounded for a sweep of millions of points while a small one is read once.
constexpr double kColumnBytes = 256.0 * 1024 * 1024;
std::size_t ColumnsPerPass(const std::string& path, std::size_t columns) {
  std::error_code error;
  const double file_bytes = static_cast<double>(std::filesystem::file_size(path, error));
  if (error || columns == 0) return 1;
  const double per_column = 4.0 * file_bytes / static_cast<double>(columns);
  return std::clamp<std::size_t>(static_cast<std::size_t>(kColumnBytes / std::max(per_column, 1.0)), 1, columns);
}

// trace.csv's column `c` (TraceColumns() order) at sample i.
double TraceValue(const Trace& trace, std::size_t c, std::size_t i) {
  switch (c) {
    case 0: return trace.time_s[i];
    case 1: return trace.command_position_m[i];
    case 2: return trace.command_velocity_m_s[i];
    case 3: return trace.command_accel_m_s2[i];
    case 4: return trace.deflection_m[i];
    case 14: return trace.block[i];
    case 15: return trace.planned_feed_mm_min[i];
    default: break;
  }
  const std::size_t axis = (c - 5) % 3;
  const Eigen::Vector3d& v = c < 8 ? trace.command_m[i] : c < 11 ? trace.actual_m[i] : trace.deflection_axes_m[i];
  return v[static_cast<Eigen::Index>(axis)];
}

// The rows trace.csv has (its columns may differ in length: the shortest).
std::size_t TraceSamples(const Trace& trace) {
  return std::min({trace.time_s.size(), trace.command_position_m.size(), trace.command_velocity_m_s.size(),
                   trace.command_accel_m_s2.size(), trace.deflection_m.size(), trace.command_m.size(),
                   trace.actual_m.size(), trace.deflection_axes_m.size(), trace.block.size(),
                   trace.planned_feed_mm_min.size()});
}

}  // namespace

MatFile::MatFile(const std::string& path, std::uint64_t largest_variable_bytes) : path_(path), temp_(path) {
  errno = 0;
  if (largest_variable_bytes > kMat5VariableBytes) {
    mat_ = LoadMatio(path_).create_ver(temp_.path().c_str(), "shapebench", MAT_FT_MAT73);
    if (mat_ == nullptr) throw MatFailure(path_, "libmatio could not create the file");
    return;
  }
  file_ = std::fopen(temp_.path().c_str(), "wb");
  if (file_ == nullptr) throw MatFailure(path_, "cannot create the file");
  const std::string header = mat5::FileHeader("shapebench");
  Write(header.data(), header.size());
}

MatFile::~MatFile() {
  if (mat_ != nullptr) Lib().close(Mat(mat_));
  if (file_ != nullptr) std::fclose(file_);
}

void MatFile::Write(const char* bytes, std::size_t size) {
  errno = 0;
  if (size > 0 && std::fwrite(bytes, 1, size, file_) != size) throw MatFailure(path_, "write failed");
}

void MatFile::Name(const std::string& name) {
  // As libmatio refuses a second variable of a name.
  errno = 0;
  if (!names_.insert(name).second) throw MatFailure(path_, "two variables named " + name);
}

void MatFile::WriteColumn(const std::string& name, const std::vector<double>& values) {
  Name(name);
  if (file_ != nullptr) {
    const std::string head = mat5::DoubleColumnHead(name, values.size());
    Write(head.data(), head.size());
    Write(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(double));
    return;
  }
  std::size_t dims[2] = {values.size(), 1};
  // matio reads the data through a non-const pointer; it does not write to it.
  matvar_t* var = Lib().var_create(name.c_str(), MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims,
                                   const_cast<double*>(values.data()), MAT_F_DONT_COPY_DATA);
  errno = 0;
  const int failed = var == nullptr ? 1 : Lib().var_write(Mat(mat_), var, MAT_COMPRESSION_NONE);
  if (var != nullptr) Lib().var_free(var);
  if (failed) throw MatFailure(path_, "libmatio failed writing variable " + name);
}

void MatFile::WriteStrings(const std::string& name, const std::vector<std::string_view>& values) {
  Name(name);
  if (file_ != nullptr) {
    std::string bytes;
    mat5::AppendStringColumn(name, values, &bytes);
    Write(bytes.data(), bytes.size());
    return;
  }
  std::size_t dims[2] = {values.size(), 1};
  matvar_t* cell = Lib().var_create(name.c_str(), MAT_C_CELL, MAT_T_CELL, 2, dims, nullptr, 0);
  if (cell == nullptr) throw MatFailure(path_, "libmatio failed creating variable " + name);
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::size_t text_dims[2] = {1, values[i].size()};
    // Copied: the cell frees its elements with it.
    matvar_t* text = Lib().var_create(nullptr, MAT_C_CHAR, MAT_T_UINT8, 2, text_dims,
                                      const_cast<char*>(values[i].data()), 0);
    Lib().var_set_cell(cell, static_cast<int>(i), text);
  }
  errno = 0;
  const int failed = Lib().var_write(Mat(mat_), cell, MAT_COMPRESSION_NONE);
  Lib().var_free(cell);
  if (failed) throw MatFailure(path_, "libmatio failed writing variable " + name);
}

void MatFile::Commit(Durability durability) {
  errno = 0;
  int failed = 0;
  if (file_ != nullptr) {
    failed = std::fclose(file_);
    file_ = nullptr;
  } else {
    failed = Lib().close(Mat(mat_));
    mat_ = nullptr;
  }
  if (failed) throw MatFailure(path_, "closing the file failed");
  temp_.Commit(durability);
}

std::string MatlabName(const std::string& column) {
  std::string name;
  for (const char c : column) {
    if (std::isalnum(static_cast<unsigned char>(c)) != 0 && static_cast<unsigned char>(c) < 128) {
      name += c;
    } else if (name.empty() || name.back() != '_') {
      name += '_';
    }
  }
  while (!name.empty() && name.back() == '_') name.pop_back();
  if (name.empty() || std::isalpha(static_cast<unsigned char>(name.front())) == 0) name = "x_" + name;
  return name.substr(0, 63);
}

void WriteTraceMat(const std::string& path, const Trace& trace, long max_rows) {
  const std::size_t samples = TraceSamples(trace);
  const std::size_t stride = TraceStride(trace.time_s.size(), max_rows);
  const std::size_t rows = samples == 0 ? 0 : (samples - 1) / stride + 1;
  MatFile mat(path, rows * sizeof(double));
  const std::vector<std::string>& columns = TraceColumns();
  std::vector<double> values;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    values.clear();
    for (std::size_t i = 0; i < samples; i += stride) values.push_back(TraceValue(trace, c, i));
    mat.WriteColumn(columns[c], values);
  }
  mat.Commit();
}

void WriteResultsMat(const std::string& results_csv, const std::string& path, Durability durability) {
  std::vector<std::string> header;
  {
    std::ifstream in(results_csv, std::ios::binary);
    CsvReader reader(in);
    if (!in || !reader.Next(&header)) throw std::runtime_error("cannot read " + results_csv + " for results.mat");
  }
  const std::size_t per_pass = ColumnsPerPass(results_csv, header.size());
  std::vector<CsvColumn> batch = ReadCsvColumns(results_csv, 0, std::min(per_pass, header.size()));
  const std::size_t rows = batch.empty() ? 0 : std::max(batch.front().numbers.size(), batch.front().ends.size());
  MatFile mat(path, rows * sizeof(double));
  for (std::size_t first = 0; first < header.size(); first += per_pass) {
    if (first > 0) batch = ReadCsvColumns(results_csv, first, std::min(per_pass, header.size() - first));
    for (std::size_t j = 0; j < batch.size(); ++j) {
      const std::string name = MatlabName(header[first + j]);
      if (batch[j].numeric) {
        mat.WriteColumn(name, batch[j].numbers);
      } else {
        mat.WriteStrings(name, batch[j].Texts());
      }
    }
  }
  mat.WriteStrings("columns", std::vector<std::string_view>(header.begin(), header.end()));
  mat.Commit(durability);
}

}  // namespace shapebench::bench
