#pragma once
// Internal to qp/: the operators of SMALSE-M's inner problems (paper (19)): A_rho = A + rho Q
// and its preconditioner M^-1 + Q / rho, each timed.
#include <Tpetra_Vector.hpp>

#include "TimedOperators.hpp"
#include "tribos/qp/SmalseM.hpp"

namespace tribos::qp {

/// A_rho = A + rho Q (the penalised Hessian of paper (19)). Counts products with A only.
/// Keeps the coordinates of Q x of its last product's input x where A gave them
/// (ProjectedOperator::applyPlusComplement): SMALSE-M's ||Q x|| of MPGP's iterate takes them
/// from there (EqualityNorm) instead of a projection of its own.
class PenalisedOperator : public SymmetricOperator {
 public:
  PenalisedOperator(const SymmetricOperator& A, const EqualityProjector& Q, double rho, const Teuchos::RCP<const Map>& map,
                    double& seconds)
      : SymmetricOperator(map, "A + rho Q"),
        A_(A),
        projected_(dynamic_cast<const ProjectedOperator*>(&A)),
        Q_(Q),
        rho_(rho),
        tmp_(map),
        seconds_(seconds) {}
  void setRho(double rho) { rho_ = rho; }
  void apply(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    if (projected_) {
      inputKnown_ = projected_->applyPlusComplement(x, y, rho_, &input_);  // Q x from the P x that A computes
      return;
    }
    inputKnown_ = false;
    A_.apply(x, y);
    Q_.applyQ(x, tmp_);
    y.update(rho_, tmp_, 1.0);
  }
  /// The coordinates of Q x for the x of the last product, where the product computed them;
  /// else null.
  const EqualityCoordinates* lastInputCoordinates() const { return inputKnown_ ? &input_ : nullptr; }

 private:
  const SymmetricOperator& A_;
  const ProjectedOperator* projected_;  ///< A, when it can add Q x without a projection
  const EqualityProjector& Q_;
  double rho_;
  mutable Vector tmp_;
  mutable EqualityCoordinates input_;  ///< of the last product's x (when inputKnown_)
  mutable bool inputKnown_ = false;
  double& seconds_;  ///< time in products (SmalseCounters::operatorSeconds)
};

/// M^-1 + Q / rho: the inner preconditioner of A_rho (paper (19)) from one of PFP on Ker G.
class PenalisedPreconditioner : public SymmetricOperator {
 public:
  PenalisedPreconditioner(const SymmetricOperator& M, const EqualityProjector& Q, double rho,
                          const Teuchos::RCP<const Map>& map, double& seconds)
      : SymmetricOperator(map, "M^-1 + Q / rho"),
        M_(M),
        projected_(dynamic_cast<const ProjectedOperator*>(&M)),
        Q_(Q),
        rho_(rho),
        tmp_(map),
        seconds_(seconds) {}
  void setRho(double rho) { rho_ = rho; }
  void apply(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    if (projected_) {
      projected_->applyPlusComplement(x, y, 1.0 / rho_, nullptr);
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
