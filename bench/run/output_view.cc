#include "bench/run/output_view.h"

#include <algorithm>

namespace shapebench::bench {

OutputView MakeOutputView(const OutputConfig& output, const controller::MultiAxisCommand& command) {
  std::array<bool, controller::kNumAxes> axis_moves{};
  for (int a = 0; a < controller::kNumAxes; ++a) {
    const auto& v = command.axes[a].velocity_m_s;
    axis_moves[a] = std::any_of(v.begin(), v.end(), [](double x) { return x != 0.0; });
  }
  return MakeOutputView(output, axis_moves);
}

OutputView MakeOutputView(const OutputConfig& output, const std::array<bool, controller::kNumAxes>& axis_moves) {
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
        if (axis_moves[a]) {
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
