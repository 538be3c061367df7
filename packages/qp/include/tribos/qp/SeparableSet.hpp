#pragma once
/// \file SeparableSet.hpp
/// A separable closed convex set Omega on dual vectors (ALGORITHMS.md 5; PERMON's QPC):
/// a product of
///  - bounds      x_i >= l_i                         (contact normal: mu_nu >= -lambda_Im,nu)
///  - ellipses    ||diag(1/a)(x_pair - c)|| <= 1      (friction: semi-axes a_j = F_j g,
///                                                     centre c = -lambda_Im,t)
///  - free entries (everything else: gluing, Dirichlet).
/// Indices are LOCAL indices of the vector's map; every block lies on one rank. A zero
/// semi-axis (g = 0: node out of contact) makes the ellipse degenerate (a segment or the
/// centre point) and is handled exactly.
#include <array>
#include <vector>

#include "tribos/qp/DualTypes.hpp"

namespace tribos::qp {

class SeparableSet {
 public:
  void addBound(int localIndex, double lower);
  /// An index -1 marks an absent row: the block is then the interval |x_i - c_i| <= a_i
  /// (friction along one tangential direction only, e.g. in a plane-strain slice).
  void addEllipse(std::array<int, 2> localIndex, std::array<double, 2> center, std::array<double, 2> semiAxes);
  /// Changes the semi-axes of ellipse k (the slip bound update of the Coulomb fixed point).
  void setSemiAxes(int k, std::array<double, 2> semiAxes);
  int numBounds() const;
  int numEllipses() const;

  /// x := P_Omega(x) (Euclidean projection).
  void project(Vector& x) const;
  /// True if x lies in Omega up to a relative tolerance.
  bool contains(const Vector& x, double tolerance = 1e-12) const;
  /// The largest alpha >= 0 with x - alpha p in Omega (x in Omega); a global minimum over
  /// ranks (one all-reduce). +infinity when no block limits the step.
  /// With `slideOnEllipses`, the ellipse blocks active at x do not limit the step (MPGP's
  /// tangent CG: such blocks move along the tangent and are projected back).
  double maxFeasibleStep(const Vector& x, const Vector& p, bool slideOnEllipses = false) const;
  /// Free gradient phi (g on free blocks and on blocks not active at x, 0 on active blocks)
  /// and chopped gradient beta (on active blocks: g - min(n^T g, 0) n with n the outer unit
  /// normal; 0 elsewhere). g^P = phi + beta is the projected gradient.
  /// With `slideOnEllipses`, a smooth active ellipse block is free along its tangent line:
  /// phi = g - (n^T g) n (the tangential part), beta = max(n^T g, 0) n (g^P is the same), so
  /// that CG moves the friction multipliers along their boundary (linearised face).
  void splitGradient(const Vector& x, const Vector& g, Vector& phi, Vector& beta, bool slideOnEllipses = false) const;
  /// sum over the active smooth ellipse blocks of kappa_k |n_k^T g_k| ||d_k||^2, with kappa_k
  /// the boundary's curvature at x along the tangent and n_k the outer normal: the second
  /// derivative that the constraint adds to f along an arc of the boundary tangent to d (the
  /// Lagrange multiplier |n^T g| times the curvature). 0 on bounds and free blocks.
  double boundaryCurvature(const Vector& x, const Vector& g, const Vector& d) const;
  /// out += H_c d, with H_c = sum over the active smooth ellipse blocks pressed outwards of
  /// kappa_k |n_k^T g_k| (I - n_k n_k^T): the Hessian that the curved boundary adds to f on the
  /// linearised face (its quadratic form on tangent d is boundaryCurvature).
  void addCurvatureProduct(const Vector& x, const Vector& g, const Vector& d, Vector& out) const;
  /// Reduced free gradient phi~ = (x - P_Omega(x - alpha phi)) / alpha.
  void reducedFreeGradient(const Vector& x, const Vector& phi, double alpha, Vector& out) const;

 private:
  std::array<double, 2> effectiveAxes(size_t k) const;
  /// Ellipse block k at (x_i, x_j) when it is smooth (both axes > 0) and on its boundary: sets
  /// y = x - c_k and a = its effective axes and returns true (the curvature terms' blocks).
  bool onSmoothBoundary(size_t k, double xi, double xj, std::array<double, 2>& y, std::array<double, 2>& a) const;

  std::vector<int> boundIndex_;
  std::vector<double> lower_;
  std::vector<std::array<int, 2>> ellipseIndex_;
  std::vector<std::array<double, 2>> center_, semiAxes_;
};

/// Euclidean projection of w onto the ellipse {y : (y_1/a_1)^2 + (y_2/a_2)^2 <= 1} centred at
/// 0 (a_j >= 0); exposed for tests. Newton on the secular equation with bisection guard.
std::array<double, 2> projectOntoEllipse(std::array<double, 2> w, std::array<double, 2> a);

}  // namespace tribos::qp
