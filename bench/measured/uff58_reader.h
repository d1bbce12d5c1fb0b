// Universal File Format dataset 58 (function at nodal DOF), ASCII and binary 58b: the
// measured FRFs `shapebench identify` and the machine key `frf_file` read
// (docs/measured-data.md). The layout is the one of the UC-SDRL description of dataset 58
// and of 58b's identifier line (byte order, floating-point format, ASCII lines, bytes):
// 80-column records between "    -1" lines; records 1-5 ID lines, 6 the DOFs, 7 the data
// form, 8-11 the abscissa, ordinate numerator, denominator and z-axis characteristics,
// 12 the values (ASCII in the Fortran widths of its case, or raw bytes in 58b).
//
// Only frequency response functions (record 6 function type 4) are read; every other
// dataset 58 is refused. Other datasets (151 header, 164 units, 2411 nodes, ...) are
// skipped. A NaN or inf value is kept and listed (Uff58Record::non_finite). Errors are ConfigError "FILE:LINE:COL: record N: ..." (exit 2).
#pragma once

#include <complex>
#include <string>
#include <vector>

#include "bench/measured/uff58_units.h"

namespace shapebench::bench {

// A value of record 12 that is NaN or inf (a line the analyser did not measure): kept in
// `values` and listed here, for the identification to refuse inside its band and ignore,
// with a warning, outside (bench/measured/frf_identification.h).
struct Uff58NonFinite {
  std::size_t point = 0;  // index into frequency_hz / values
  int line = 0;
  int column = 0;  // 1-based; the first column of record 12 in 58b
  std::string text;  // as written ("nan", "inf") or "binary value N"
};

struct Uff58Record {
  int line = 0;  // the identifier line ("    58" or "    58b")
  int record6_line = 0;
  int record7_line = 0;
  int record9_line = 0;
  int record12_line = 0;
  bool binary = false;
  std::string id1;  // record 1, trimmed
  int response_node = 0;
  int response_direction = 0;  // 1, 2, 3 = +x, +y, +z; negative: the opposite sense; 0 scalar
  int reference_node = 0;
  int reference_direction = 0;
  FrfResponse response = FrfResponse::kAcceleration;
  FrfExcitation excitation = FrfExcitation::kForce;
  std::string units;  // as understood, e.g. "m/s2 per N"
  std::vector<double> frequency_hz;
  // SI (a units label's scale, e.g. g, applied), in the senses recorded (not yet flipped
  // by a negative direction).
  std::vector<std::complex<double>> values;
  std::vector<Uff58NonFinite> non_finite;  // in file order; the abscissa is always finite

  int DerivativeOrder() const { return static_cast<int>(response); }
  // The axis 0, 1, 2 of the response direction (a translation), or -1.
  int ResponseAxis() const;
  // +1 or -1: the product of the senses of the response and reference directions (0,
  // a scalar, counts +1), which turns the values into +axis response per +axis excitation.
  double DirectionSign() const;
};

struct Uff58File {
  std::string file;
  std::vector<Uff58Record> records;  // in file order
  // Writer quirks read anyway because the data proves them, "FILE:LINE:COL: record N: ..."
  // (pyuff's 58b byte count of complex doubles, half the data's).
  std::vector<std::string> warnings;
};

// Parses the bytes of a UFF file named `file` (for messages). Throws ConfigError.
Uff58File ParseUff58(const std::string& bytes, const std::string& file);

// Reads and parses `path` (at most 64 MiB, a regular file). Throws ConfigError.
Uff58File ReadUff58(const std::string& path);

}  // namespace shapebench::bench
