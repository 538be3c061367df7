#pragma once
// Internal: ||Q x|| of MPGP's iterate at each of its stop tests, for SMALSE-M's inner bound
// M_k ||G mu|| (paper (19)-(20); ALGORITHMS.md 4). Computed afresh it costs a projection (in
// T-FETI a coarse solve, the dominant cost at many subdomains: doc/measurements/coarse_problem.md). With
// linear coordinates (EqualityProjector::coordinates: ||Q x||^2 = u^T w) it follows a CG step
// x := x - alpha p for the price of the coordinates of p, which the product A p has just
// computed (the projector keeps them): u -= alpha u_p, w -= alpha w_p.
#include <vector>

#include "tribos/qp/DualTypes.hpp"

namespace tribos::qp {

class EqualityNorm {
 public:
  /// Coordinates are recomputed afresh after `refreshEvery` consecutive tracked steps, so
  /// that the rounding of the updates cannot accumulate.
  explicit EqualityNorm(const EqualityProjector& Q, int refreshEvery = 10) : Q_(Q), refreshEvery_(refreshEvery) {}
  /// A new inner solve: the next norm() is computed afresh.
  void restart() {
    valid_ = false;
    stepsSinceNorm_ = 0;
  }
  /// x := x - alpha p has just happened (Mpgp's cgStep).
  void cgStep(double alpha, const Vector& p);
  /// ||Q x|| for the iterate x at a stop test (scratch: a vector of x's map). Collective.
  double norm(const Vector& x, Vector& scratch);
  /// Norms that followed a CG step without coordinates of x (for tests).
  long long trackedNorms() const { return tracked_; }

 private:
  const EqualityProjector& Q_;
  int refreshEvery_;
  bool valid_ = false;      ///< u_, w_ are the coordinates of the iterate of the last norm()
  int stepsSinceNorm_ = 0;  ///< CG steps reported since the last norm()
  int trackedInARow_ = 0;
  long long tracked_ = 0;
  std::vector<double> u_, w_, up_, wp_;
};

}  // namespace tribos::qp
