// The robust band of a sweep: for each series of a line plot and each ratio metric the
// sweep checks or plots, the intervals of the plot's x key where the metric stays at or
// below a threshold (the check's max, else the sweep's `band_threshold:`, else the
// metric's 5% level), the one holding the pattern's design frequency named first. Read
// from results.csv (so `merge` gives the same), written as bands.csv and drawn on the plot.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "bench/sweep/sweep_layout.h"

namespace shapebench::bench {

struct RobustBand {
  double from = 0.0;  // the x values of the first and last point of the run at or below
  double to = 0.0;
  bool contains_design = false;
};

struct SeriesBands {
  BandSpec spec;
  std::string series_value;  // results.csv's text of the series key ("" without series)
  // The pattern's design frequency (pattern_frequency_hz of the series' points, when kept
  // and x is a frequency), NaN when unknown.
  double design = std::numeric_limits<double>::quiet_NaN();
  std::vector<RobustBand> bands;
};

// The runs of consecutive points (in x's order) whose value is at or below `threshold`
// (an undefined value ends a run), as [lowest x, highest x]; the run containing
// `design` first, the others in ascending x.
std::vector<RobustBand> BandsAtOrBelow(const std::vector<double>& x, const std::vector<double>& values,
                                       double threshold, double design);

// Every band of `layout.bands` from `results_csv`, each series of each spec in turn.
// Throws std::runtime_error when results.csv cannot be read.
std::vector<SeriesBands> SweepBands(const SweepLayout& layout, const std::string& results_csv);

// The robust bands as `check` runs a sweep's points (no results.csv): each band's metric
// at the points of its slice (the other axes at their first value), then the same bands
// SweepBands finds in results.csv.
class BandTally {
 public:
  explicit BandTally(const Sweep& sweep);
  // A point that ran (a failed one leaves its values undefined).
  void Add(std::uint64_t point, const Metrics& metrics);
  std::vector<SeriesBands> Bands() const;

 private:
  struct Spec {
    BandSpec band;
    std::size_t x_axis = 0;
    std::size_t x_key = 0;  // within the axis (a zip group)
    std::size_t series_axis = 0;  // == axes.size() without series
    std::size_t series_key = 0;
    std::vector<double> values;  // [series * nx + x]
    std::vector<double> design;  // per series
  };
  const Sweep& sweep_;
  std::vector<Spec> specs_;
};

// bands.csv: metric,x,series,value,threshold,design,rank,from,to,contains_design; one row
// per band (rank 1 the first named), a series with none one row with empty from and to.
std::string BandsCsv(const std::vector<SeriesBands>& bands);

// bands.json: {"bands": [{metric, x, series, value, threshold, design (null when
// unknown), "intervals": [{from, to, contains_design}, ...] in bands.csv's order}, ...]}.
std::string BandsJson(const std::vector<SeriesBands>& bands);

// "residual_ratio <= 0.05: method=zvd 23.1 to 27.4 (holds the design 25); ..." per spec.
std::vector<std::string> BandsSummary(const std::vector<SeriesBands>& bands);

}  // namespace shapebench::bench
