// Accelerometer logs: the CSV Klipper's ACCELEROMETER_MEASURE and TEST_RESONANCES write
// (raw_data_*.csv) and most other loggers can:
//   #time,accel_x,accel_y,accel_z
//   0.000000,12.5,-3.1,980.2
// time in s, accelerations in mm/s^2. The first non-blank line is the header: it starts
// with '#', names each of the four columns once, in any order, and nothing else. Later
// lines starting with '#' are comments; blank lines are skipped; a line is one sample
// with as many fields as the header, each a finite decimal number, time strictly
// increasing. Every error is a ConfigError at FILE:LINE:COL naming the column (or
// "header"), the CLI's exit 2.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace shapebench::bench {

// The three acceleration axes, as the log's columns and --axis name them.
inline constexpr std::array<const char*, 3> kAccelColumns = {"accel_x", "accel_y", "accel_z"};

struct AccelLog {
  std::string file;  // as given: errors name it
  std::vector<double> time_s;
  std::array<std::vector<double>, 3> accel_mm_s2;  // x, y, z; one value per sample
  std::vector<int> line;  // the line of each sample (1-based)
  // Where the last sample's time field starts (1-based): errors about the whole record
  // (too short, too slowly sampled) point there.
  int last_time_column = 1;
};

// Parses `text` as the log of `file` (the name errors show). Throws ConfigError.
AccelLog ParseAccelLog(const std::string& text, const std::string& file);

// Reads and parses `path`; a file that cannot be read is a ConfigError without position.
AccelLog ReadAccelLog(const std::string& path);

}  // namespace shapebench::bench
