#include "tribos/qp/SmalseM.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>

namespace tribos::qp {

namespace {
/// A_rho = A + rho Q (the penalised Hessian of paper (19)). Counts products with A only.
class PenalisedOperator : public SymmetricOperator {
 public:
  PenalisedOperator(const SymmetricOperator& A, const EqualityProjector& Q, double rho, const Teuchos::RCP<const Map>& map)
      : A_(A), Q_(Q), rho_(rho), tmp_(map) {}
  void setRho(double rho) { rho_ = rho; }
  void apply(const Vector& x, Vector& y) const override {
    A_.apply(x, y);
    Q_.applyQ(x, tmp_);
    y.update(rho_, tmp_, 1.0);
  }

 private:
  const SymmetricOperator& A_;
  const EqualityProjector& Q_;
  double rho_;
  mutable Vector tmp_;
};
}  // namespace

SmalseCounters SmalseM::solve(const SymmetricOperator& A, const EqualityProjector& Q, const Vector& c,
                              SeparableSet& omega, Vector& mu, const OuterHook& hook) const {
  const SmalseSettings& s = settings_;
  SmalseCounters counters;
  const auto map = mu.getMap();
  // Scale-free parameters: rho and M relative to ||A||, eta relative to ||c|| (= ||P h||).
  counters.normA = powerMethod(A, *map, s.powerIterations, 1e-4, &counters.operatorApplications);
  const double normC = c.norm2();
  if (normC == 0.0 || counters.normA == 0.0) {
    mu.putScalar(0.0);
    omega.project(mu);
    counters.converged = true;
    return counters;
  }
  double rho = s.rho * counters.normA;
  // ||A_rho|| = max(||PFP||, rho): PFP and rho Q act on the orthogonal spaces Ker G and Im G^T.
  // The power method's estimate is a lower bound: keep the MPGP step safely below 2/||A_rho||.
  double normArho = 1.02 * std::max(counters.normA, rho);
  double M = s.M0 * counters.normA;
  const double eta = s.eta * normC, eps = s.tolerance * normC;
  PenalisedOperator Arho(A, Q, rho, map);
  const Mpgp mpgp(s.mpgp);
  Vector betaT(map), b(map), g(map), Qmu(map);  // betaT = G^T beta (the multiplier as a dual vector)
  betaT.putScalar(0.0);
  double previousL = 0.0, previousGmu = 0.0;
  auto equalityNorm = [&](const Vector& x) {
    Q.applyQ(x, Qmu);
    return Qmu.norm2();
  };
  // ||G mu|| is measured as ||A|| ||Q mu||: the units of g^P and P h, as in the paper's
  // problem scaled to ||PFP|| = 1 (ALGORITHMS.md 4).
  const double normA = counters.normA;
  auto smalseConverged = [&](double gp, double gmu, const Vector& x) {
    if (gp > eps) return false;
    if (s.equalityTest == "Paper") return gmu <= s.tolerance * s.M0 * x.norm2();
    return normA * gmu <= eps;
  };

  omega.project(mu);
  for (int k = 0; k < s.maxOuterIterations; ++k) {
    // Step 1: mu^k ~ argmin L_rho(mu, beta^k) over Omega with ||g^P|| <= min(M_k ||G mu||, eta)
    // (or the final accuracy reached).
    b.update(1.0, c, -1.0, betaT, 0.0);
    // The inner bound never drops below a tenth of the final accuracy: M_k may shrink
    // without limit when the slip bound moves (the Lagrangian is then not monotone), and
    // an inner target under round-off would never be met.
    const auto inner = mpgp.solve(Arho, b, omega, normArho, mu, g, [&](double gp, const Vector& x) {
      const double gmu = equalityNorm(x);
      return gp <= std::max(std::min(M * gmu, eta), s.innerFloor * eps) || smalseConverged(gp, gmu, x);
    });
    counters.outerIterations = k + 1;
    counters.innerIterations += inner.iterations;
    counters.cgSteps += inner.cgSteps;
    counters.expansionSteps += inner.expansionSteps;
    counters.proportioningSteps += inner.proportioningSteps;
    counters.operatorApplications += inner.operatorApplications;
    const double gp = inner.projectedGradientNorm;
    const double gmu = equalityNorm(mu);
    counters.projectedGradient = gp / normC;
    counters.equalityResidual = normA * gmu / normC;
    // L_rho(mu, beta) = 1/2 mu^T A_rho mu - b^T mu = 1/2 mu^T (g - b) with g = A_rho mu - b.
    Vector gMinusB(map);
    gMinusB.update(1.0, g, -1.0, b, 0.0);
    const double L = 0.5 * mu.dot(gMinusB);
    const bool done = smalseConverged(gp, gmu, mu);

    // Step 3: beta^{k+1} = beta^k + rho G mu^k, kept as G^T beta (+= rho Q mu).
    if (!done) betaT.update(rho, Qmu, 1.0);
    // Step 4: M_{k+1} = betaM M_k when the Lagrangian did not grow enough.
    if (k > 0 && L < previousL + 0.5 * rho * gmu * gmu) M *= s.betaM;
    previousL = L;
    // Optional penalty growth when ||G mu|| decreased by less than the target ratio.
    if (s.rhoGrowth > 1.0 && k > 0 && gmu > s.rhoTargetRatio * previousGmu) {
      rho *= s.rhoGrowth;
      normArho = 1.02 * std::max(counters.normA, rho);
      Arho.setRho(rho);
    }
    previousGmu = gmu;
    if (s.monitor)
      s.monitor({k + 1, inner.iterations, gp / normC, normA * gmu / normC, M / normA, counters.operatorApplications});
    // Coulomb: the slip bound update (inexact successive approximations) may veto the stop.
    const bool veto = hook ? hook(k, mu, gp / normC, normA * gmu / normC, M / normA) : false;
    if (done && !veto) {
      counters.converged = true;
      break;
    }
  }
  return counters;
}

}  // namespace tribos::qp
