// SweepBands, BandsCsv, BandsSummary (bench/sweep/robust_band.h).
#include "bench/sweep/robust_band.h"

#include <algorithm>
#include <cmath>

#include "common/csv.h"
#include "common/ends_with.h"
#include "bench/output/json_number.h"
#include "bench/output/report.h"
#include "bench/scenario/metrics.h"
#include "bench/sweep/sweep_slice.h"

namespace shapebench::bench {
namespace {

// The design frequency of each series: its first defined pattern_frequency_hz, when kept
// and the band's x is a frequency; NaN otherwise.
std::vector<double> DesignPerSeries(const SweepLayout& layout, const BandSpec& spec, const std::string& results_csv,
                                    std::size_t series_count) {
  std::vector<double> design(series_count, std::numeric_limits<double>::quiet_NaN());
  const bool kept = std::find(layout.metrics.begin(), layout.metrics.end(), "pattern_frequency_hz") != layout.metrics.end();
  if (!kept || !EndsWith(spec.x, "frequency_hz")) return design;
  const Slice slice = ReadSlice(layout, results_csv, "pattern_frequency_hz", spec.x, spec.series, false);
  const std::size_t nx = slice.x.texts.size();
  for (std::size_t s = 0; s < series_count; ++s) {
    for (std::size_t i = 0; i < nx && std::isnan(design[s]); ++i) {
      if (std::isfinite(slice.z[s * nx + i])) design[s] = slice.z[s * nx + i];
    }
  }
  return design;
}

}  // namespace

std::vector<RobustBand> BandsAtOrBelow(const std::vector<double>& x, const std::vector<double>& values,
                                       double threshold, double design) {
  std::vector<RobustBand> bands;
  bool open = false;
  for (std::size_t i = 0; i < x.size() && i < values.size(); ++i) {
    const bool inside = std::isfinite(values[i]) && values[i] <= threshold;
    if (inside && !open) bands.push_back({x[i], x[i], false});
    if (inside) {
      bands.back().from = std::min(bands.back().from, x[i]);
      bands.back().to = std::max(bands.back().to, x[i]);
    }
    open = inside;
  }
  for (RobustBand& band : bands) band.contains_design = band.from <= design && design <= band.to;
  std::stable_sort(bands.begin(), bands.end(), [](const RobustBand& a, const RobustBand& b) {
    if (a.contains_design != b.contains_design) return a.contains_design;
    return a.from < b.from;
  });
  return bands;
}

std::vector<SeriesBands> SweepBands(const SweepLayout& layout, const std::string& results_csv) {
  std::vector<SeriesBands> all;
  for (const BandSpec& spec : layout.bands) {
    const Slice slice = ReadSlice(layout, results_csv, spec.metric, spec.x, spec.series, false);
    if (!slice.x.numeric) continue;  // no interval of a key of names
    const std::size_t nx = slice.x.texts.size();
    const std::vector<double> design = DesignPerSeries(layout, spec, results_csv, slice.y.texts.size());
    for (std::size_t s = 0; s < slice.y.texts.size(); ++s) {
      SeriesBands series{spec, slice.y.texts[s], design[s], {}};
      const std::vector<double> values(slice.z.begin() + static_cast<std::ptrdiff_t>(s * nx),
                                       slice.z.begin() + static_cast<std::ptrdiff_t>((s + 1) * nx));
      series.bands = BandsAtOrBelow(slice.x.numbers, values, spec.threshold, design[s]);
      all.push_back(std::move(series));
    }
  }
  return all;
}

BandTally::BandTally(const Sweep& sweep) : sweep_(sweep) {
  const auto find = [&](const std::string& key, std::size_t* axis, std::size_t* index) {
    for (std::size_t a = 0; a < sweep.axes.size(); ++a) {
      for (std::size_t k = 0; k < sweep.axes[a].keys.size(); ++k) {
        if (sweep.axes[a].keys[k].key == key) *axis = a, *index = k;
      }
    }
  };
  for (const BandSpec& band : SweepLayout::Of(sweep).bands) {
    Spec spec;
    spec.band = band;
    spec.series_axis = sweep.axes.size();
    find(band.x, &spec.x_axis, &spec.x_key);
    if (!band.series.empty()) find(band.series, &spec.series_axis, &spec.series_key);
    const std::size_t series = spec.series_axis < sweep.axes.size() ? sweep.axes[spec.series_axis].size() : 1;
    spec.values.assign(series * sweep.axes[spec.x_axis].size(), std::numeric_limits<double>::quiet_NaN());
    spec.design.assign(series, std::numeric_limits<double>::quiet_NaN());
    specs_.push_back(std::move(spec));
  }
}

void BandTally::Add(std::uint64_t point, const Metrics& metrics) {
  if (specs_.empty()) return;
  const std::vector<std::uint64_t> digits = sweep_.AxisIndices(point);
  for (Spec& spec : specs_) {
    bool in_slice = true;
    for (std::size_t a = 0; a < digits.size(); ++a) {
      if (a != spec.x_axis && a != spec.series_axis && digits[a] != 0) in_slice = false;
    }
    const MetricInfo* info = FindMetric(spec.band.metric);
    if (!in_slice || info == nullptr) continue;
    const std::size_t s = spec.series_axis < digits.size() ? digits[spec.series_axis] : 0;
    spec.values[s * sweep_.axes[spec.x_axis].size() + digits[spec.x_axis]] = metrics.*info->field;
    if (EndsWith(spec.band.x, "frequency_hz")) spec.design[s] = metrics.pattern_frequency_hz;
  }
}

std::vector<SeriesBands> BandTally::Bands() const {
  std::vector<SeriesBands> all;
  for (const Spec& spec : specs_) {
    const SweepValues& x_values = sweep_.axes[spec.x_axis].keys[spec.x_key];
    std::vector<double> x(x_values.size(), std::numeric_limits<double>::quiet_NaN());
    bool numeric = true;
    for (std::uint64_t i = 0; i < x_values.size(); ++i) numeric = numeric && ParseNumber(x_values.Text(i), &x[i]);
    if (!numeric) continue;
    for (std::size_t s = 0; s < spec.design.size(); ++s) {
      SeriesBands series{spec.band, "", spec.design[s], {}};
      if (spec.series_axis < sweep_.axes.size()) series.series_value = sweep_.axes[spec.series_axis].keys[spec.series_key].Text(s);
      const std::vector<double> values(spec.values.begin() + static_cast<std::ptrdiff_t>(s * x.size()),
                                       spec.values.begin() + static_cast<std::ptrdiff_t>((s + 1) * x.size()));
      series.bands = BandsAtOrBelow(x, values, spec.band.threshold, spec.design[s]);
      all.push_back(std::move(series));
    }
  }
  return all;
}

std::string BandsCsv(const std::vector<SeriesBands>& bands) {
  std::string csv = "metric,x,series,value,threshold,design,rank,from,to,contains_design\n";
  for (const SeriesBands& series : bands) {
    const std::string head = CsvField(series.spec.metric) + "," + CsvField(series.spec.x) + "," +
                             CsvField(series.spec.series) + "," + CsvField(series.series_value) + "," +
                             ShortestDouble(series.spec.threshold) + "," +
                             (std::isfinite(series.design) ? ShortestDouble(series.design) : "") + ",";
    if (series.bands.empty()) csv += head + ",,,\n";
    for (std::size_t r = 0; r < series.bands.size(); ++r) {
      const RobustBand& band = series.bands[r];
      csv += head + std::to_string(r + 1) + "," + ShortestDouble(band.from) + "," + ShortestDouble(band.to) + "," +
             (band.contains_design ? "1" : "0") + "\n";
    }
  }
  return csv;
}

std::string BandsJson(const std::vector<SeriesBands>& bands) {
  nlohmann::ordered_json all = nlohmann::ordered_json::array();
  for (const SeriesBands& series : bands) {
    nlohmann::ordered_json intervals = nlohmann::ordered_json::array();
    for (const RobustBand& band : series.bands) {
      intervals.push_back({{"from", band.from}, {"to", band.to}, {"contains_design", band.contains_design}});
    }
    all.push_back({{"metric", series.spec.metric},
                   {"x", series.spec.x},
                   {"series", series.spec.series},
                   {"value", series.series_value},
                   {"threshold", series.spec.threshold},
                   {"design", JsonNumber(series.design)},
                   {"intervals", intervals}});
  }
  return nlohmann::ordered_json{{"bands", all}}.dump(2) + "\n";
}

std::vector<std::string> BandsSummary(const std::vector<SeriesBands>& bands) {
  std::vector<std::string> lines;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const SeriesBands& series = bands[i];
    const BandSpec& spec = series.spec;
    if (i == 0 || spec.metric != bands[i - 1].spec.metric || spec.x != bands[i - 1].spec.x) {
      lines.push_back("robust band " + spec.metric + " <= " + ShortestDouble(spec.threshold) + " along " + spec.x +
                      ":");
    }
    std::string line = "  " + (spec.series.empty() ? spec.metric : spec.series + "=" + series.series_value) + ": ";
    if (series.bands.empty()) line += "none";
    for (std::size_t b = 0; b < series.bands.size(); ++b) {
      const RobustBand& band = series.bands[b];
      line += (b == 0 ? "" : ", ") + ShortestDouble(band.from) + " to " + ShortestDouble(band.to);
      if (band.contains_design) line += " (holds the design " + ShortestDouble(series.design) + ")";
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace shapebench::bench
