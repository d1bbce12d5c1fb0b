// The right-hand side, root functions, Jacobian and event handling of a NonlinearPlant
// (model/nonlinear_plant.h) for CVODE (model/nonlinear_integrator.h); docs/nonlinear.md has
// the equations. The integrated state is y = [z; zeta]: z = [x; v] the augmented linear
// state, zeta one bristle deflection per LuGre element.
//
// Modes make every force smooth between events (root functions):
//   Coulomb / Stribeck friction   slipping with sign s (F = s g(w) + sigma2 w; root: w = 0)
//                                 or stuck (w held at 0 by the force F* that keeps w' = 0,
//                                 solved jointly for every stuck element; root: |F*| = F_s)
//   LuGre friction                one mode; root w = 0 only restarts at the kink of |w|
//   backlash                      in the gap or in contact on either side (roots d = +-b/2)
//   saturation                    within or beyond the limit on either side (F_m = +-L)
// At an event the new modes are chosen from the state there; an element that sticks gets
// the impulse through itself that makes its w exactly 0 (a stuck set is held consistent:
// any stuck element whose F* exceeds its F_s is released).
#pragma once

#include <algorithm>
#include <vector>

#include <Eigen/Dense>

#include "model/nonlinear_plant.h"

namespace shapebench::model {

class NonlinearDynamics {
 public:
  explicit NonlinearDynamics(const NonlinearPlant& plant);

  int num_augmented() const { return nz_; }       // z = [x; v]
  int size() const { return nz_ + num_bristles_; }  // y = [z; zeta]
  int num_roots() const { return num_roots_; }
  int num_elements() const { return static_cast<int>(elements_.size()); }
  // Element i's mode (the plant's order): friction +-1 sliding, 0 stuck (LuGre 0);
  // backlash and the force limit -1, 0 (within), +1.
  int mode(int i) const { return elements_[i].mode; }
  // The bristle states' scale (F_s / sigma0 per LuGre element), for tolerances.
  std::vector<double> BristleScales() const;

  // The held input changed: forcing = B_z a (length nz).
  void SetForcing(const Eigen::VectorXd& forcing);
  // Per element: a value added to its row z and to that row's rate (the rows of a response
  // the state leaves out: model/held_input_response.h); 0 until set.
  void SetOffsets(const double* values, const double* rates) {
    std::copy(values, values + num_elements(), offset_value_.begin());
    std::copy(rates, rates + num_elements(), offset_rate_.begin());
  }
  // Whether the offsets' rates are read (only a stuck element's holding force reads them).
  bool ReadsRates() const { return !stuck_.empty(); }
  // Modes at rest (y from Reset): sliding where w != 0, stuck where w == 0 and F_s > 0.
  void InitModes(const double* y);
  // After the input changed: releases stuck elements the new forcing breaks loose. True
  // when a mode changed.
  bool ReleaseOverloaded(const double* y);
  // At CVODE's roots (`found`: +1 rising, -1 falling, 0 none per root function): new modes,
  // impulses for elements that stick (y changed in place). True when a mode changed.
  bool HandleRoots(const int* found, double* y);

  // The groups of states of y the Jacobian couples (connected components of its sparsity:
  // the linear part's, each element's row, column and bristle together), ascending.
  std::vector<std::vector<int>> Blocks() const;

  // Per root function: -1 where only a falling crossing is an event (CVodeSetRootDirection:
  // a sliding element's s w, a stuck one's F_s - |F*|), 0 for either way.
  std::vector<int> RootDirections() const;

  void Rhs(const double* y, double* ydot);
  void Roots(const double* y, double* g);
  // Dense, column-major, size() x size().
  void Jacobian(const double* y, double* jac);

 private:
  struct Sparse {  // a vector without its zeros
    std::vector<int> index;
    std::vector<double> value;
    void Assign(const Eigen::VectorXd& v);
    double Dot(const double* x) const;
  };
  struct Element {
    NonlinearElement config;
    Sparse row;     // over z
    Sparse column;  // over z (x part)
    Sparse row_a;   // row A_z: the rate of row z without forcing and element forces
    int bristle = -1;  // LuGre: index of zeta in y after z
    int root = 0;      // its first root function
    int mode = 0;      // friction: +-1 sliding, 0 stuck; backlash/saturation: -1, 0, +1
    bool sticks = false;  // Coulomb or Stribeck friction (config.law's Sticks())
    double row_forcing = 0.0;  // row . forcing
  };

  static bool Sticks(const Element& e) { return e.sticks; }
  static bool Stuck(const Element& e) { return e.sticks && e.mode == 0; }
  // The friction of an element that has a bristle or sticks.
  static const FrictionElement& Friction(const Element& e) { return std::get<FrictionElement>(e.config.law); }
  // The forces of every element at y (stuck ones solved jointly), into force_.
  void Forces(const double* y);
  // The force and its derivative by its row value (and by its bristle state) of a
  // non-stuck element.
  double Force(const Element& e, double w, const double* y, double* dw, double* dzeta) const;
  void SolveStuck(const double* y);
  // Corrects the stuck forces (and ydot) by the rate their rows still have in ydot.
  void RefineStuck(double* ydot);
  // Gives every stuck element the impulse that makes its w 0 (jointly).
  void Project(double* y);
  // Releases stuck elements whose holding force exceeds F_s until the stuck set holds.
  bool Settle(const double* y);
  // The stuck set's G_SS (row_i . column_j) and its LU, rebuilt when the set changes.
  void RebuildStuckSet();

  int nz_ = 0;
  int num_bristles_ = 0;
  int num_roots_ = 0;
  Eigen::MatrixXd a_z_;
  std::vector<std::vector<std::pair<int, double>>> a_sparse_;  // per row of A_z: (col, value)
  Eigen::VectorXd forcing_;
  std::vector<Element> elements_;
  Eigen::MatrixXd coupling_;  // row_i . column_j
  std::vector<int> stuck_;    // indices of stuck elements
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> stuck_solver_;  // of G_SS (2+ stuck)
  Eigen::VectorXd stuck_rhs_;
  Eigen::MatrixXd grads_;  // Jacobian scratch: dF_e/dy per element (columns)
  std::vector<double> force_;
  std::vector<double> value_;  // row z per element
  std::vector<double> rate_;   // LuGre: zeta' per element (Forces)
  std::vector<double> offset_value_;  // SetOffsets
  std::vector<double> offset_rate_;
  double Value(int i, const double* y) const { return elements_[i].row.Dot(y) + offset_value_[i]; }
};

}  // namespace shapebench::model
