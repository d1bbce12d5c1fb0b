// Sensitivity curves of shapers (see the header for the file's keys and the band).
#include "bench/sensitivity/sensitivity.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>

#include "common/atomic_file.h"
#include "bench/config/config_document.h"
#include "bench/scenario/controller_reader.h"
#include "bench/output/gnuplot.h"
#include "bench/config/node_reader.h"
#include "common/format.h"
#include "common/interval_search.h"
#include "common/validation_error.h"
#include "controller/profile_table.h"
#include "controller/shaper_registry.h"

namespace shapebench::bench {
namespace {

using controller::Impulse;

// Values this close above the level count as inside (EI touches V at r = 1).
bool Inside(double value, double level) { return value <= level * (1.0 + 1e-9); }

// How a label shows a PatternConfig key a shaper reads (ShaperEntry::parameters); keys
// not listed (custom's impulses) are left out.
std::string ParameterText(const std::string& key, const controller::PatternConfig& p) {
  if (key == "vibration_tolerance") return " V=" + FormatNumber(p.vibration_tolerance);
  if (key == "k1") return " k1=" + FormatNumber(p.k1);
  if (key == "t1_s") return " t1=" + FormatNumber(p.t1_s);
  if (key == "impulse_count") return " n=" + std::to_string(p.impulse_count);
  if (key == "impulse_spacing_periods") return " s=" + FormatNumber(p.impulse_spacing_periods);
  return "";
}

std::string AutoLabel(const controller::PatternConfig& p) {
  const controller::ShaperEntry& entry = controller::FindShaper(p.method);
  std::string label = entry.kind == controller::ShaperKind::kPatentStep ? "method " + p.method : p.method;
  std::string frequencies;
  for (const double f : p.DesignFrequencies()) frequencies += (frequencies.empty() ? "" : "+") + FormatNumber(f);
  label += " " + frequencies + " Hz";
  if (p.design_damping_ratio > 0.0) label += " zeta_d=" + FormatNumber(p.design_damping_ratio);
  if (!p.damping_ratios.empty()) {
    std::string ratios;
    for (const double z : p.damping_ratios) ratios += (ratios.empty() ? "" : "+") + FormatNumber(z);
    label += " zeta_d=" + ratios;
  }
  for (const std::string& key : entry.parameters) label += ParameterText(key, p);
  return label;
}

// A label safe in a CSV header and a gnuplot title: no commas, quotes or newlines.
std::string Sanitized(const std::string& text) {
  std::string out;
  for (const char c : text) out += (c == ',' || c == '"' || c == '\n' || c == '\r') ? ' ' : c;
  return out;
}

// The band's edge between `inside_r` and `outside_r`, bisected to 1e-12.
double Edge(const std::function<double(double)>& residual, double level, double inside_r,
            double outside_r) {
  return BisectEdge([&](double r) { return Inside(residual(r), level); }, inside_r, outside_r, 1e-12);
}

// Walks from `start` (inside) in `direction` (+1, -1) in steps of `step` until the residual
// leaves the level or `limit` is reached. A local maximum of the samples is refined by
// golden-section (to 1e-9 in r) over the two steps around it: a hump that rises above the
// level between two samples ends the band there, one that only touches it (EI at its
// design point; within 1e-6 relative) does not. Returns the edge; *open when `limit` was reached inside.
double WalkToEdge(const std::function<double(double)>& residual, double level, double start,
                  double direction, double step, double limit, bool* open) {
  double r = start;
  double v = residual(r);
  // Ratios stay positive (the behind sample of a walk starting near 0 is the start).
  const double first_behind = r - direction * step;
  double v_behind = first_behind > 0.0 ? residual(first_behind) : v;
  for (;;) {
    const double next = direction > 0 ? std::min(limit, r + step) : std::max(limit, r - step);
    if (next == r) {
      *open = true;
      return r;
    }
    const double v_next = residual(next);
    if (!Inside(v_next, level)) return Edge(residual, level, r, next);
    if (v >= v_behind && v >= v_next) {
      const double behind = std::max(0.5 * std::min(r, next), r - direction * step);
      const IntervalPoint hump = GoldenSection(residual, std::min(behind, next),
                                               std::max(behind, next), Extreme::kMaximum, 1e-9);
      // A hump behind the start is the other walk's.
      // A peak within 1e-6 relative of the level touches it: EI realized on a grid
      // (period_s) overshoots its tolerance by ~1e-8 relative at its design hump.
      if (hump.value > level * (1.0 + 1e-6) && direction * (hump.x - start) >= 0.0) {
        // From the last sample before the hump (inside: the walk passed it).
        return Edge(residual, level, direction * (hump.x - r) >= 0.0 ? r : behind, hump.x);
      }
    }
    v_behind = v;
    v = v_next;
    r = next;
  }
}

}  // namespace

double ResidualPercent(const std::vector<Impulse>& impulses, double design_hz, double ratio,
                       double plant_damping_ratio) {
  return 100.0 * controller::ResidualVibration(impulses, ratio * design_hz, plant_damping_ratio);
}

Band BandAroundDesign(const std::function<double(double)>& residual, double level, double from,
                      double to) {
  constexpr double kStep = 1e-3;
  constexpr double kLowest = 1e-9;
  Band band;
  double start = 1.0;
  if (!Inside(residual(start), level)) {
    // The sample nearest the design point that is inside, on a grid of kStep or finer.
    // At most a million samples (a huge ratio range must neither overflow the count nor
    // take forever).
    const long samples =
        std::max(2L, static_cast<long>(std::min(1e6, std::ceil((to - from) / kStep))) + 1);
    double best = -1.0;
    for (long k = 0; k < samples; ++k) {
      const double r = from + (to - from) * static_cast<double>(k) / static_cast<double>(samples - 1);
      if (Inside(residual(r), level) && (best < 0.0 || std::abs(r - 1.0) < std::abs(best - 1.0))) best = r;
    }
    if (best < 0.0) return band;
    start = best;
  }
  band.found = true;
  // Downward to r -> 0, upward to 10 x max(1, to).
  band.low = WalkToEdge(residual, level, start, -1.0, kStep, kLowest, &band.open_low);
  band.high = WalkToEdge(residual, level, start, +1.0, kStep, 10.0 * std::max(1.0, to), &band.open_high);
  return band;
}

namespace {

// `shapers:`: each a pattern as in controller.pattern with an optional label, validated;
// labels sanitized and made unique.
std::vector<SensitivityShaper> ReadShapers(const ConfigDocument& document, const NodeReader& top) {
  std::vector<SensitivityShaper> shapers_read;
  const auto shapers = top.Child("shapers");
  if (!shapers) {
    throw top.Error("missing 'shapers': a list of pattern mappings as in controller.pattern, e.g. "
                    "shapers: [{method: zv, frequency_hz: 25}, {method: zvd, frequency_hz: 25}]");
  }
  for (const NodeReader& entry : shapers->Elements()) {
    SensitivityShaper shaper;
    shaper.pattern = ReadPattern(entry, {"label"});
    entry.Read("label", &shaper.label);
    // A curve has no machine: `machine` is refused; a frequency not given stays 25 Hz.
    for (const char* key : {"frequency_hz", "frequencies_hz", "design_damping_ratio"}) {
      const auto value = entry.Child(key);
      if (value && value->IsScalar() && value->node().Scalar() == "machine") {
        throw value->Error("a sensitivity curve has no machine to take it from; give a number");
      }
    }
    try {
      shaper.pattern.validate();
    } catch (const ValidationError& error) {
      throw document.ErrorAtPath(entry.path() + "." + error.field(), error.message());
    }
    if (shaper.label.empty()) shaper.label = AutoLabel(shaper.pattern);
    shapers_read.push_back(shaper);
  }
  if (shapers_read.empty()) throw shapers->Error("expected at least one shaper");
  // Two shapers with the same label are told apart by their position.
  std::set<std::string> seen;
  for (std::size_t i = 0; i < shapers_read.size(); ++i) {
    std::string& label = shapers_read[i].label;
    label = Sanitized(label);
    if (!seen.insert(label).second) label += " #" + std::to_string(i + 1);
  }
  return shapers_read;
}

// `ratio: {from, to, steps}` into the spec.
void ReadRatioRange(const NodeReader& ratio, SensitivitySpec* spec) {
  ratio.ExpectMap({"from", "to", "steps"});
  ratio.Read("from", &spec->ratio_from);
  ratio.Read("to", &spec->ratio_to);
  ratio.Read("steps", &spec->ratio_steps);
  auto fail = [&](const std::string& key, const std::string& message) {
    const auto child = ratio.Child(key);
    return (child ? *child : ratio).Error(message);
  };
  if (!(spec->ratio_from > 0.0)) throw fail("from", "must be > 0 (got " + FormatNumber(spec->ratio_from) + ")");
  if (!(spec->ratio_to > spec->ratio_from)) {
    throw fail("to", "must be above from (" + FormatNumber(spec->ratio_from) + "; got " + FormatNumber(spec->ratio_to) + ")");
  }
  if (spec->ratio_steps < 2 || spec->ratio_steps > 1000001) {
    throw fail("steps", "must be in [2, 1000001] (got " + std::to_string(spec->ratio_steps) + ")");
  }
}

}  // namespace

SensitivitySpec LoadSensitivity(const std::string& path, const std::vector<Override>& overrides) {
  ConfigDocument document(ConfigDocument::ParseFile(path), path);
  for (std::size_t i = 0; i < overrides.size(); ++i) {
    document.ApplyOverride(overrides[i], static_cast<int>(i) + 1);
  }
  NodeReader top(document, document.root(), "");
  top.ExpectMap({"shapers", "ratio", "damping_ratios", "level", "period_s"});
  SensitivitySpec spec;
  spec.source_file = path;
  spec.shapers = ReadShapers(document, top);
  if (const auto ratio = top.Child("ratio")) ReadRatioRange(*ratio, &spec);
  if (const auto damping = top.Child("damping_ratios")) {
    spec.damping_ratios.clear();
    for (const NodeReader& value : damping->Elements()) {
      const double z = value.AsNumber();
      if (!(z >= 0.0 && z < 1.0)) throw value.Error("must be in [0, 1) (got " + FormatNumber(z) + ")");
      spec.damping_ratios.push_back(z);
    }
    if (spec.damping_ratios.empty()) throw damping->Error("expected at least one damping ratio, e.g. [0.0]");
  }
  if (const auto level = top.Child("level")) {
    spec.level = level->AsNumber();
    if (!(spec.level > 0.0 && spec.level < 1.0)) {
      throw level->Error("must be in (0, 1), a fraction of the unshaped vibration (got " +
                         FormatNumber(spec.level) + ")");
    }
  }
  if (const auto period = top.Child("period_s")) {
    const double period_s = period->AsNumber();
    if (!(period_s > 0.0 && period_s <= 1.0)) {
      throw period->Error("must be in (0, 1] s (got " + FormatNumber(period_s) + ")");
    }
    spec.period_s = period_s;
  }
  return spec;
}

SensitivityResult ComputeSensitivity(const SensitivitySpec& spec) {
  SensitivityResult result;
  result.level = spec.level;
  result.period_s = spec.period_s;
  for (long k = 0; k < spec.ratio_steps; ++k) {
    result.ratio.push_back(spec.ratio_from + (spec.ratio_to - spec.ratio_from) * static_cast<double>(k) /
                                                 static_cast<double>(spec.ratio_steps - 1));
  }
  for (std::size_t s = 0; s < spec.shapers.size(); ++s) {
    const controller::PatternConfig& pattern = spec.shapers[s].pattern;
    const double design_hz = pattern.DesignFrequencies().front();
    std::vector<std::pair<bool, std::vector<Impulse>>> variants;
    const std::vector<Impulse> impulses = controller::ShaperImpulses(pattern);
    variants.emplace_back(false, impulses);
    if (spec.period_s) {
      const std::vector<double> table = controller::ProfileTableFromImpulses(
          impulses, *spec.period_s, controller::ShaperGridDesign(pattern));
      variants.emplace_back(true, controller::TableImpulses(table, *spec.period_s));
    }
    for (const double zeta : spec.damping_ratios) {
      for (const auto& [realized, sequence] : variants) {
        SensitivityCurve curve;
        curve.label = spec.shapers[s].label;
        curve.shaper = s;
        curve.damping_ratio = zeta;
        curve.realized = realized;
        const std::vector<Impulse>& seq = sequence;
        auto residual = [&](double r) { return ResidualPercent(seq, design_hz, r, zeta) / 100.0; };
        for (const double r : result.ratio) curve.residual_percent.push_back(100.0 * residual(r));
        curve.at_design_percent = 100.0 * residual(1.0);
        curve.band_5 = BandAroundDesign(residual, 0.05, spec.ratio_from, spec.ratio_to);
        curve.band_level = BandAroundDesign(residual, spec.level, spec.ratio_from, spec.ratio_to);
        result.curves.push_back(curve);
      }
    }
  }
  return result;
}

std::string CurveName(const SensitivityCurve& curve, const SensitivityResult& result) {
  std::string name = curve.label + " zeta=" + FormatNumber(curve.damping_ratio);
  if (curve.realized && result.period_s) name += " table " + FormatNumber(*result.period_s) + " s";
  return name;
}

namespace {

std::string BandText(const Band& band) {
  if (!band.found) return "none";
  char text[96];
  std::snprintf(text, sizeof text, "%.5f [%s%.5f, %.5f%s]", band.width(), band.open_low ? "<" : "",
                band.low, band.high, band.open_high ? "+" : "");
  return text;
}

}  // namespace

void PrintSensitivityTable(std::ostream& out, const SensitivityResult& result) {
  std::size_t width = 6;
  for (const SensitivityCurve& c : result.curves) width = std::max(width, c.label.size());
  const bool two_levels = std::abs(result.level - 0.05) > 1e-12;
  out << "residual vibration vs plant frequency / design frequency (" << FormatNumber(result.ratio.front())
      << " to " << FormatNumber(result.ratio.back()) << ", " << result.ratio.size()
      << " points), % of an unshaped step's\n"
      << "band: width of the interval around ratio 1 where V <= the level [low, high]\n\n";
  char line[512];
  std::snprintf(line, sizeof line, "%-*s  %-10s  %-14s  %-10s  %-36s%s\n", static_cast<int>(width),
                "shaper", "plant zeta", "grid", "V(1) %", "5% band width [low, high]",
                two_levels ? (FormatNumber(result.level * 100.0) + "% band width [low, high]").c_str() : "");
  out << line;
  for (const SensitivityCurve& c : result.curves) {
    const std::string grid = c.realized && result.period_s ? "table " + FormatNumber(*result.period_s) + " s" : "exact";
    std::snprintf(line, sizeof line, "%-*s  %-10s  %-14s  %-10.4g  %-36s%s\n", static_cast<int>(width),
                  c.label.c_str(), FormatNumber(c.damping_ratio).c_str(), grid.c_str(), c.at_design_percent,
                  BandText(c.band_5).c_str(), two_levels ? BandText(c.band_level).c_str() : "");
    out << line;
  }
  out << "(< / +: the band reaches r -> 0 / the search's upper end, 10 x the range's)\n";
}

void WriteSensitivityCsv(const std::string& path, const SensitivityResult& result) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "ratio";
    for (const SensitivityCurve& c : result.curves) out << "," << CurveName(c, result);
    out << "\n";
    char value[40];
    for (std::size_t k = 0; k < result.ratio.size(); ++k) {
      std::snprintf(value, sizeof value, "%.10g", result.ratio[k]);
      out << value;
      for (const SensitivityCurve& c : result.curves) {
        std::snprintf(value, sizeof value, "%.10g", c.residual_percent[k]);
        out << "," << value;
      }
      out << "\n";
    }
  });
}

