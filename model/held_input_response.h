// The exact response of a plant's linear part to its held inputs, tick by tick, in a form
// the nonlinear integrator can read at any instant (model/nonlinear_integrator.h): CVODE
// then integrates only the nonlinear elements' correction to it.
//
// Why: the held acceleration jumps at every tick, and a jump in the forcing restarts
// CVODE's history (BDF assumes a smooth solution). Subtracting the linear part's response
// z_p (z_p' = A_z z_p + B_z a, a held over each tick) leaves e = z - z_p with
//   e' = A_z e + sum_e column_e F_e(row_e (z_p + e), ...),
// no forcing of its own: the jumps stay in z_p, which is exact (Van Loan's exponential,
// model/exact_integrator.h), and e only sees the elements' forces, smooth between events.
//
// Inside a tick the elements read row . z_p(t) and its rate at whatever instants CVODE
// evaluates them. Those rows are Chebyshev series over the tick, in pieces short enough
// (spectral radius rho of A_z times the piece at most kMaxRhoPiece) that degree kDegree
// interpolates every exp(lambda t) to rounding: the coefficient of T_k falls like
// (rho piece / 4)^k / k!, below 1e-17 at k = 17 for rho piece = 3.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "model/linear_plant.h"

namespace shapebench::model {

class HeldInputResponse {
 public:
  static constexpr int kDegree = 16;
  static constexpr double kMaxRhoPiece = 3.0;

  // `probes`: rows over z = [x; v] (size num_states + num_inputs) read at any instant;
  // outputs: C (over x) at the `substeps` substeps of each period.
  HeldInputResponse(const LinearPlant& plant, double period_s, int substeps, const Eigen::MatrixXd& probes);

  int num_probes() const { return static_cast<int>(probes_.rows()); }
  int pieces() const { return pieces_; }

  // z_p at the start of tick 0, the input 0.
  void Reset(const Eigen::VectorXd& z0);
  // The input held over the current tick (num_inputs values).
  void SetInput(const double* accel);
  // To the start of the next tick under the held input.
  void NextTick();
  // The probes' values and (unless null) rates at `tau` seconds into the current tick
  // (0 <= tau <= period).
  void Probe(double tau, double* values, double* rates) const;
  // Every output row (C z_p) at the end of substep j (1 .. substeps) of the current tick.
  void OutputsAt(int j, double* outputs) const;
  // z_p at `tau` into the current tick (an exponential computed on the spot: rarely).
  Eigen::VectorXd StateAt(double tau) const;
  const Eigen::VectorXd& start() const { return start_; }

 private:
  // A stack of rows over (z, a) without z's columns that are 0 in every row: the products
  // run over the rest (an axis' rows read that axis' states only).
  struct Rows {
    std::vector<int> columns;  // of z
    Eigen::MatrixXd over_z;    // rows x columns.size()
    Eigen::MatrixXd over_a;    // rows x num_inputs
    Rows() = default;
    Rows(const Eigen::MatrixXd& z, const Eigen::MatrixXd& a);
    void Apply(const Eigen::VectorXd& state, const Eigen::VectorXd& accel, Eigen::VectorXd* gathered,
               double* out) const;
  };
  void UpdateSeries();

  LinearPlant plant_;
  int substeps_;
  int nz_;
  int pieces_ = 1;
  double piece_s_;
  Eigen::MatrixXd probes_;
  std::vector<Rows> series_rows_;  // per piece and probe (piece * probes + probe): b_k
  // Per distinct output row that is not 0: its value at every substep j, C_row z_p(j h / S);
  // per output row the one it is (-1: 0 throughout).
  std::vector<Rows> outputs_rows_;
  std::vector<int> output_of_row_;
  Eigen::MatrixXd tick_phi_;
  Eigen::MatrixXd tick_gamma_;
  Eigen::VectorXd start_;
  Eigen::VectorXd accel_;
  Eigen::VectorXd next_;
  Eigen::VectorXd gathered_;  // scratch
  // This tick's series, their derivatives' (per unit of the piece's [-1, 1] variable), and
  // its outputs at the substeps (per row of outputs_rows_, the substeps in a row).
  Eigen::VectorXd series_;
  Eigen::VectorXd slopes_;
  Eigen::VectorXd tick_outputs_;
};

}  // namespace shapebench::model
