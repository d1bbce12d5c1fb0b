// MAT version 5 variables as bytes, laid out as libmatio 1.5 writes them without compression
// (Mat_CreateVer(path, header, MAT_FT_MAT5), Mat_VarWrite(..., MAT_COMPRESSION_NONE)):
// MatFile writes version 5 files from these, byte for byte the files libmatio wrote, since
// libmatio costs a dozen writes and four seeks a cell of a column of strings (6.4k
// instructions a row of results.mat). Version 7.3 (HDF5) stays libmatio's.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace shapebench::bench::mat5 {

// The 128-byte file header: `text` (at most 115 bytes kept) ended by a NUL and padded with
// spaces to 116 bytes, an 8-byte subsystem offset of spaces, version 0x0100, "IM".
std::string FileHeader(const std::string& text);

// An N x 1 double variable up to its data: what precedes the N little-endian doubles, which
// end it (8 bytes each: no padding).
std::string DoubleColumnHead(const std::string& name, std::size_t rows);

// An N x 1 cell of char row vectors (each string's bytes as UTF-8), appended whole to *out.
void AppendStringColumn(const std::string& name, const std::vector<std::string_view>& values, std::string* out);

}  // namespace shapebench::bench::mat5
