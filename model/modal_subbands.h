// A wide band fitted in sub-bands (docs/measured-data.md, step 0): the modes of a band of
// many lines (a hammer test's 12,800 lines, 24 peaks) are found sub-band by sub-band, each by
// the whole method (diagram, LSFD, refinement, missed poles) on its own lines, then the
// linear terms refitted on the whole band. Modes far apart interact weakly: a sub-band's
// residual terms take the others. One fit of the whole band needs a high order for its many
// modes and refines them all together, its work growing with lines x modes^3 a trial.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace shapebench::model {

// A band of more lines is fitted in sub-bands of about kSubBandLines lines at most.
inline constexpr int kMaxLinesPerFit = 4096;
inline constexpr int kSubBandLines = 2048;

// The sub-bands' edges as line indices, first 0 and last lines - 1: the fewest equal parts of
// at most kSubBandLines lines, each inner edge moved to the line where the sum over the FRFs
// of |H| is the least within an eighth of a part of it (between peaks, not on one).
std::vector<std::size_t> SubBandEdges(const std::vector<std::vector<std::complex<double>>>& frfs);

// Whether a sub-band's mode at `frequency_hz` lies within two lines of an inner edge: it is
// left out (the edge lies where |H| is least: such a pole fits the cut, not a peak; the
// neighbouring sub-band holds the peak it leans on).
bool NearInnerEdge(double frequency_hz, const std::vector<double>& edges_hz, double line_spacing_hz);

}  // namespace shapebench::model
