// The design report; see the header.
#include "bench/output/design_report.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "bench/output/gnuplot.h"
#include "bench/output/json_number.h"
#include "common/atomic_file.h"
#include "common/format.h"

namespace shapebench::bench {
namespace {

using controller::DesignBand;
using controller::Impulse;

// The shortest text of a number that reads back to the same double, for the YAML fragment.
std::string Exact(double value) {
  char text[40];
  for (int digits = 15; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    if (std::strtod(text, nullptr) == value) break;
  }
  return text;
}

std::string FormName(DesignForm form) { return form == DesignForm::kImpulses ? "impulses" : "profile_table"; }

std::string DesignPercent(double fraction) { return FormatNumber(fraction * 100.0, 4) + "%"; }

double MeanTime(const controller::DesignResult& r) {
  double mean = 0.0;
  for (std::size_t k = 0; k < r.coefficients.size(); ++k) mean += r.coefficients[k] * k * r.grid_s;
  return mean;
}

void PrintPattern(std::ostream& out, const DesignReport& report) {
  const std::vector<Impulse> impulses = DesignImpulses(report.result);
  out << "\npattern (" << impulses.size() << " non-zero of " << report.result.coefficients.size()
      << " grid points; time_s amplitude)\n";
  for (const Impulse& i : impulses) out << "  " << FormatNumber(i.time_s, 8) << "  " << FormatNumber(i.amplitude, 8) << "\n";
}

void PrintRegistry(std::ostream& out, const DesignReport& report) {
  out << "\nthe registry and the patent's methods against the same specification (each designed at every "
         "band's centre, convolved; ranked by duration)\n";
  out << "  method        duration_s    vs design     added_s     worst V per band           meets\n";
  for (std::size_t i = 0; i < report.registry.size(); ++i) {
    const controller::ShaperAgainstSpec& s = report.registry[i];
    const double added = i < report.registry_added_time_s.size() ? report.registry_added_time_s[i] : NAN;
    std::string worst;
    for (double v : s.worst_v) worst += (worst.empty() ? "" : ", ") + DesignPercent(v);
    char line[200];
    std::snprintf(line, sizeof line, "  %-12s  %-12s  %-12s  %-10s  %-25s  %s\n", s.method.c_str(),
                  FormatNumber(s.duration_s, 6).c_str(),
                  ((s.duration_s >= report.result.duration_s ? "+" : "") +
                   FormatNumber(s.duration_s - report.result.duration_s, 4))
                      .c_str(),
                  FormatNumber(added, 4).c_str(), worst.c_str(), s.meets ? "yes" : "no");
    out << line;
  }
}

void PrintValidation(std::ostream& out, const DesignReport& report) {
  out << "\n--validate: the bench's own runs, one mode at a time across each band (residual shaped / unshaped)\n";
  out << "  mode  worst residual ratio  at_hz        at_damping  worst peak_ratio  runs\n";
  for (std::size_t b = 0; b < report.validation.size(); ++b) {
    const BandValidation& v = report.validation[b];
    char line[200];
    std::snprintf(line, sizeof line, "  %-4d  %-20s  %-11s  %-10s  %-16s  %d\n", report.modes[b],
                  DesignPercent(v.worst_residual_ratio).c_str(), FormatNumber(v.worst_at_hz, 6).c_str(),
                  FormatNumber(v.worst_at_damping, 4).c_str(), FormatNumber(v.worst_peak_ratio, 6).c_str(), v.runs);
    out << line;
  }
}

}  // namespace

std::vector<Impulse> DesignImpulses(const controller::DesignResult& result) {
  std::vector<Impulse> impulses;
  const std::size_t n = result.coefficients.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (result.coefficients[k] != 0.0 || k + 1 == n) {
      impulses.push_back({static_cast<double>(k) * result.grid_s, result.coefficients[k]});
    }
  }
  return impulses;
}

void PrintDesignReport(std::ostream& out, const DesignReport& report) {
  const controller::DesignResult& r = report.result;
  out << "design (" << report.file << ")\n";
  out << "  form            " << FormName(report.form) << " on a " << FormatNumber(r.grid_s) << " s grid"
      << (report.form == DesignForm::kProfileTable ? " (controller.period_s)" : "") << "\n";
  out << "  duration_s      " << FormatNumber(r.duration_s) << " s (" << r.coefficients.size() << " grid points)\n";
  out << "  mean_time_s     " << FormatNumber(MeanTime(r)) << " s (the secondary objective: least)\n";
  out << "  tolerance       " << DesignPercent(report.spec.tolerance) << " over every band";
  if (report.spec.derivatives > 0) out << ", " << report.spec.derivatives << " derivative(s) zero at each centre";
  out << "\n  guaranteed_v    " << DesignPercent(r.guaranteed_v) << " anywhere in the bands (polygon of "
      << controller::kPolygonSides << " sides: V / cos(pi/" << controller::kPolygonSides << "); sampling margin "
      << DesignPercent(report.spec.margin) << ")\n";
  out << "  motion added    " << FormatNumber(report.added_motion_time_s) << " s (the scenario's move or program, "
      << "over no shaping)\n";
  out << "  lp_solves       " << r.lp_solves << " (COIN-OR CLP, dual simplex)\n";
  out << "\nbands (axes " << report.axes << ")\n";
  out << "  mode  frequency_hz  band_hz              damping_ratio      worst_v\n";
  for (std::size_t b = 0; b < report.spec.bands.size(); ++b) {
    const DesignBand& band = report.spec.bands[b];
    char line[200];
    std::snprintf(line, sizeof line, "  %-4d  %-12s  %-19s  %-17s  %s\n", report.modes[b],
                  FormatNumber(report.mode_frequency_hz[b], 6).c_str(),
                  (FormatNumber(band.frequency_lo_hz, 6) + ".." + FormatNumber(band.frequency_hi_hz, 6)).c_str(),
                  (band.damping_hi > band.damping_lo
                       ? FormatNumber(band.damping_lo, 4) + ".." + FormatNumber(band.damping_hi, 4)
                       : FormatNumber(band.damping_lo, 4))
                      .c_str(),
                  DesignPercent(r.worst_v[b]).c_str());
    out << line;
  }
  PrintPattern(out, report);
  if (!report.registry.empty()) PrintRegistry(out, report);
  if (!report.validation.empty()) PrintValidation(out, report);
  if (report.table_too_long()) {
    out << "\nnote: the table has " << r.coefficients.size() << " coefficients, more than the scenario's "
        << "controller.post_interp.max_table_length (" << report.max_table_length
        << "): raise max_table_length, or take the impulses form (--form impulses; --out writes "
           "design_impulses.yaml)\n";
  }
  out << "\nscenario fragment" << " (--out writes it as design.yaml)\n" << DesignFragment(report, report.form);
}