namespace {

// The plot's terms for the curves. Curves that coincide (zv and method 1, an exact curve
// and its realized table) must all stay visible: each shaper and damping its colour, dash
// type and point type, its realized table thinner, dashed, with open points; markers every
// N samples, each curve's at its own phase so coinciding curves show every marker.
void WriteCurveTerms(std::FILE* gnuplot, const SensitivityResult& result) {
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  static const int kDash[] = {1, 4, 5, 6};  // a period prime to the colours' and points'
  std::size_t shapers = 0;
  for (const SensitivityCurve& c : result.curves) shapers += c.realized ? 0 : 1;
  static const int kFilled[] = {7, 5, 9, 11, 13, 15};
  static const int kOpen[] = {6, 4, 8, 10, 12, 14};
  const std::size_t n = result.ratio.size();
  const std::size_t every = std::max<std::size_t>(1, n / 10);
  const std::size_t count = std::max<std::size_t>(1, result.curves.size());
  std::size_t shaper = 0;
  for (std::size_t i = 0; i < result.curves.size(); ++i) {
    const SensitivityCurve& c = result.curves[i];
    if (!c.realized && i > 0) ++shaper;
    const char* colour = kColours[shaper % 10];
    const int dash = c.realized ? 2 : kDash[shaper % 4];
    const int point = c.realized ? kOpen[shaper % 6] : kFilled[shaper % 6];
    // The first drawn, underneath, the widest: a curve drawn over it leaves its edges.
    const double width =
        c.realized ? 1.0 : 3.0 - 1.5 * static_cast<double>(shaper) / static_cast<double>(std::max<std::size_t>(1, shapers - 1));
    const std::size_t phase = (i * every / count) % every;
    std::fprintf(gnuplot,
                 "$data using 1:%zu with lines lw %g dt %d lc rgb '%s' notitle, \\\n     "
                 "$data every %zu::%zu using 1:%zu with points pt %d ps 1.1 lc rgb '%s' notitle, \\\n     "
                 "NaN with linespoints lw %g dt %d pt %d ps 1.1 lc rgb '%s' title %s, \\\n     ",
                 i + 2, width, dash, colour, every, phase, i + 2, point, colour, width, dash, point, colour,
                 GnuplotQuoted(CurveName(c, result)).c_str());
  }
}

}  // namespace

