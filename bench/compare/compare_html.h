// `compare --report FILE.html` of two scenarios (bench/output/html_report.h's page).
#pragma once

#include "bench/compare/compare_runs.h"
#include "bench/output/html_report.h"

namespace shapebench::bench {

// Both sides' labels, every metric side by side in engineering units with its change,
// the gates' PASS/FAIL, the overlaid deflection plot and both effective scenarios.
HtmlReport CompareHtmlReport(const ScenarioComparison& comparison);

}  // namespace shapebench::bench
