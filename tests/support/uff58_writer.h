// A UFF dataset 58 writer for the tests (ASCII in each case's Fortran widths, and binary
// 58b in either byte order), written from the dataset's description, independently of the
// reader (bench/measured/uff58_reader.h); and the synthetic FRFs the tests identify.
#pragma once

#include <cmath>
#include <complex>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace shapebench::bench::testing {

struct UffFrf {
  std::vector<double> frequency_hz;
  std::vector<std::complex<double>> values;
  int function_type = 4;
  int response_node = 1;
  int response_direction = 2;
  int reference_node = 1;
  int reference_direction = 2;
  int ordinate_type = 6;  // 2, 4 real; 5, 6 complex (single, double)
  bool even = true;
  int numerator_type = 12;  // acceleration
  std::string numerator_units = "m/s2";
  int denominator_type = 13;  // excitation force
  std::string denominator_units = "N";
};

inline std::string Printed(const char* format, double value) {
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

// Records 1-11 (the identifier line excluded), each ending in '\n'.
inline std::string UffHeader(const UffFrf& frf) {
  char line[128];
  std::string text = "synthetic FRF\nNONE\nNONE\nNONE\nNONE\n";
  std::snprintf(line, sizeof line, "%5d%10d%5d%10d %-10s%10d%4d %-10s%10d%4d\n", frf.function_type, 0, 0, 0, "NONE",
                frf.response_node, frf.response_direction, "NONE", frf.reference_node, frf.reference_direction);
  text += line;
  const double df = frf.frequency_hz.size() > 1 ? frf.frequency_hz[1] - frf.frequency_hz[0] : 1.0;
  std::snprintf(line, sizeof line, "%10d%10zu%10d%13.5e%13.5e%13.5e\n", frf.ordinate_type, frf.values.size(),
                frf.even ? 1 : 0, frf.even ? frf.frequency_hz[0] : 0.0, frf.even ? df : 0.0, 0.0);
  text += line;
  auto characteristics = [&](int type, const std::string& label, const std::string& units) {
    std::snprintf(line, sizeof line, "%10d%5d%5d%5d %-20s %-20s\n", type, 0, 0, 0, label.c_str(), units.c_str());
    text += line;
  };
  characteristics(18, "Frequency", "Hz");
  characteristics(frf.numerator_type, "Response", frf.numerator_units);
  characteristics(frf.denominator_type, "Reference", frf.denominator_units);
  characteristics(0, "NONE", "NONE");
  return text;
}

// Record 12's numbers in file order: [x,] re[, im] per point.
inline std::vector<double> UffNumbers(const UffFrf& frf) {
  std::vector<double> numbers;
  const bool complex = frf.ordinate_type >= 5;
  for (std::size_t i = 0; i < frf.values.size(); ++i) {
    if (!frf.even) numbers.push_back(frf.frequency_hz[i]);
    numbers.push_back(frf.values[i].real());
    if (complex) numbers.push_back(frf.values[i].imag());
  }
  return numbers;
}

// One ASCII dataset 58, from "    -1" to "    -1".
inline std::string Uff58Ascii(const UffFrf& frf) {
  std::string text = "    -1\n    58\n" + UffHeader(frf);
  const bool single = frf.ordinate_type == 2 || frf.ordinate_type == 5;
  std::vector<const char*> formats;  // one Fortran record's fields, repeated
  if (single) {
    formats.assign(6, "%13.5e");
  } else if (frf.even) {
    formats.assign(4, "%20.12e");
  } else if (frf.ordinate_type == 4) {
    formats = {"%13.5e", "%20.12e", "%13.5e", "%20.12e"};
  } else {
    formats = {"%13.5e", "%20.12e", "%20.12e"};
  }
  const std::vector<double> numbers = UffNumbers(frf);
  for (std::size_t i = 0; i < numbers.size(); ++i) {
    text += Printed(formats[i % formats.size()], numbers[i]);
    if (i % formats.size() == formats.size() - 1 || i + 1 == numbers.size()) text += "\n";
  }
  return text + "    -1\n";
}

// One binary dataset 58b: the numbers in the record's precision (every one, the abscissa
// included), in the byte order asked for.
inline std::string Uff58Binary(const UffFrf& frf, bool big_endian) {
  const std::vector<double> numbers = UffNumbers(frf);
  const bool single = frf.ordinate_type == 2 || frf.ordinate_type == 5;
  std::string data;
  for (double number : numbers) {
    unsigned char bytes[8];
    const std::size_t size = single ? 4 : 8;
    if (single) {
      const float narrow = static_cast<float>(number);
      std::memcpy(bytes, &narrow, 4);
    } else {
      std::memcpy(bytes, &number, 8);
    }
    for (std::size_t b = 0; b < size; ++b) data += static_cast<char>(bytes[big_endian ? size - 1 - b : b]);
  }
  char identifier[128];
  std::snprintf(identifier, sizeof identifier, "%6d%c%6d%6d%12d%12zu%6d%6d%12d%12d\n", 58, 'b', big_endian ? 2 : 1, 2,
                11, data.size(), 0, 0, 0, 0);
  return "    -1\n" + std::string(identifier) + UffHeader(frf) + data + "    -1\n";
}

// The three modes of the tests: 22 Hz 2 %, 40 Hz 3 %, 41.2 Hz 1.5 % (the last two 3 %
// apart, their half-power bands overlapping), with real modal constants R_r in 1/kg.
struct SyntheticFrfMode {
  double frequency_hz;
  double damping_ratio;
  double constant;
};
inline const std::vector<SyntheticFrfMode>& SyntheticModes() {
  static const std::vector<SyntheticFrfMode> kModes = {{22.0, 0.02, 1.0 / 80.0}, {40.0, 0.03, 1.0 / 120.0},
                                                   {41.2, 0.015, -1.0 / 150.0}};
  return kModes;
}

// Receptance sum_r R_r / (w_r^2 - w^2 + 2 j zeta_r w_r w) at f.
inline std::complex<double> SyntheticReceptance(double f_hz) {
  const double w = 2.0 * M_PI * f_hz;
  std::complex<double> h = 0.0;
  for (const SyntheticFrfMode& m : SyntheticModes()) {
    const double wr = 2.0 * M_PI * m.frequency_hz;
    h += m.constant / std::complex<double>(wr * wr - w * w, 2.0 * m.damping_ratio * wr * w);
  }
  return h;
}

// The accelerance (j w)^2 x receptance on 0..100 Hz every 0.125 Hz, with complex
// Gaussian noise of `noise` x each line's magnitude (seeded), multiplied by `factor`
// (a units label's scale, a direction's sense).
inline UffFrf SyntheticAccelerance(double noise, unsigned seed, std::complex<double> factor = 1.0) {
  UffFrf frf;
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal(0.0, noise / std::sqrt(2.0));
  for (int k = 0; k <= 800; ++k) {
    const double f = 0.125 * k;
    const double w = 2.0 * M_PI * f;
    const std::complex<double> a = -w * w * SyntheticReceptance(f);
    frf.frequency_hz.push_back(f);
    frf.values.push_back(factor * (a + std::abs(a) * std::complex<double>(normal(generator), normal(generator))));
  }
  return frf;
}

}  // namespace shapebench::bench::testing
