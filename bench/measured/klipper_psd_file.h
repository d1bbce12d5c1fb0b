// Klipper's PSD files, read as its scripts/calibrate_shaper.py parse_log reads them (the
// pinned commit, bench/measured/klipper_calibrate.h):
// - lines starting with '#' before the header are skipped; the header starts "freq,";
// - `freq,psd_x,psd_y,psd_z,psd_xyz` (what TEST_RESONANCES writes, resonances_*.csv; also
//   the start of SHAPER_CALIBRATE's calibration_data_*.csv): one data set, the fit reads
//   psd_xyz (the sum; --axis picks psd_x, psd_y or psd_z);
// - any other `freq,NAME,...` header: one data set a column (the sum of the axes only),
//   up to a column `shapers:`;
// - a header with a `,shapers:` column (calibration_data_*.csv) is already normalised
//   (bench/measured/klipper_psd.h), the other files are normalised after reading;
// - later lines starting with '#' are comments; an empty field is 0 (numpy's
//   filling_values); the columns after `shapers:` (the shapers' responses) are read as
//   numbers and not used. Every field must be a finite number (Klipper would read NaN).
// Errors are ConfigErrors at FILE:LINE:COL naming the column.
#pragma once

#include <string>

#include "bench/measured/klipper_psd.h"

namespace shapebench::bench {

// Whether `text` is one of Klipper's PSD files: its first line that is neither blank nor
// a '#' comment starts with "freq,".
bool IsKlipperPsdFile(const std::string& text);

// What a file that is neither an accelerometer log nor a Klipper PSD file looks like
// (shapebench's own psd.csv, a UFF file, a modal file, a spreadsheet export), "" when it
// looks like nothing known (the log reader then names what is wrong).
std::string ForeignFileKind(const std::string& text);

KlipperSpectrum ParseKlipperPsdFile(const std::string& text, const std::string& file);

}  // namespace shapebench::bench
