// The modal model of FRFs that model/modal_identification.h fits once its poles are picked:
// the residues and residual terms by linear least squares for given poles (LSFD), the
// modes' check against the data (a mode must show in it), and the refinement of poles and
// residues together by nonlinear least squares on the FRFs (Ceres' Levenberg-Marquardt).
//
// Normalised units keep the problem well scaled whatever the band and the FRFs' unit:
// x = w / w_ref (w_ref the band's top line), the data divided by its RMS, and
//   D(x) = (j x)^d [sum_r a_r / (j x - mu_r) + conj(a_r) / (j x - conj(mu_r)) - bL / x^2 + bU]
// with d the FRF's derivative order (0 receptance, 1 mobility, 2 accelerance).
#pragma once

#include <complex>
#include <vector>

#include "model/modal_work.h"

namespace shapebench::model {

struct ModalModel {
  std::vector<std::complex<double>> poles;  // mu_r = lambda_r / w_ref, Im mu_r > 0
  std::vector<std::vector<double>> linear;  // per FRF: Re a_r, Im a_r for each pole, then bL, bU
};

// Mode `r`'s term of FRF `frf` at x, in the measured form.
std::complex<double> ModeTerm(const ModalModel& model, std::size_t frf, std::size_t r, double x, int d);
// The whole model of FRF `frf` at x, in the measured form.
std::complex<double> ModelValue(const ModalModel& model, std::size_t frf, double x, int d);

// LSFD: each FRF's linear terms for model->poles (columns normalised for the solve; zeros
// where the solve is not finite).
void FitLinear(const std::vector<double>& x, const std::vector<std::vector<std::complex<double>>>& data, int d,
               ModalModel* model);

// sum over FRFs and lines of |model - data|^2.
double SquaredError(const std::vector<double>& x, const std::vector<std::vector<std::complex<double>>>& data, int d,
                    const ModalModel& model);

// How far mode r shows in the data: the largest magnitude of its term over the lines of
// its band (frequency within max(2 zeta, 2 line spacings) of its own), divided by the RMS
// of the data over those lines, largest over the FRFs.
double Prominence(const std::vector<double>& x, const std::vector<std::vector<std::complex<double>>>& data, int d,
                  const ModalModel& model, std::size_t r);

// Refines poles and linear terms together from `model` by nonlinear least squares.
// Keeps the result (returns true) when it lowers the squared error and every pole stays
// physical (damping ratio in (0, max_damping_ratio), frequency within [x_lo, x_hi]);
// otherwise leaves `model` as it was. Single-threaded: the same result on every host.
bool RefineModalModel(const std::vector<double>& x, const std::vector<std::vector<std::complex<double>>>& data, int d,
                      double max_damping_ratio, double x_lo, double x_hi, ModalModel* model);

// Poles the diagram missed (two close modes in one cluster, a mode its orders did not
// stabilise): candidates are each pole split in two (at its frequency times 1 -+ max(zeta,
// 0.5 %)) and a new pole at the line of the largest residual; each is fitted (LSFD, then
// RefineModalModel) and the best kept when it lowers the squared error by `min_drop` (a
// fraction), all its poles show (Prominence >= min_prominence) and no two of them lie
// closer than two lines before the fit and one line after it (the data cannot tell such a
// pair from one mode); repeated up to
// `max_added` times. Each trial's LSFD and refinement is charged to `budget` before it runs
// (the trials are most of the work of a wide band). Returns, per pole of the result, the drop
// its addition brought (0 for the poles given).
std::vector<double> AddMissedPoles(const std::vector<double>& x,
                                   const std::vector<std::vector<std::complex<double>>>& data, int d,
                                   double max_damping_ratio, double min_prominence, double min_drop, int max_added,
                                   ModalModel* model, WorkBudget* budget);

}  // namespace shapebench::model
