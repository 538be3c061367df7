#pragma once
/// \file DualOperators.hpp
/// T-FETI's dual operators, one object each for every caller: F, A = P F P, the projected
/// preconditioner P D P (D lumped or Dirichlet) and Q = I - P. SMALSE-M, MPGP and projected
/// CG apply them through qp's contract (the one-vector apply and the fused products of
/// qp::ProjectedOperator); they are Tpetra::Operators on TotalFeti::dualMap() too
/// (qp::SymmetricOperator), so that Belos, Anasazi or a user's own Tpetra code applies the same
/// objects (perf/prototypes/belos_projected_cg.cpp runs Belos's CG on them). Each product
/// counts as TotalFeti counts it. They hold a reference to the TotalFeti, which must outlive them.
#include <Teuchos_RCP.hpp>

#include <functional>
#include <vector>

#include "tribos/feti/TotalFeti.hpp"
#include "tribos/qp/DualTypes.hpp"

namespace tribos::feti {

/// F = B K^dagger B^T.
class FOperator : public qp::SymmetricOperator {
 public:
  explicit FOperator(const TotalFeti& feti);
  void apply(const qp::Vector& x, qp::Vector& y) const override;

 private:
  const TotalFeti& feti_;
};

/// A = P F P: one F application per product (what the paper counts as n_PFP). P F P x is
/// applyPF(P x): two projections, and F without the kernel projections of K^dagger (P x is in
/// Ker G). A_rho = A + rho Q reuses P x for Q x = x - P x (qp::ProjectedOperator).
class ProjectedDualOperator : public qp::ProjectedOperator {
 public:
  explicit ProjectedDualOperator(const TotalFeti& feti);
  void apply(const qp::Vector& x, qp::Vector& y) const override { applyWith(x, y, nullptr); }
  bool applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s, qp::EqualityCoordinates* ofX) const override;

 private:
  void applyWith(const qp::Vector& x, qp::Vector& y, CoarseCoordinates* ofX) const;
  const TotalFeti& feti_;
  Teuchos::RCP<DualVector> tmp_;  ///< P x of the last product
  mutable CoarseCoordinates coordinates_;  ///< of the last product's x, handed on
};

/// P D P with D lumped (B K B^T) or Dirichlet (B S B^T): an approximate inverse of PFP on
/// Ker G, for MPGP's preconditioning in face. D defaults to the one the TotalFeti was built
/// with; None, or a D it was not built for, is std::invalid_argument.
class ProjectedDualPreconditioner : public qp::ProjectedOperator {
 public:
  explicit ProjectedDualPreconditioner(const TotalFeti& feti) : ProjectedDualPreconditioner(feti, feti.preconditioner()) {}
  ProjectedDualPreconditioner(const TotalFeti& feti, DualPreconditioner D);
  void apply(const qp::Vector& x, qp::Vector& y) const override;
  bool applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s, qp::EqualityCoordinates*) const override;

 private:
  const TotalFeti& feti_;
  bool dirichlet_;
  Teuchos::RCP<DualVector> tmp_;  ///< P x of the last product
};

/// Q = I - P = G^T (G G^T)^{-1} G, the equality constraint G x = 0 of SMALSE-M.
class CoarseSpaceProjector : public qp::EqualityProjector {
 public:
  explicit CoarseSpaceProjector(const TotalFeti& feti) : feti_(feti) {}
  void applyQ(const qp::Vector& x, qp::Vector& y) const override;
  /// ||Q x||^2 = x^T Q x = (G x)^T (G G^T)^{-1} G x: G and the coarse solve, no G^T pass.
  double normQ(const qp::Vector& x, qp::Vector&) const override;
  bool coordinates(const qp::Vector& x, std::vector<double>& u, std::vector<double>& w) const override;

 private:
  const TotalFeti& feti_;
  mutable std::vector<double> gx_, a_;  ///< G x and (G G^T)^{-1} G x, reused
};

/// Which dual operator (makeDualOperator), for callers that want Trilinos's contract only.
enum class DualOperatorKind {
  F,          ///< F = B K^dagger B^T (FOperator)
  PFP,        ///< P F P (ProjectedDualOperator)
  Projector,  ///< P = I - G^T (G G^T)^{-1} G
  PDP,        ///< P D P (ProjectedDualPreconditioner)
};

/// The operator `kind` of `feti`. PDP needs a preconditioner (std::invalid_argument otherwise).
Teuchos::RCP<qp::SymmetricOperator> makeDualOperator(const TotalFeti& feti, DualOperatorKind kind);

/// Any symmetric y = op(x) on the dual map of `feti` as an operator of the family; `name`
/// appears in its errors.
Teuchos::RCP<qp::SymmetricOperator> wrapDualOperator(const TotalFeti& feti,
                                                     std::function<void(const DualVector&, DualVector&)> op,
                                                     const char* name);

}  // namespace tribos::feti
