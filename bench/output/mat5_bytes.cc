// mat5 (bench/output/mat5_bytes.h): the layout of libmatio 1.5.23's mat5.c (Mat_Create5,
// Mat_VarWrite5, WriteCellArrayField, WriteCharData, WriteData), uncompressed.
#include "bench/output/mat5_bytes.h"

#include <algorithm>

namespace shapebench::bench::mat5 {
namespace {

// The data types and array classes of the MAT 5 format.
constexpr std::uint32_t kInt8 = 1, kInt32 = 5, kUint32 = 6, kDouble = 9, kMatrix = 14, kUtf8 = 16;
constexpr std::uint32_t kCellClass = 1, kCharClass = 4, kDoubleClass = 6;

void Put32(std::uint32_t value, std::string* out) {
  const char bytes[4] = {static_cast<char>(value), static_cast<char>(value >> 8), static_cast<char>(value >> 16),
                         static_cast<char>(value >> 24)};
  out->append(bytes, 4);
}

// Zeros up to the next multiple of `unit` bytes of a `size`-byte element.
void Pad(std::size_t size, std::size_t unit, std::string* out) {
  if (size % unit != 0) out->append(unit - size % unit, '\0');
}

std::size_t Padded8(std::size_t size) { return (size + 7) / 8 * 8; }

// The array flags, dimensions (rows x cols, as libmatio: 32 bits) and name sub-elements;
// a name of at most 4 bytes (none too) in the small element format.
void PutArrayHead(std::uint32_t array_class, std::size_t rows, std::size_t cols, const std::string& name,
                  std::string* out) {
  Put32(kUint32, out);
  Put32(8, out);
  Put32(array_class, out);
  Put32(0, out);  // nzmax
  Put32(kInt32, out);
  Put32(8, out);
  Put32(static_cast<std::uint32_t>(rows), out);
  Put32(static_cast<std::uint32_t>(cols), out);
  if (name.size() <= 4) {
    Put32(kInt8 | static_cast<std::uint32_t>(name.size()) << 16, out);
    out->append(name);
    out->append(4 - name.size(), '\0');
  } else {
    Put32(kInt8, out);
    Put32(static_cast<std::uint32_t>(name.size()), out);
    out->append(name);
    Pad(name.size(), 8, out);
  }
}

// Bytes of the array flags, dimensions and name sub-elements.
std::size_t ArrayHeadBytes(const std::string& name) {
  return 16 + 16 + (name.size() <= 4 ? 8 : 8 + Padded8(name.size()));
}

}  // namespace

std::string FileHeader(const std::string& text) {
  std::string header(128, ' ');
  const std::size_t kept = std::min<std::size_t>(text.size(), 115);
  header.replace(0, kept, text, 0, kept);
  header[kept] = '\0';
  header[124] = '\0';  // version 0x0100, little-endian
  header[125] = '\x01';
  header[126] = 'I';
  header[127] = 'M';
  return header;
}

std::string DoubleColumnHead(const std::string& name, std::size_t rows) {
  std::string out;
  Put32(kMatrix, &out);
  // libmatio's sizes are 32 bits (MatFile keeps to version 5's limit).
  Put32(static_cast<std::uint32_t>(ArrayHeadBytes(name) + 8 + rows * sizeof(double)), &out);
  PutArrayHead(kDoubleClass, rows, 1, name, &out);
  Put32(kDouble, &out);
  Put32(static_cast<std::uint32_t>(rows * sizeof(double)), &out);
  return out;
}

void AppendStringColumn(const std::string& name, const std::vector<std::string_view>& values, std::string* out) {
  const std::string no_name;
  const std::size_t element_head = ArrayHeadBytes(no_name) + 8;
  std::size_t bytes = ArrayHeadBytes(name);
  for (const std::string_view value : values) bytes += 8 + element_head + Padded8(value.size());
  out->reserve(out->size() + 8 + bytes);
  Put32(kMatrix, out);
  Put32(static_cast<std::uint32_t>(bytes), out);
  PutArrayHead(kCellClass, values.size(), 1, name, out);
  for (const std::string_view value : values) {
    Put32(kMatrix, out);
    Put32(static_cast<std::uint32_t>(element_head + Padded8(value.size())), out);
    PutArrayHead(kCharClass, 1, value.size(), no_name, out);
    Put32(kUtf8, out);
    Put32(static_cast<std::uint32_t>(value.size()), out);
    out->append(value);
    Pad(value.size(), 8, out);
  }
}

}  // namespace shapebench::bench::mat5
