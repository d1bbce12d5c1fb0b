// The band an identification is given when the user gives none (`identify --band auto`,
// docs/measured-data.md): the FRFs' significant peaks with an octave's margin around them.
#pragma once

#include <complex>
#include <string>
#include <vector>

namespace shapebench::model {

// Peak detection of the automatic band: a line is a peak when the sum over the FRFs of
// |H| there is the largest of the kPeakHalfWidthLines lines either side (all of them in
// the run) and at least kPeakOverMedian times that sum's median over the run. The same
// rule gave the peer's starting frequencies (tests/data/uff/real/README.md).
inline constexpr int kPeakHalfWidthLines = 10;
inline constexpr double kPeakOverMedian = 5.0;

struct AutoBand {
  double min_frequency_hz = 0.0;
  double max_frequency_hz = 0.0;
  std::vector<double> peaks_hz;  // the significant peaks, ascending
  // The run of lines the peaks were sought in: the longest stretch above 0 Hz where every
  // FRF is a finite number.
  double run_min_hz = 0.0;
  double run_max_hz = 0.0;
  std::string rule;  // how the band was chosen, in words (JSON, table)
};

// The band from the lowest peak's half to 1.5 times the highest (within the run); the
// whole run when no peak stands out. Throws ValidationError("band") when the run has
// fewer than 4 lines.
AutoBand ChooseBand(const std::vector<double>& frequency_hz, const std::vector<std::vector<std::complex<double>>>& frfs);

}  // namespace shapebench::model
