#pragma once
// Internal: wall time that SMALSE-M spends inside what it is given (A, the preconditioner, Q,
// the outer hook), so that the rest of its time, its own vector work (updates, projections
// onto Omega, reductions), can be reported (SmalseCounters::operatorSeconds; issue 9).
#include <vector>

#include "tribos/core/Timer.hpp"
#include "tribos/qp/DualTypes.hpp"

namespace tribos::qp {

using core::ScopedSeconds;

/// A with the time of its products added to `seconds`.
class TimedOperator : public SymmetricOperator {
 public:
  TimedOperator(const SymmetricOperator& A, double& seconds)
      : SymmetricOperator(A.getDomainMap(), A.name()), A_(A), seconds_(seconds) {}
  void apply(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    A_.apply(x, y);
  }

 private:
  const SymmetricOperator& A_;
  double& seconds_;
};

/// Q with the time of every call added to `seconds`.
class TimedProjector : public EqualityProjector {
 public:
  TimedProjector(const EqualityProjector& Q, double& seconds) : Q_(Q), seconds_(seconds) {}
  void applyQ(const Vector& x, Vector& y) const override {
    ScopedSeconds timed(seconds_);
    Q_.applyQ(x, y);
  }
  double normQ(const Vector& x, Vector& scratch) const override {
    ScopedSeconds timed(seconds_);
    return Q_.normQ(x, scratch);
  }
  bool coordinates(const Vector& x, std::vector<double>& u, std::vector<double>& w) const override {
    ScopedSeconds timed(seconds_);
    return Q_.coordinates(x, u, w);
  }

 private:
  const EqualityProjector& Q_;
  double& seconds_;
};

}  // namespace tribos::qp
