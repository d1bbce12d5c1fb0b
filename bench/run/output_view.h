// Which scalar the deflection metrics and the plot read from the 3-D outputs (`output:
// {direction: ...}`): one signed component, or the magnitude.
#pragma once

#include <array>

#include <Eigen/Dense>

#include "bench/scenario/scenario.h"
#include "controller/controller.h"

namespace shapebench::bench {

struct OutputView {
  bool magnitude = true;
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  // a unit axis when !magnitude
  int axis = -1;                                        // that axis, -1 for the magnitude

  double Of(const Eigen::Vector3d& v) const { return magnitude ? v.norm() : v.dot(direction); }
};

// `auto` picks the only axis the command moves, else the magnitude.
OutputView MakeOutputView(const OutputConfig& output, const controller::MultiAxisCommand& command);
// The same from which axes the command moves (any velocity not 0), found before.
OutputView MakeOutputView(const OutputConfig& output, const std::array<bool, controller::kNumAxes>& axis_moves);

}  // namespace shapebench::bench
