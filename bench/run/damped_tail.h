// The settling tail of a linear plant in closed form: from its state at the end of the
// residual window (input 0 from there on), when the deflection in the view leaves the 5%
// band for good (model/band_crossing.h), instead of simulating until it has stayed inside
// for a period. Also the envelopes of every output row, which bound what the tail's samples
// could still add to the peak and contour metrics (the master then knows they add nothing).
#pragma once

#include <array>
#include <memory>

#include <Eigen/Dense>

#include "bench/run/output_view.h"
#include "model/band_crossing.h"
#include "model/free_response.h"
#include "model/linear_plant.h"
#include "model/multi_axis_machine.h"

namespace shapebench::bench {

class DampedTail {
 public:
  // `plant`: a machine plant (MachinePlant::plant, kNumOutputRows rows); `view` an axis.
  DampedTail(const model::LinearPlant& plant, const OutputView& view);

  // The free response from state x; false when x does not split into modes
  // (ModalDecomposition::WellSplit): the master simulates the tail then.
  bool Split(const Eigen::VectorXd& x);

  // After Split: the view's deflection t after the state, its last band crossing
  // (LastBandCrossing), and per output row the envelope at t = 0 (a bound for all t >= 0).
  double ViewAt(double t) const { return rows_[view_row_].At(t); }
  double LastCrossing(double band) const { return model::LastBandCrossing(rows_[view_row_], band); }
  double Envelope(int row) const { return rows_[row].Envelope(0.0); }

 private:
  std::shared_ptr<const model::ModalDecomposition> modes_;
  Eigen::MatrixXcd cv_;  // C V, every output row
  int view_row_ = 0;
  std::array<model::FreeTerms, model::kNumOutputRows> rows_;
};

}  // namespace shapebench::bench
