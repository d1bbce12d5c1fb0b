// CheckReportsJson (bench/output/report.h): `check --json`.
#include <cmath>

#include "bench/output/json_number.h"
#include "bench/output/report.h"

namespace shapebench::bench {
namespace {

nlohmann::ordered_json ResultJson(const CheckResult& result) {
  nlohmann::ordered_json json;
  json["metric"] = result.metric;
  if (!result.point.empty()) json["point"] = result.point;
  json["value"] = JsonNumber(result.value);
  json["bound"] = result.bound;
  json["passed"] = result.passed;
  json["message"] = result.message;
  if (!result.statistic.empty()) {
    json["statistic"] = {{"name", result.statistic},
                         {"samples", result.samples},
                         {"passing", result.passing},
                         {"interval_95", {JsonNumber(result.interval_low), JsonNumber(result.interval_high)}}};
  }
  if (result.banded()) {
    json["band"] = {{"key", result.band_key},
                    {"from", JsonNumber(result.band_from)},
                    {"to", JsonNumber(result.band_to)},
                    {"worst_value", JsonNumber(result.value)},
                    {"worst_at", JsonNumber(result.worst_at)},
                    {"runs", result.band_runs},
                    {"text", BandText(result)}};
  }
  return json;
}

}  // namespace

nlohmann::ordered_json CheckReportsJson(const std::vector<ScenarioCheckReport>& reports) {
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const ScenarioCheckReport& report : reports) {
    nlohmann::ordered_json file;
    file["file"] = report.file;
    file["name"] = report.name;
    file["error"] = report.error.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(report.error);
    file["results"] = nlohmann::ordered_json::array();
    for (const CheckResult& result : report.results) file["results"].push_back(ResultJson(result));
    file["point_errors"] = nlohmann::ordered_json::array();
    for (const auto& [point, message] : report.point_errors) {
      file["point_errors"].push_back({{"point", point}, {"message", message}});
    }
    files.push_back(file);
  }
  return {{"files", files}};
}

}  // namespace shapebench::bench
