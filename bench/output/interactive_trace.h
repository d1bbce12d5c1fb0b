// The interactive trace of a `run --report` page: the deflection and the commanded
// acceleration over time in dygraphs (MIT; Debian libjs-dygraphs), the library inlined from
// /usr/share/javascript/dygraphs so the page stays one file that fetches nothing: drag to
// zoom, double-click to reset, hover for the values with their units (docs/views.md).
#pragma once

#include <string>

#include "bench/run/run_result.h"

namespace shapebench::bench {

// Where the library is read from (Debian's libjs-dygraphs).
inline constexpr const char* kDygraphsDir = "/usr/share/javascript/dygraphs";

// The <style>, <div> and <script> elements of the trace (at most 20,000 samples: every
// k-th past that), each graph registered in window.shapebenchTraces; "" when the library is
// not installed (the page then keeps its static plot only).
std::string InteractiveTraceHtml(const RunResult& result);

}  // namespace shapebench::bench
