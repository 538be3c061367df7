#pragma once
/// \file DualTypes.hpp
/// What qp/ sees of the world: distributed vectors (Tpetra, each entry owned by one rank)
/// and symmetric operators on them. qp/ knows nothing of meshes or FETI.
#include <Tpetra_Map_decl.hpp>
#include <Tpetra_Vector_decl.hpp>

#include <vector>

namespace tribos::qp {

using Map = Tpetra::Map<int, long long>;
using Vector = Tpetra::Vector<double, int, long long>;

/// y = A x for a symmetric positive semidefinite A. Implementations count their applications.
class SymmetricOperator {
 public:
  virtual ~SymmetricOperator() = default;
  virtual void apply(const Vector& x, Vector& y) const = 0;
};

/// Coordinates of Q x that are linear in x (EqualityProjector::coordinates): ||Q x||^2 = u^T w.
struct EqualityCoordinates {
  std::vector<double> u, w;
};

/// A = P X P with P = I - Q for the Q of the equality constraint that SMALSE-M is given. Such
/// an operator computes P x anyway, so A x + s Q x needs no projection of its own: Q x = x - P x
/// (A_rho = A + rho Q and the preconditioner M^-1 + Q / rho save one projection per product).
class ProjectedOperator : public SymmetricOperator {
 public:
  /// y = A x + s Q x. With `ofX` (may be null): also the coordinates of Q x that computing P x
  /// gives on the way (the bits of EqualityProjector::coordinates(x)); returns whether it gave
  /// them.
  virtual bool applyPlusComplement(const Vector& x, Vector& y, double s, EqualityCoordinates* ofX) const = 0;
};

/// The orthogonal projector Q onto Im G^T (so that P = I - Q projects onto Ker G) of the
/// equality constraint G x = 0. With G's rows orthonormalised, ||G x|| = ||Q x||.
class EqualityProjector {
 public:
  virtual ~EqualityProjector() = default;
  virtual void applyQ(const Vector& x, Vector& y) const = 0;
  /// ||Q x|| (scratch: a vector of x's map, overwritten). The default projects; an
  /// implementation may do it without G^T: ||Q x||^2 = (G x)^T (G G^T)^{-1} G x.
  virtual double normQ(const Vector& x, Vector& scratch) const;
  /// Optional: coordinates of Q x that are linear in x, replicated on every rank, with
  /// ||Q x||^2 = u^T w (u = G x and w = (G G^T)^{-1} G x, so that Q x = G^T w). SMALSE-M then
  /// follows ||Q x|| along MPGP's CG steps x := x - alpha p by u, w -= alpha (u_p, w_p)
  /// instead of a projection per inner iteration (EqualityNorm.hpp). Collective. Returns
  /// false where there are none (the default).
  virtual bool coordinates(const Vector& x, std::vector<double>& u, std::vector<double>& w) const;
};

}  // namespace tribos::qp
