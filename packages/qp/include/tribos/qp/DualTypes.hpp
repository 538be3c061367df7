#pragma once
/// \file DualTypes.hpp
/// What qp/ sees of the world: distributed vectors (Tpetra, each entry owned by one rank)
/// and symmetric operators on them. qp/ knows nothing of meshes or FETI.
#include <Tpetra_Map_decl.hpp>
#include <Tpetra_Operator.hpp>
#include <Tpetra_Vector_decl.hpp>

#include <string>
#include <vector>

namespace tribos::qp {

using Map = Tpetra::Map<int, long long>;
using Vector = Tpetra::Vector<double, int, long long>;

/// y = A x for a symmetric positive semidefinite A. Implementations count their applications.
/// The one operator family of Tribos: the solvers here call the one-vector apply(x, y) (and,
/// where an operator offers them, the fused products of ProjectedOperator); the same object is
/// a Tpetra::Operator, so that Belos, Anasazi or a user's Tpetra code applies it as it is
/// (T-FETI's F, P F P, P and P D P: feti/DualOperators.hpp). Its Tpetra apply computes
/// Y = alpha A X + beta Y column by column with the one-vector apply (beta = 0 ignores Y's old
/// values), after checking that X and Y live on the operator's map (the same map, or one with
/// the same global ids on every rank; collective): a vector of another map is
/// std::invalid_argument naming the operator, never a silent product. An operator made
/// without a map (a test's dense matrix) serves the solvers here only: its Tpetra apply throws.
class SymmetricOperator : public Tpetra::Operator<double, int, long long> {
 public:
  using MultiVector = Tpetra::MultiVector<double, int, long long>;
  explicit SymmetricOperator(Teuchos::RCP<const Map> map = Teuchos::null, std::string name = "operator")
      : map_(std::move(map)), name_(std::move(name)) {}
  /// y = A x.
  virtual void apply(const Vector& x, Vector& y) const = 0;
  /// Tpetra's contract: Y = alpha A X + beta Y (A symmetric, so every mode is the same).
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp mode = Teuchos::NO_TRANS, double alpha = 1.0,
             double beta = 0.0) const final;
  Teuchos::RCP<const Map> getDomainMap() const final { return map_; }
  Teuchos::RCP<const Map> getRangeMap() const final { return map_; }
  bool hasTransposeApply() const final { return true; }
  const std::string& name() const { return name_; }

 private:
  /// Throws std::invalid_argument unless V lives on map_ (collective: Map::isSameAs).
  void requireOwnMap(const MultiVector& V, const char* which) const;
  Teuchos::RCP<const Map> map_;
  std::string name_;
  mutable Teuchos::RCP<Vector> column_;  ///< A X_j before it is scaled into Y_j
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
  using SymmetricOperator::SymmetricOperator;
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
