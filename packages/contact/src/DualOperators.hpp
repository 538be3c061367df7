#pragma once
// Internal to contact/: the operators SMALSE-M sees, built on T-FETI's (doc/design.md,
// "Contact solve"): A = P F P, the preconditioner P D P and Q = I - P.
#include <algorithm>
#include <cmath>
#include <vector>

#include "tribos/feti/TotalFeti.hpp"
#include "tribos/qp/SmalseM.hpp"

namespace tribos::contact {

using feti::DualVector;

/// A = P F P: one F application per product (what the paper counts as n_PFP). P F P x is
/// applyPF(P x): two projections, and F without the kernel projections of K^dagger (P x is in
/// Ker G). A_rho = A + rho Q reuses P x for Q x = x - P x (ProjectedOperator).
class ProjectedDualOperator : public qp::ProjectedOperator {
 public:
  explicit ProjectedDualOperator(const feti::TotalFeti& feti) : feti_(feti), tmp_(feti.createDualVector()) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override { applyWith(x, y, nullptr); }
  bool applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s, qp::EqualityCoordinates* ofX) const override {
    applyWith(x, y, ofX ? &coordinates_ : nullptr);
    y.update(s, x, -s, *tmp_, 1.0);  // + s (x - P x)
    if (!ofX) return false;
    ofX->u.swap(coordinates_.gx);
    ofX->w.swap(coordinates_.a);
    return true;
  }

 private:
  void applyWith(const qp::Vector& x, qp::Vector& y, feti::CoarseCoordinates* ofX) const {
    feti_.project(x, *tmp_, ofX);
    feti_.applyPF(*tmp_, y);
  }
  const feti::TotalFeti& feti_;
  Teuchos::RCP<DualVector> tmp_;  ///< P x of the last product
  mutable feti::CoarseCoordinates coordinates_;  ///< of the last product's x, handed on
};

/// P D P with D the lumped (B K B^T) or Dirichlet (B S B^T) dual preconditioner: an
/// approximate inverse of PFP on Ker G, for MPGP's preconditioning in face.
class ProjectedDualPreconditioner : public qp::ProjectedOperator {
 public:
  ProjectedDualPreconditioner(const feti::TotalFeti& feti, bool dirichlet)
      : feti_(feti), dirichlet_(dirichlet), tmp_(feti.createDualVector()) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override {
    feti_.project(x, *tmp_);
    if (dirichlet_)
      feti_.applyDirichlet(*tmp_, y);
    else
      feti_.applyLumped(*tmp_, y);
    feti_.project(y, y);
  }
  bool applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s, qp::EqualityCoordinates*) const override {
    apply(x, y);
    y.update(s, x, -s, *tmp_, 1.0);  // + s (x - P x)
    return false;
  }

 private:
  const feti::TotalFeti& feti_;
  bool dirichlet_;
  Teuchos::RCP<DualVector> tmp_;  ///< P x of the last product
};

/// Q = I - P = G^T (G G^T)^{-1} G.
class CoarseSpaceProjector : public qp::EqualityProjector {
 public:
  explicit CoarseSpaceProjector(const feti::TotalFeti& feti) : feti_(feti) {}
  void applyQ(const qp::Vector& x, qp::Vector& y) const override {
    feti_.project(x, y);
    y.update(1.0, x, -1.0);
  }
  /// ||Q x||^2 = x^T Q x = (G x)^T (G G^T)^{-1} G x: G and the coarse solve, no G^T pass.
  double normQ(const qp::Vector& x, qp::Vector&) const override {
    feti_.coarseCoordinates(x, gx_, a_);
    double q = 0.0;
    for (size_t i = 0; i < a_.size(); ++i) q += gx_[i] * a_[i];
    return std::sqrt(std::max(q, 0.0));
  }
  bool coordinates(const qp::Vector& x, std::vector<double>& u, std::vector<double>& w) const override {
    feti_.coarseCoordinates(x, u, w);
    return true;
  }

 private:
  const feti::TotalFeti& feti_;
  mutable std::vector<double> gx_, a_;  ///< G x and (G G^T)^{-1} G x, reused
};

}  // namespace tribos::contact
