// The free response of a LinearPlant's states x (LinearPlant::A) with the input at 0, in
// complex modes: A = V diag(lambda) V^{-1}, x(t) = sum_i v_i z_i e^{lambda_i t}, z = V^{-1} x(0).
// It covers every plant form: modal (proportional damping), lumped masses with dashpots
// (non-proportional damping: complex mode shapes) and servo loops (real poles). An output
// row c then vibrates as sum_i c v_i z_i e^{lambda_i t}: a pole pair's part is
// 2 Re(c v_i z_i e^{lambda_i t}), of amplitude (envelope at t = 0) |2 c v_i z_i|; a real
// pole's is at most |c v_i z_i|. For one mode of the modal form this is the envelope
// |gain| sqrt(q^2 + ((q' + zeta w q) / w_d)^2) (tests/model/free_response_test.cc).
#pragma once

#include <complex>
#include <memory>
#include <vector>

#include <Eigen/Dense>

namespace shapebench::model {

// One pole of the free response (a pair counted once, by its member of positive imaginary
// part), or several equal ones together (the same mode on two axes): their amplitudes are
// then not split arbitrarily between them.
struct FreePole {
  double frequency_hz = 0.0;   // |lambda| / 2 pi (a real pole: its rate / 2 pi)
  double damping_ratio = 0.0;  // -Re(lambda) / |lambda| (a real pole: 1)
  bool oscillatory = false;    // a complex pair
  std::vector<int> members;    // indices into the eigenvalues (the pair's upper member)
};

// The residual amplitude of a pole pair, its part y(t) = Re(p e^{lambda t}) of the free
// response (lambda = -sigma + i w_d, damping ratio zeta): the envelope |p| (its amplitude at
// t = 0), capped at ResidualCap(zeta) times the largest |y(t)|, t >= 0 (PairPeak):
// CappedResidual(|p|, PairPeak, ResidualCap(zeta)).
// - zeta <= 1/2: every free response reaches |p| e^{-pi zeta / sqrt(1 - zeta^2)} within half
//   a damped period (|cos| = 1 somewhere in it), so |p| <= ResidualCap(zeta) PairPeak for
//   every state: the cap never acts, the amplitude is |p| bit for bit, and shaped /
//   unshaped stays the shaper's V(w, zeta).
// - zeta -> 1: |p| grows as 1 / w_d while y stays bounded (a near-critical mode cannot
//   complete a cycle); the cap falls to 1 + 1e-9 and the amplitude tends to the response's
//   largest |value|.
// Always PairPeak <= amplitude <= ResidualCap(zeta) PairPeak <= 6.13 PairPeak (6.13: the cap
// at zeta = 1/2, its largest).

// The largest |y(t)| over t >= 0 of y(t) = e^{-sigma t} (y0 cos(w_d t) + (y0' + sigma y0)
// sin(w_d t) / w_d) (sigma >= 0, w_d > 0): |y0|, or |y| at the first stationary point after
// t = 0 if larger (later ones are smaller by e^{-sigma pi / w_d} each). Finite as w_d -> 0
// (sin(w_d t) / w_d stays bounded).
double PairPeak(double y0, double y0dot, double sigma, double wd);
// e^{pi z / sqrt(1 - z^2)}, z = min(zeta, 1 - zeta): the decay over half a damped period up to
// zeta = 1/2, mirrored above it so that it falls to 1 at zeta = 1; times 1 + 1e-9 (rounding).
double ResidualCap(double damping_ratio);
// Whether CappedResidual can return less than the envelope at this damping: not up to
// zeta = 1/2 (above; bit for bit: ModalDecomposition.CapNeverActsUpToHalfDamping), where a
// caller may take the envelope without PairPeak's atan2, exp, cos and sin.
inline bool ResidualCapCanAct(double damping_ratio) { return !(damping_ratio <= 0.5); }
// min(envelope, cap x peak); NaN for a NaN envelope.
inline double CappedResidual(double envelope, double peak, double cap) {
  return envelope > cap * peak ? cap * peak : envelope;
}

// The amplitude of one pole's part of the free response, in the output's unit.
struct PoleAmplitude {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double amplitude = 0.0;
  bool capped = false;  // a pair whose envelope exceeded the cap (near-critical damping)
};

class ModalDecomposition {
 public:
  explicit ModalDecomposition(const Eigen::MatrixXd& a);

