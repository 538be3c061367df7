#pragma once
// Internal: the over-relaxed multiplier update of SMALSE-M, beta^{k+1} = beta^k + omega rho G mu^k
// (ALGORITHMS.md 4, Step 3 with omega = 1: the paper's update after (19)), omega chosen from the
// measured contraction of ||G mu|| (doc/parameters.md, "The multiplier step").
//
// Why it works: with the inner problems solved exactly and the active set fixed, Step 3 is a
// gradient ascent with step rho on the dual function of the equality constraint, a concave
// quadratic whose Hessian, times rho, has its eigenvalues theta in (0, 1) (theta = rho s /
// (1 + rho s), s the curvature of each mode). The error in beta contracts mode by mode by
// |1 - omega theta|: omega = 1 leaves the slowest mode at r0 = 1 - theta_min, and any omega in
// (0, 2) converges. The omega that balances the slowest mode against the stiffest (theta -> 1),
// 2 / (1 + theta_min) = 2 / (2 - r0), contracts every mode by at least r0 / (2 - r0): 0.5 -> 1/3.
// r0 is read off ||G mu||: the ratio r of two successive norms is what the slowest mode gives
// under the omega in use, r = 1 - omega (1 - r0). Its signature: the slow mode keeps the sign
// of G mu from one outer iteration to the next (1 - omega theta_min > 0), the stiff modes flip
// it once omega > 1. A negative cosine between successive G mu, or a ratio r >= 1 (no steady
// contraction: the active set or the slip bound moved), says the estimate does not hold: omega
// returns to 1.
#include <algorithm>

namespace tribos::qp {

class MultiplierRelaxation {
 public:
  /// Rates up to this are left alone: little to gain (r0 0.3 -> 0.18) where the ratio is most
  /// disturbed by the moving active set (the cells of doc/parameters.md: a lower bound moved
  /// the small cells both ways).
  static constexpr double kFastRate = 0.3;
  /// The largest r0 believed: omega <= 2 / (2 - 0.8) = 5/3 keeps the stiff modes' factor
  /// |1 - omega| <= 2/3, away from 1 (omega = 2), where a rate over-estimated by a transient
  /// would stall them.
  static constexpr double kSlowestRate = 0.8;

  /// After an outer iteration with ||Q mu|| = gmu, the previous one's previousGmu (> 0) and
  /// cosine = the cosine of the angle between the two Q mu: the omega for this update, which
  /// unrelaxedRatio() then reports for it.
  double next(double gmu, double previousGmu, double cosine) {
    const double r = gmu / previousGmu;
    unrelaxedRatio_ = 1.0 - (1.0 - r) / omega_;
    const bool steady = r < 1.0 && cosine > 0.0;
    const double r0 = std::min(unrelaxedRatio_, kSlowestRate);
    omega_ = steady && r0 > kFastRate ? 2.0 / (2.0 - r0) : 1.0;
    return omega_;
  }
  /// The contraction that omega = 1 would have given at the last next() (the ratio measured,
  /// undone of the relaxation in use): what a rho update needs (SmalseSettings::rhoUpdate).
  double unrelaxedRatio() const { return unrelaxedRatio_; }

 private:
  double omega_ = 1.0;
  double unrelaxedRatio_ = 1.0;
};

}  // namespace tribos::qp
