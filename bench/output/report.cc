#include "bench/output/report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iomanip>

#include "bench/output/json_number.h"
#include "common/atomic_file.h"
#include "common/csv.h"
#include "common/format.h"

namespace shapebench::bench {
std::string MetricUnit(const std::string& name) {
  const MetricInfo* info = FindMetric(name);
  return info != nullptr ? std::string(info->shown_unit()) : "";
}

namespace {

// The table, a metric's row followed by note(name) where that is not empty.
void PrintMetricRows(std::ostream& out, const Metrics& metrics,
                     const std::function<std::string(std::string_view)>& note) {
  std::size_t width = 0;
  for (const MetricInfo& info : MetricTable()) width = std::max(width, info.name.size());
  auto print = [&](const MetricInfo& info) {
    const double value = metrics.*info.field;
    out << std::left << std::setw(static_cast<int>(width) + 2) << info.name;
    if (std::isnan(value)) {
      out << "n/a\n";
    } else if (info.is_bool()) {
      const std::string where = note ? note(info.name) : "";
      out << (value != 0.0 ? "true" : "false") << (where.empty() ? "" : " (" + where + ")") << "\n";
    } else {
      out << EngineeringText(value, info.unit) << "\n";  // um, mm, ms: JSON keeps SI
    }
  };
  for (const MetricInfo& info : MetricTable()) print(info);
  // A nonlinear plant's own metrics, where defined (a linear run's table is as it was).
  for (const MetricInfo& info : NonlinearMetricTable()) {
    if (!std::isnan(metrics.*info.field)) print(info);
  }
}

}  // namespace

void PrintMetricsTable(std::ostream& out, const Metrics& metrics) { PrintMetricRows(out, metrics, nullptr); }

void PrintRunTable(std::ostream& out, const RunResult& result) {
  // A stroke alarm says where it fired (issue 32 item 15).
  PrintMetricRows(out, result.metrics, [&result](std::string_view name) {
    return name == "stroke_alarm" && result.command.stroke_alarm ? result.command.stroke_alarm_site.Text() : "";
  });
  std::size_t width = 0;
  for (const MetricInfo& info : MetricTable()) width = std::max(width, info.name.size());
  // Where in the program the largest values come from (metric_sources.h).
  for (const auto& [name, source] : SourceEntries(result.sources)) {
    if (!source->present) continue;
    // The longest name (peak_command_acceleration_source) fills the column: one space after it.
    out << std::left << std::setw(static_cast<int>(width) + 2) << name << (name.size() >= width + 2 ? " " : "")
        << SourceText(*source) << "\n";
  }
  if (std::isfinite(result.integrator_rtol_used)) {
    out << std::left << std::setw(static_cast<int>(width) + 2) << "integrator_rtol_used"
        << FormatNumber(result.integrator_rtol_used) << "\n";
  }
}

nlohmann::ordered_json MetricsJson(const Metrics& metrics) {
  nlohmann::ordered_json json = nlohmann::ordered_json::object();
  for (const MetricInfo& info : MetricTable()) {
    const std::string name(info.name);
    const double value = metrics.*info.field;
    if (info.is_bool() && std::isfinite(value)) {
      json[name] = value != 0.0;
    } else if (std::isfinite(value)) {
      json[name] = value;
    } else {
      json[name] = nullptr;
    }
  }
  for (const MetricInfo& info : NonlinearMetricTable()) {
    const double value = metrics.*info.field;
    if (std::isfinite(value)) json[std::string(info.name)] = value;  // absent where n/a
  }
  return json;
}

nlohmann::ordered_json StrokeAlarmJson(const controller::StrokeAlarmSite& site) {
  nlohmann::ordered_json json;
  json["time_s"] = JsonNumber(site.time_s);
  json["block"] = site.block >= 0 ? nlohmann::ordered_json(site.block + 1) : nullptr;
  json["line"] = site.line > 0 ? nlohmann::ordered_json(site.line) : nullptr;
  json["axis"] = site.axis >= 0 ? nlohmann::ordered_json(std::string(1, static_cast<char>('x' + site.axis))) : nullptr;
  json["position_m"] = JsonNumber(site.position_m);
  json["limit_m"] = JsonNumber(site.limit_m);
  return json;
}

std::vector<std::pair<std::string, const MetricSource*>> SourceEntries(const MetricSources& sources) {
  return {{"peak_deflection_source", &sources.peak_deflection},
          {"max_contour_error_source", &sources.max_contour_error},
          {"cruise_residual_source", &sources.cruise_residual},
          {"peak_command_acceleration_source", &sources.peak_command_acceleration}};
}

nlohmann::ordered_json SourceJson(const MetricSource& source) {
  if (!source.present) return nullptr;
  const auto site = [](const ProgramSite& at) {
    nlohmann::ordered_json json;
    json["time_s"] = JsonNumber(at.time_s);
    json["block"] = at.block;
    json["file"] = at.file.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(at.file);
    json["line"] = at.file.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(at.line);
    return json;
  };
  nlohmann::ordered_json json = site(source.at);
  json["cause"] = site(source.cause);
  return json;
}

nlohmann::ordered_json RunJson(const RunResult& result) {
  nlohmann::ordered_json json = MetricsJson(result.metrics);
  nlohmann::ordered_json modes = nlohmann::ordered_json::array();
  for (const model::PoleAmplitude& mode : result.residual_modes) {
    nlohmann::ordered_json entry;
    entry["frequency_hz"] = mode.frequency_hz;
    entry["damping_ratio"] = mode.damping_ratio;
    entry["amplitude_m"] = std::isfinite(mode.amplitude) ? nlohmann::ordered_json(mode.amplitude) : nullptr;
    modes.push_back(entry);
  }
  json["residual_modes"] = modes;
  // Only where the alarm fired (a run without one is as it was).
  if (result.command.stroke_alarm) json["stroke_alarm_source"] = StrokeAlarmJson(result.command.stroke_alarm_site);
  json["integrator_rtol_used"] =
      std::isfinite(result.integrator_rtol_used) ? nlohmann::ordered_json(result.integrator_rtol_used) : nullptr;
  for (const auto& [name, source] : SourceEntries(result.sources)) json[name] = SourceJson(*source);
  return json;
}

const std::vector<std::string>& TraceColumns() {
  static const std::vector<std::string> columns = {
      "t_s",         "command_position_m", "command_velocity_m_s", "command_accel_m_s2",
      "deflection_m", "command_x_m",       "command_y_m",          "command_z_m",
      "actual_x_m",  "actual_y_m",         "actual_z_m",           "deflection_x_m",
      "deflection_y_m", "deflection_z_m",  "block",                "planned_feed_mm_min"};
  return columns;
}

std::size_t TraceStride(std::size_t samples, long max_rows) {
  const auto limit = static_cast<std::size_t>(std::max(max_rows, 2L));
  if (samples <= limit) return 1;
  return (samples - 1 + (limit - 1) - 1) / (limit - 1);
}

std::size_t WriteTraceCsv(const std::string& path, const Trace& trace, long max_rows) {
  const std::size_t samples = trace.time_s.size();
  const std::size_t stride = TraceStride(samples, max_rows);
  WriteFileAtomically(path, [&](std::ostream& out) {
    if (stride > 1) {
      out << "# decimated: 1 in " << stride << " of " << samples
          << " samples kept (limits.max_trace_rows " << max_rows
          << "); the metrics use every sample\n";
    }
    const std::vector<std::string>& columns = TraceColumns();
    for (std::size_t c = 0; c < columns.size(); ++c) out << (c == 0 ? "" : ",") << columns[c];
    out << "\n";
    char line[1024];  // 15 numbers of at most 40 characters, a block number
    const std::size_t rows = std::min({trace.time_s.size(), trace.command_position_m.size(),
                                       trace.command_velocity_m_s.size(),
                                       trace.command_accel_m_s2.size(), trace.deflection_m.size(),
                                       trace.command_m.size(), trace.actual_m.size(),
                                       trace.deflection_axes_m.size(), trace.block.size(),
                                       trace.planned_feed_mm_min.size()});
    for (std::size_t i = 0; i < rows; i += stride) {
      const Eigen::Vector3d& c = trace.command_m[i];
      const Eigen::Vector3d& a = trace.actual_m[i];
      const Eigen::Vector3d& d = trace.deflection_axes_m[i];
      char* end = line;
      for (const double value : {trace.time_s[i], trace.command_position_m[i],
                                 trace.command_velocity_m_s[i], trace.command_accel_m_s2[i],
                                 trace.deflection_m[i], c.x(), c.y(), c.z(), a.x(), a.y(), a.z(),
                                 d.x(), d.y(), d.z()}) {
        end = AppendExactDouble(end, line + sizeof line, value);
        *end++ = ',';
      }
      end += std::snprintf(end, static_cast<std::size_t>(line + sizeof line - end), "%d,", trace.block[i]);
      end = AppendExactDouble(end, line + sizeof line, trace.planned_feed_mm_min[i]);
      *end++ = '\n';
      out.write(line, end - line);
    }
  });
  return stride;
}

}  // namespace shapebench::bench
