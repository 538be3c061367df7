#pragma once
// Internal: ||Q x|| of MPGP's iterate at each of its stop tests, for SMALSE-M's inner bound
// M_k ||G mu|| (paper (19)-(20); ALGORITHMS.md 4). Computed afresh it costs a projection (in
// T-FETI a coarse solve, the dominant cost at many subdomains: doc/measurements/coarse_problem.md). With
// linear coordinates (EqualityProjector::coordinates: ||Q x||^2 = u^T w) it follows a CG step
// x := x - alpha p for the price of the coordinates of p, which the product A p has just
// computed: u -= alpha u_p, w -= alpha w_p. Where MPGP's gradient came from a product with the
// iterate itself, its coordinates come from that product. The products hand them over
// explicitly (`lastProduct`: the coordinates of the last product's input, where it gave them).
#include <functional>
#include <vector>

#include "tribos/qp/DualTypes.hpp"

namespace tribos::qp {

class EqualityNorm {
 public:
  /// Coordinates are recomputed afresh after `refreshEvery` consecutive tracked steps, so
  /// that the rounding of the updates cannot accumulate.
  /// `lastProduct` (may be empty): the coordinates of the input of the last product with A, or
  /// null where that product did not compute them; without it, Q's coordinates are computed.
  using ProductCoordinates = std::function<const EqualityCoordinates*()>;
  explicit EqualityNorm(const EqualityProjector& Q, int refreshEvery = 10, ProductCoordinates lastProduct = {})
      : Q_(Q), refreshEvery_(refreshEvery), lastProduct_(std::move(lastProduct)) {}
  /// A new inner solve: the next norm() is computed afresh.
  void restart() {
    valid_ = false;
    fromProduct_ = false;
    stepsSinceNorm_ = 0;
  }
  /// x := x - alpha p has just happened, right after the product A p (Mpgp's cgStep).
  void cgStep(double alpha, const Vector& p);
  /// g = A x - b has just been computed by a product with the iterate x (Mpgp's
  /// gradientFromProduct): the next norm() takes x's coordinates from that product.
  void gradientFromProduct() { fromProduct_ = true; }
  /// ||Q x|| for the iterate x at a stop test (scratch: a vector of x's map). Collective.
  double norm(const Vector& x, Vector& scratch);
  /// Norms that followed a CG step without coordinates of x (for tests).
  long long trackedNorms() const { return tracked_; }

 private:
  /// u, w of `x`: from the last product when `fromProduct` and it gave them, else computed.
  bool coordinatesOf(const Vector& x, bool fromProduct, std::vector<double>& u, std::vector<double>& w) const;
  const EqualityProjector& Q_;
  int refreshEvery_;
  ProductCoordinates lastProduct_;
  bool fromProduct_ = false;  ///< the last product's input is the iterate (gradientFromProduct)
  bool valid_ = false;      ///< u_, w_ are the coordinates of the iterate of the last norm()
  int stepsSinceNorm_ = 0;  ///< CG steps reported since the last norm()
  int trackedInARow_ = 0;
  long long tracked_ = 0;
  std::vector<double> u_, w_, up_, wp_;
};

}  // namespace tribos::qp
