#include "bench/sim/output_view.h"

#include <algorithm>

namespace shapebench::bench {

OutputView MakeOutputView(const OutputConfig& output, const controller::MultiAxisCommand& command) {
  OutputView view;
  int axis = -1;
  switch (output.direction) {
    case OutputDirection::kX: axis = 0; break;
    case OutputDirection::kY: axis = 1; break;
    case OutputDirection::kZ: axis = 2; break;
    case OutputDirection::kMagnitude: break;
    case OutputDirection::kAuto: {
      int moving = 0;
      for (int a = 0; a < controller::kNumAxes; ++a) {
        const auto& v = command.axes[a].velocity_m_s;
        if (std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; })) {
          ++moving;
          axis = a;
        }
      }
      if (moving != 1) axis = -1;
      break;
    }
  }
  if (axis >= 0) {
    view.magnitude = false;
    view.direction(axis) = 1.0;
    view.axis = axis;
  }
  return view;
}

}  // namespace shapebench::bench
