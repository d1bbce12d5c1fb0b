// Modal parameters from measured frequency response functions (docs/measured-data.md):
// the poles by the least-squares complex frequency-domain method (LSCF: a common-
// denominator polynomial in z = exp(-j w Ts), fitted by linear least squares at increasing
// orders, its roots the poles), picked from a stabilisation diagram, then the modal
// constants by least squares in the frequency domain (LSFD) with lower and upper residual
// terms. The method follows Verboven's thesis (Frequency-domain system identification for
// modal analysis, VUB 2002, ch. 5) as pyEMA (ladisk/pyEMA, MIT) applies it to FRFs.
//
// Units: an FRF is given in its measured form, (j w)^derivative_order times receptance:
// 0 receptance (displacement per excitation), 1 mobility (velocity), 2 accelerance
// (acceleration). The modal constants are those of the receptance,
//   H(w) = sum_r R_r / (w_r^2 - w^2 + 2 j zeta_r w_r w) - LR / w^2 + UR,
// R_r = 2 j w_d,r A_r with A_r the residue of the pole lambda_r = -zeta_r w_r + j w_d,r;
// a real (proportionally damped) mode has a real R_r.
#pragma once

#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "model/modal_work.h"

namespace shapebench::model {

// Receptance from an FRF of the given form at `frequency_hz` (> 0): h / (j w)^order.
std::complex<double> ToReceptance(std::complex<double> h, double frequency_hz, int derivative_order);

// IdentificationOptions::max_work's default (docs/reliability.md#limits: 1e11, about 3,000 times
// the shipped measurement's stabilisation diagram (3.2e7; its whole fit 1e8-2e8); ten copies
// of it at order 200 need 1.05e11, above it).
constexpr double kDefaultIdentificationWork = 1e11;

// The first order auto_order tries.
constexpr int kFirstAutoOrder = 8;

struct IdentificationOptions {
  // The band the poles are searched in and the modal constants fitted over, in Hz; lines
  // at 0 Hz are left out (the lower residual is singular there).
  double min_frequency_hz = 0.0;
  double max_frequency_hz = std::numeric_limits<double>::infinity();
  // The highest model order, in pole pairs (the LSCF polynomial has twice that degree);
  // orders 1..max_order are fitted. Capped by the lines in the band (an order needs more
  // lines than coefficients).
  int max_order = 30;
  // Choose the order, max_order being its cap: the diagram is built to kFirstAutoOrder,
  // then to twice that and so on, until the modes picked up to one order are those picked
  // up to the next (as many, at least one, each frequency within frequency_tolerance);
  // that next order is used (ModalIdentification::orders_compared, order_stop).
  bool auto_order = false;
  // After the fit, a mode whose removal (the rest refitted by LSFD) raises the band's fit
  // error by less than this many points (1 % of the data's norm: issue 34's measure of an
  // extra mode) is dropped, the least first, and the rest refitted
  // (RejectedMode::error_rise_percent); 0 turns it off.
  double min_error_rise_percent = 1.0;
  // A pole is stable when the previous order has one within these relative distances.
  double frequency_tolerance = 0.01;
  double damping_tolerance = 0.05;
  // A physical pole: damping ratio in (0, max_damping_ratio), frequency inside the band.
  double max_damping_ratio = 0.5;
  // A mode is a cluster of stable poles (frequencies within frequency_tolerance of its
  // mean) found at this fraction of the orders at least (and at 3 orders at least).
  double min_stable_fraction = 0.2;
  // A mode must show in the data: its term's largest magnitude in its band (frequency
  // within 2 zeta of its own, 2 lines at least) at least this fraction of the data's RMS
  // there (model/modal_refinement.h, Prominence); the least prominent below it is dropped
  // and the rest refitted, until none is.
  double min_prominence = 0.1;
  // Poles and residues refined together by nonlinear least squares on the FRFs after
  // LSFD (model/modal_refinement.h).
  bool refine = true;
  // After the refinement, poles the diagram missed are added while one lowers the squared
  // error by this fraction at least and shows in the data (AddMissedPoles), at most
  // max_added_modes of them.
  double min_error_drop = 0.1;
  int max_added_modes = 5;
  // The most work the fit may take, in multiply-adds estimated from its sizes before each
  // part runs (model/modal_work.h: the diagram, every refinement, the trials of poles the
  // diagram missed, the LSFD re-solves, in every sub-band); beyond, SolverError("WORK_LIMIT")
  // naming max_work_key, the option or key that sets it. Counted, never timed: the same
  // verdict on every host.
  double max_work = kDefaultIdentificationWork;
  std::string max_work_key = "--max-work";

