// InteractiveTraceHtml (bench/output/interactive_trace.h).
#include "bench/output/interactive_trace.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "bench/output/report.h"
#include "common/csv.h"

namespace shapebench::bench {
namespace {

// A file of the library, its source-map comment dropped (the map is not inlined: nothing
// may be fetched); "" when it cannot be read.
std::string LibraryFile(const std::string& name) {
  std::ifstream in(std::string(kDygraphsDir) + "/" + name, std::ios::binary);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  std::string content = text.str();
  const std::size_t map = content.rfind("sourceMappingURL=");
  if (map != std::string::npos) {
    const std::size_t line = content.rfind('\n', map);
    content.erase(line == std::string::npos ? 0 : line + 1);
  }
  return content;
}

// A number for JavaScript: null where it is not finite (dygraphs leaves a gap).
std::string JsNumber(double value) { return std::isfinite(value) ? ExactDouble(value) : "null"; }

// [[t, deflection um, acceleration m/s2], ...]
std::string TraceData(const Trace& trace) {
  const std::size_t samples =
      std::min({trace.time_s.size(), trace.deflection_m.size(), trace.command_accel_m_s2.size()});
  const std::size_t stride = TraceStride(samples, 20'000);
  std::string data = "[";
  for (std::size_t i = 0; i < samples; i += stride) {
    data += (i == 0 ? "[" : ",[") + ExactDouble(trace.time_s[i]) + "," + JsNumber(trace.deflection_m[i] * 1e6) +
            "," + JsNumber(trace.command_accel_m_s2[i]) + "]";
  }
  return data + "]";
}

}  // namespace

std::string InteractiveTraceHtml(const RunResult& result) {
  const std::string script = LibraryFile("dygraph.min.js");
  const std::string style = LibraryFile("dygraph.min.css");
  if (script.empty() || result.trace.time_s.empty()) return "";
  std::ostringstream html;
  html << "<style>" << style << "\n.trace{width:100%;height:420px}</style>\n"
       << "<div id=\"trace\" class=\"trace\"></div>\n"
       << "<script>" << script << "\n</script>\n"
       << "<script>\n(function () {\n"
       << "  var units = {'deflection': ' um', 'command acceleration': ' m/s2'};\n"
       << "  var g = new Dygraph(document.getElementById('trace'), " << TraceData(result.trace) << ", {\n"
       << "    labels: ['time', 'deflection', 'command acceleration'],\n"
       << "    xlabel: 'time [s]', ylabel: 'deflection [um]', y2label: 'command acceleration [m/s2]',\n"
       << "    series: {'command acceleration': {axis: 'y2'}},\n"
       << "    colors: ['#1f77b4', '#999999'], legend: 'always', labelsSeparateLines: true,\n"
       << "    axes: {x: {valueFormatter: function (t) { return 't = ' + t.toPrecision(6) + ' s'; }}},\n"
       << "    valueFormatter: function (v, opts, name) { return v.toPrecision(5) + (units[name] || ''); }\n"
       << "  });\n"
       << "  window.shapebenchTraces = (window.shapebenchTraces || []).concat([g]);\n"
       << "})();\n</script>\n";
  return html.str();
}

}  // namespace shapebench::bench
