#pragma once
// Internal to qp/: the state of one MPGP inner solve and its step kinds (ALGORITHMS.md 5;
// MPRGP with preconditioning in face, chopped proportioning and tangent CG on the friction
// ellipses, doc/theory.md "Where MPGP departs from the paper's"). Mpgp::solve is the loop that
// picks a step kind per iteration; each step keeps x, g = A x - b, the split phi / beta of g
// and the search direction consistent for the next.
#include <array>

#include "tribos/qp/Mpgp.hpp"

namespace tribos::qp {

class MpgpRun {
 public:
  MpgpRun(const MpgpSettings& settings, const SymmetricOperator& A, const Vector& b, const SeparableSet& omega,
          double normA, Vector& x, Vector& g);

  /// x projected onto Omega, g = A x - b (kept when `gradientGiven` and the projection leaves
  /// x in place), its split and a fresh search direction.
  void start(bool gradientGiven);
  /// ||g^P||^2, ||beta||^2 and phi~^T phi (the proportioning test) in one reduction.
  std::array<double, 3> iterationSums();
  /// A proportional iterate: a CG step on the face (plain or sliding along the ellipses), or
  /// an expansion step when the CG step would leave Omega.
  void proportionalStep();
  /// Not proportional: release constraints by a gradient projection step, or, right after
  /// one, by the exact step along the chopped gradient (chopped proportioning).
  void proportioningStep();

  MpgpCounters counters;

 private:
  enum class Direction { Current, Restart, Conjugate };

  void split(const Vector& at, const Vector& gradientAt, Vector& free, Vector& chopped) const;
  void gradient();
  void preconditionedFreeGradient();
  void restartDirection() { direction_ = Direction::Restart; }
  void conjugateDirection(const Vector& product, double curvature);
  void resolveDirection();
  double objective(const Vector& at, const Vector& gradientAt);
  void projectedStep(const Vector& direction);
  void startSliding();
  void gradientProjectionStep();
  bool tentativeProjectedStep(double alpha, const Vector& d);
  void choppedGradientStep();
  bool slidingCgStep(double alphaCg, double pAp);
  void cgStep(double alphaCg, double pAp);
  void expansionStep(double alphaFeasible);
  bool optimalExpansionStep();

  const MpgpSettings& settings_;
  const SymmetricOperator& A_;
  const Vector& b_;
  const SeparableSet& omega_;
  Vector& x_;
  Vector& g_;
  const double alphaBar_;
  Vector phi_, beta_, p_, Ap_, reduced_, gradientProjected_, trial_, trialGradient_, z_, zFull_, scratch_;
  Vector previousX_, previousG_;  ///< saved iterate and gradient, to undo a step that did not decrease f
  int slideFrom_, failedSlides_ = 0;
  bool slide_;
  Direction direction_ = Direction::Current;
  const Vector* conjugateProduct_;       ///< (A + H_c) p of the CG step that left Conjugate
  double conjugateCurvature_ = 0.0;      ///< its p^T (A + H_c) p
  int proportioningRun_ = 0;             ///< consecutive proportioning steps so far
};

}  // namespace tribos::qp