  // Throws ValidationError naming the field.
  void validate() const;
};


enum class PoleStability { kNew, kFrequency, kStable };

// One physical pole of one order of the stabilisation diagram.
struct DiagramPole {
  int order = 0;  // pole pairs of the model
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  // kNew: no pole of the previous order within frequency_tolerance; kFrequency: one in
  // frequency, not in damping; kStable: both.
  PoleStability stability = PoleStability::kNew;
};

struct IdentifiedMode {
  double frequency_hz = 0.0;  // undamped natural frequency |lambda| / 2 pi
  double damping_ratio = 0.0;
  std::vector<std::complex<double>> modal_constants;  // R_r, one per FRF (receptance)
  int stable_orders = 0;  // the orders its cluster has a stable pole at
  double prominence = 0.0;  // IdentificationOptions::min_prominence's measure, after the fit
  // 0 for a mode of the diagram; for one the diagram missed (model/modal_refinement.h,
  // AddMissedPoles), the fraction of the squared error its addition removed.
  double error_drop = 0.0;
  // Its peak is narrower than a line: its damping was fitted on its own neighbourhood
  // (model/modal_local_damping.h).
  bool local_damping = false;
};

// A cluster of stable poles that PickModes found and the data did not show: its pole from
// the diagram, its prominence when it was dropped.
struct RejectedMode {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  int stable_orders = 0;
  double prominence = 0.0;
  // > 0: dropped by min_error_rise_percent, its removal raising the fit error by this many
  // points; 0: dropped for its prominence.
  double error_rise_percent = 0.0;
};

struct FrfFit {
  std::vector<std::complex<double>> synthesized;  // in the measured form, at the band's lines
  double lower_residual = 0.0;  // LR of the receptance
  double upper_residual = 0.0;  // UR
  double error_percent = 0.0;   // ||H_fit - H|| / ||H|| over the band, in %
};

struct ModalIdentification {
  std::vector<double> frequency_hz;  // the band's lines used
  int max_order = 0;                 // the highest order fitted (after the cap)
  // auto_order: the orders whose picked modes were compared, ascending, and why it
  // stopped: "settled" (the last two agree), "cap" (max_order or the lines reached),
  // "work" (the next would exceed max_work).
  std::vector<int> orders_compared;
  std::string order_stop;
  std::vector<DiagramPole> diagram;
  std::vector<IdentifiedMode> modes;  // ascending frequency
  std::vector<RejectedMode> rejected;  // in the order they were dropped
  // Whether the nonlinear refinement was kept (it lowered the error, its poles physical);
  // false: the modes are the diagram's with LSFD residues.
  bool refined = false;
  // A band of more than kMaxLinesPerFit lines is fitted in sub-bands (model/modal_subbands.h):
  // their edges in Hz, ascending, and each one's order (empty: one fit). max_order,
  // orders_compared and order_stop are then those of the sub-band of the highest order.
  std::vector<double> sub_band_edges_hz;
  std::vector<int> sub_band_orders;
  double work = 0.0;  // the multiply-adds charged to max_work
  std::vector<FrfFit> fits;           // one per FRF
  double fit_error_percent = 0.0;     // over every FRF together
};

// `frfs` are FRFs of one structure on the grid `frequency_hz` (ascending), each in the
// measured form `derivative_order`. Throws ValidationError("band", ...) when fewer than 4
// lines lie in the band, ValidationError on non-finite data.
ModalIdentification IdentifyModes(const std::vector<double>& frequency_hz,
                                  const std::vector<std::vector<std::complex<double>>>& frfs,
                                  int derivative_order, const IdentificationOptions& options);

// Throws ValidationError("frf") when `result`'s fit error or modes are not finite numbers
// (lines 1e-300 Hz apart: the LSCF basis degenerates) rather than report "-nan %", exit 0.
void RequireFinite(const ModalIdentification& result);

}  // namespace shapebench::model