  int num_states() const { return static_cast<int>(lambda_.size()); }
  const Eigen::VectorXcd& eigenvalues() const { return lambda_; }
  const Eigen::MatrixXcd& eigenvectors() const { return v_; }
  const std::vector<FreePole>& poles() const { return poles_; }  // ascending frequency

  // Modal coordinates z = V^{-1} x of a state (or of the columns of a matrix).
  Eigen::VectorXcd Coordinates(const Eigen::VectorXd& x) const { return v_inv_ * x; }
  Eigen::MatrixXcd Coordinates(const Eigen::MatrixXd& x) const { return v_inv_ * x; }

  // Per pole: the amplitude of rows `cv` (= C V, rows x states, precomputed once) of the
  // free response from modal coordinates z, the Euclidean norm over the rows of
  // sum_{members} cv_i z_i (doubled for a pair). Their sum bounds the rows' norm for all
  // t >= 0. A pair's is capped (CappedResidual) at sqrt(n) ResidualCap(zeta) times the
  // largest PairPeak of its n rows (n those it reaches: |p| <= sqrt(n) max_r |p_r|). NaN
  // amplitudes when z is not WellSplit.
  std::vector<PoleAmplitude> Amplitudes(const Eigen::MatrixXcd& cv, const Eigen::VectorXcd& z) const;

  // The same amplitudes from a real state x and real rows `c` of C, through a real basis of
  // the poles' invariant subspaces instead of V: a pair's (Re v, Im v), v's phase turned so
  // that v^T v is real (Re v and Im v are then orthogonal), each of norm 1. As a pair nears
  // critical damping its eigenvectors v and conj(v) become parallel and V^{-1} cancels
  // (WellSplit false; short of that, parts of 1e-7 already near zeta = 1 - 1e-10), while
  // this basis still spans the pair's invariant subspace well: the residual metrics take it
  // where a pair's cap acts or V^{-1} does not split. NaN amplitudes when even this basis
  // does not split x (WellSplit's two tests: a defective A, an exactly critical pair).
  std::vector<PoleAmplitude> AmplitudesOfState(const Eigen::MatrixXd& c, const Eigen::VectorXd& x) const;

  // False when V is too close to singular for the modal coordinates to mean anything (a
  // defective A: a critically damped pair): V V^{-1} is off the identity by more than
  // kMaxInverseError, or the parts of the state would cancel by more than kMaxCancellation
  // of its size.
  bool WellSplit(const Eigen::VectorXcd& z) const;
  static constexpr double kMaxCancellation = 1e6;
  static constexpr double kMaxInverseError = 1e-6;

 private:
  Eigen::VectorXcd lambda_;
  Eigen::MatrixXcd v_;
  Eigen::MatrixXcd v_inv_;
  std::vector<FreePole> poles_;
  bool invertible_ = false;
  // AmplitudesOfState's real basis: its columns, their inverse, A times them, the columns of
  // each pole (poles_ order).
  void BuildRealBasis(const Eigen::MatrixXd& a);
  Eigen::MatrixXd basis_;
  Eigen::MatrixXd basis_inv_;
  Eigen::MatrixXd a_basis_;
  std::vector<std::vector<Eigen::Index>> pole_columns_;
  bool real_invertible_ = false;
};

// The decomposition of `a`, computed once and handed out again for an equal matrix (the
// last few per thread, as DiscretizeExactly does): a sweep's points on one plant share it.
std::shared_ptr<const ModalDecomposition> DecomposeModes(const Eigen::MatrixXd& a);

}  // namespace shapebench::model