nlohmann::ordered_json DesignJson(const DesignReport& report) {
  const controller::DesignResult& r = report.result;
  nlohmann::ordered_json json;
  json["file"] = report.file;
  json["form"] = FormName(report.form);
  json["grid_s"] = JsonNumber(r.grid_s);
  json["duration_s"] = JsonNumber(r.duration_s);
  json["mean_time_s"] = JsonNumber(MeanTime(r));
  if (report.form == DesignForm::kProfileTable) {
    json["coefficients"] = r.coefficients;
  } else {
    json["impulses"] = nlohmann::ordered_json::array();
    for (const Impulse& i : DesignImpulses(r)) json["impulses"].push_back({{"time_s", i.time_s}, {"amplitude", i.amplitude}});
  }
  json["tolerance"] = report.spec.tolerance;
  json["margin"] = report.spec.margin;
  json["polygon_sides"] = controller::kPolygonSides;
  json["guaranteed_v"] = JsonNumber(r.guaranteed_v);
  json["derivatives"] = report.spec.derivatives;
  json["bands"] = nlohmann::ordered_json::array();
  for (std::size_t b = 0; b < report.spec.bands.size(); ++b) {
    const DesignBand& band = report.spec.bands[b];
    json["bands"].push_back({{"mode", report.modes[b]},
                             {"frequency_lo_hz", band.frequency_lo_hz},
                             {"frequency_hi_hz", band.frequency_hi_hz},
                             {"damping_lo", band.damping_lo},
                             {"damping_hi", band.damping_hi},
                             {"worst_v", JsonNumber(r.worst_v[b])}});
  }
  json["lp_solves"] = r.lp_solves;
  json["secondary_objective"] = r.secondary_objective;
  json["table_too_long"] = report.table_too_long();
  json["added_motion_time_s"] = JsonNumber(report.added_motion_time_s);
  json["registry"] = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < report.registry.size(); ++i) {
    const controller::ShaperAgainstSpec& s = report.registry[i];
    const double added = i < report.registry_added_time_s.size() ? report.registry_added_time_s[i] : NAN;
    json["registry"].push_back({{"method", s.method},
                                {"duration_s", s.duration_s},
                                {"added_motion_time_s", JsonNumber(added)},
                                {"meets", s.meets},
                                {"worst_v", s.worst_v}});
  }
  if (!report.validation.empty()) {
    json["validation"] = nlohmann::ordered_json::array();
    for (std::size_t b = 0; b < report.validation.size(); ++b) {
      const BandValidation& v = report.validation[b];
      json["validation"].push_back({{"mode", report.modes[b]},
                                   {"worst_residual_ratio", JsonNumber(v.worst_residual_ratio)},
                                   {"at_hz", v.worst_at_hz},
                                   {"at_damping", v.worst_at_damping},
                                   {"worst_peak_ratio", JsonNumber(v.worst_peak_ratio)},
                                   {"runs", v.runs}});
    }
  }
  return json;
}

std::string DesignFragment(const DesignReport& report, DesignForm form) {
  std::ostringstream out;
  out << "# shapebench design " << report.file << ": " << FormatNumber(report.result.duration_s) << " s, V <= "
      << DesignPercent(report.spec.tolerance) << " over every band (docs/design.md)\n";
  out << "controller:\n";
  if (form == DesignForm::kImpulses) {
    out << "  pattern:\n    method: custom\n    impulses:\n";
    for (const Impulse& i : DesignImpulses(report.result)) {
      out << "      - {time_s: " << Exact(i.time_s) << ", amplitude: " << Exact(i.amplitude) << "}\n";
    }
    return out.str();
  }
  out << "  pattern: {method: none}\n  post_interp:\n    type: profile_table\n    table: [";
  for (std::size_t k = 0; k < report.result.coefficients.size(); ++k) {
    out << (k == 0 ? "" : ", ") << Exact(report.result.coefficients[k]);
  }
  out << "]\n";
  return out.str();
}

}  // namespace shapebench::bench
