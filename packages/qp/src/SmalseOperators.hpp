#pragma once
// Internal to qp/: the operators of SMALSE-M's inner problems (paper (19)): A_rho = A + rho Q
// and its preconditioner M^-1 + Q / rho, each timed.
#include <Tpetra_Vector.hpp>

#include "TimedOperators.hpp"
#include "tribos/qp/SmalseM.hpp"

namespace tribos::qp {

/// A_rho = A + rho Q (the penalised Hessian of paper (19)). Counts products with A only.
class PenalisedOperator : public SymmetricOperator {
 public:
  PenalisedOperator(const SymmetricOperator& A, const EqualityProjector& Q, double rho, const Teuchos::RCP<const Map>& map,
                    double& seconds)
      : A_(A), projected_(dynamic_cast<const ProjectedOperator*>(&A)), Q_(Q), rho_(rho), tmp_(map), seconds_(seconds) {}
  void setRho(double rho) { rho_ = rho; }
  void apply(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    if (projected_) {
      projected_->applyPlusComplement(x, y, rho_);  // Q x from the P x that A computes
      return;
    }
    A_.apply(x, y);
    Q_.applyQ(x, tmp_);
    y.update(rho_, tmp_, 1.0);
  }

 private:
  const SymmetricOperator& A_;
  const ProjectedOperator* projected_;  ///< A, when it can add Q x without a projection
  const EqualityProjector& Q_;
  double rho_;
  mutable Vector tmp_;
  double& seconds_;  ///< time in products (SmalseCounters::operatorSeconds)
};

/// M^-1 + Q / rho: the inner preconditioner of A_rho (paper (19)) from one of PFP on Ker G.
class PenalisedPreconditioner : public SymmetricOperator {
 public:
  PenalisedPreconditioner(const SymmetricOperator& M, const EqualityProjector& Q, double rho,
                          const Teuchos::RCP<const Map>& map, double& seconds)
      : M_(M), projected_(dynamic_cast<const ProjectedOperator*>(&M)), Q_(Q), rho_(rho), tmp_(map), seconds_(seconds) {}
  void setRho(double rho) { rho_ = rho; }
  void apply(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    if (projected_) {
      projected_->applyPlusComplement(x, y, 1.0 / rho_);
      return;
    }
    M_.apply(x, y);
    Q_.applyQ(x, tmp_);
    y.update(1.0 / rho_, tmp_, 1.0);
  }

 private:
  const SymmetricOperator& M_;
  const ProjectedOperator* projected_;  ///< M, when it can add Q x / rho without a projection
  const EqualityProjector& Q_;
  double rho_;
  mutable Vector tmp_;
  double& seconds_;
};

}  // namespace tribos::qp
