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

// The amplitude of one pole's part of the free response, in the output's unit.
struct PoleAmplitude {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  double amplitude = 0.0;
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
  // t >= 0. NaN amplitudes when z is not WellSplit.
  std::vector<PoleAmplitude> Amplitudes(const Eigen::MatrixXcd& cv, const Eigen::VectorXcd& z) const;

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
};

// The decomposition of `a`, computed once and handed out again for an equal matrix (the
// last few per thread, as DiscretizeExactly does): a sweep's points on one plant share it.
std::shared_ptr<const ModalDecomposition> DecomposeModes(const Eigen::MatrixXd& a);

}  // namespace shapebench::model