void WriteSensitivityPlot(const std::string& path_png, const SensitivityResult& result,
                          const std::string& title) {
  RunGnuplot(path_png, [&](std::FILE* gnuplot, const std::string& output_path) {
    // The legend below the plot, two columns: the bottom margin grows with its rows.
    const std::size_t entries = result.curves.size() + (std::abs(result.level - 0.05) > 1e-12 ? 2 : 1);
    const std::size_t rows = (entries + 1) / 2;
    std::fprintf(gnuplot, "set terminal pngcairo size 1000,%zu noenhanced font 'sans,10'\n",
                 560 + 16 * rows);
    std::fprintf(gnuplot, "set encoding utf8\n");
    std::fprintf(gnuplot, "set output %s\n", GnuplotQuoted(output_path).c_str());
    std::fprintf(gnuplot, "set title %s\n", GnuplotQuoted(title).c_str());
    std::fprintf(gnuplot, "set xlabel 'plant natural frequency / design frequency [-]'\n");
    std::fprintf(gnuplot, "set ylabel 'residual vibration [%% of unshaped]'\n");
    std::fprintf(gnuplot, "set grid\nset bmargin %zu\n", rows + 5);
    std::fprintf(gnuplot, "set key at screen 0.5, screen 0.01 center bottom horizontal maxcols 2 box\n");
    std::fprintf(gnuplot, "set xrange [%.17g:%.17g]\nset yrange [0:*]\n", result.ratio.front(),
                 result.ratio.back());
    std::fprintf(gnuplot, "$data << EOD\n");
    for (std::size_t k = 0; k < result.ratio.size(); ++k) {
      std::fprintf(gnuplot, "%.10g", result.ratio[k]);
      for (const SensitivityCurve& c : result.curves) std::fprintf(gnuplot, " %.10g", c.residual_percent[k]);
      std::fprintf(gnuplot, "\n");
    }
    std::fprintf(gnuplot, "EOD\nplot ");
    WriteCurveTerms(gnuplot, result);
    std::fprintf(gnuplot, "5 with lines lw 1.5 dt 3 lc rgb '#cc0000' title '5%% level'");
    if (std::abs(result.level - 0.05) > 1e-12) {
      const std::string name = FormatNumber(result.level * 100.0) + "% level";
      std::fprintf(gnuplot, ", \\\n     %.17g with lines lw 1.5 dt 4 lc rgb '#444444' title %s",
                   result.level * 100.0, GnuplotQuoted(name).c_str());
    }
    std::fprintf(gnuplot, "\nunset output\nquit\n");
  });
}

}  // namespace shapebench::bench
