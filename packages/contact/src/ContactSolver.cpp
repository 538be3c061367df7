#include "tribos/contact/ContactSolver.hpp"
#include "tribos/contact/FixedPointWatch.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "tribos/core/Errors.hpp"
#include "tribos/core/ReproducibleSum.hpp"

namespace tribos::contact {

namespace {
using feti::DualVector;

/// A = P F P: one F application per product (what the paper counts as n_PFP). P F P x is
/// applyPF(P x): two projections, and F without the kernel projections of K^dagger (P x is in
/// Ker G). A_rho = A + rho Q reuses P x for Q x = x - P x (ProjectedOperator).
class ProjectedDualOperator : public qp::ProjectedOperator {
 public:
  explicit ProjectedDualOperator(const feti::TotalFeti& feti) : feti_(feti), tmp_(feti.createDualVector()) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override {
    feti_.project(x, *tmp_);
    feti_.applyPF(*tmp_, y);
  }
  void applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s) const override {
    apply(x, y);
    y.update(s, x, -s, *tmp_, 1.0);  // + s (x - P x)
  }

 private:
  const feti::TotalFeti& feti_;
  Teuchos::RCP<DualVector> tmp_;  ///< P x of the last product
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
  void applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s) const override {
    apply(x, y);
    y.update(s, x, -s, *tmp_, 1.0);  // + s (x - P x)
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
  /// ||Q x||^2 = x^T Q x = (G x)^T (G G^T)^{-1} G x: G and the coarse solve, no G^T pass
  /// (neither when x was projected recently: TotalFeti::coarseCoordinates).
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

/// The contact nodes whose rows this rank owns, with local row indices.
struct LocalContact {
  std::vector<int> node;                    ///< index into B.contact
  std::vector<LO> normalRow;                ///< local index of N_r
  std::vector<std::array<LO, 2>> tangentialRow;  ///< local indices of T1_r, T2_r (-1: absent)
  /// Multiplier of T_j per unit multiplier of N_r at equal physical force: rowScale_N /
  /// rowScale_Tj (rows are scaled to unit norm separately; 1 unless prescribed components
  /// were dropped from some rows).
  std::vector<std::array<double, 2>> axisScale;
  std::vector<int> ellipse;                 ///< index of the node's friction block, -1 if none
};

LocalContact localContact(const feti::ConstraintMatrix& B, int rank) {
  LocalContact lc;
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  for (size_t i = 0; i < B.contact.size(); ++i) {
    const auto& c = B.contact[i];
    if (c.normalRow < first || c.normalRow >= end) continue;
    lc.node.push_back(static_cast<int>(i));
    lc.normalRow.push_back(static_cast<LO>(c.normalRow - first));
    std::array<LO, 2> t{-1, -1};
    std::array<double, 2> s{1.0, 1.0};
    for (int j = 0; j < 2; ++j)
      if (c.hasTangential[j]) {
        t[j] = static_cast<LO>(c.tangentialRow(j) - first);
        s[j] = c.rowScale / c.tangentialScale[j];
      }
    lc.tangentialRow.push_back(t);
    lc.axisScale.push_back(s);
    lc.ellipse.push_back(-1);
  }
  return lc;
}

/// Where lambda_t of one node stands against its friction bound g (N-multiplier units):
/// semi-axes a_j = F_j axisScale_j g on the present tangential rows.
struct FrictionState {
  bool degenerate = false;  ///< a present axis has a = 0: the node slides freely along it
  double normalised = 0.0;  ///< ||diag(1/a) lambda_t|| over the non-degenerate axes
  double excess = 0.0;      ///< max(||F^-1 lambda_t|| - g, 0) + |lambda_t| on zero axes (N units)
  std::array<double, 2> axes{0.0, 0.0};
};

FrictionState frictionState(const std::array<double, 2>& lambdaT, const std::array<LO, 2>& rows,
                            const std::array<double, 2>& axisScale, const std::array<double, 2>& F, double g,
                            double tinyForce) {
  FrictionState s;
  double scaled2 = 0.0, unitBound2 = 0.0;
  for (int j = 0; j < 2; ++j) {
    if (rows[j] < 0) continue;
    s.axes[j] = F[j] * axisScale[j] * g;
    if (!(s.axes[j] > tinyForce)) {
      s.degenerate = true;
      s.excess += std::abs(lambdaT[j]) / axisScale[j];
      continue;
    }
    scaled2 += (lambdaT[j] / s.axes[j]) * (lambdaT[j] / s.axes[j]);
    unitBound2 += (lambdaT[j] / (F[j] * axisScale[j])) * (lambdaT[j] / (F[j] * axisScale[j]));
  }
  s.normalised = std::sqrt(scaled2);
  s.excess += std::max(std::sqrt(unitBound2) - g, 0.0);
  return s;
}

// The sum of every rank's terms, the same bits on any layout (core/ReproducibleSum.hpp);
// `count` bounds the number of terms over all ranks and is the same on every rank.
double globalSum(const Teuchos::Comm<int>& comm, const std::vector<double>& terms, long long count) {
  return core::reproducibleSum(&comm, terms.data(), terms.size(), count);
}
double globalMax(const Teuchos::Comm<int>& comm, double v) {
  double out = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &v, &out);
  return out;
}

struct FixedPointDiverged {
  std::string message;
};
}  // namespace

ContactResult solveContact(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                           const FrictionSettings& friction, const qp::SmalseSettings& smalseSettings,
                           const std::string& preconditioner) {
  const auto& comm = *feti.comm();
  const int rank = comm.getRank();
  const bool frictional = friction.model != "None";
  if (friction.model != "None" && friction.model != "Tresca" && friction.model != "Coulomb")
    throw core::InputError("Contact/Friction Model: \"" + friction.model +
                           "\" is not a contact model (None, Tresca, Coulomb)");
  ContactResult result;
  LocalContact lc = localContact(B, rank);  // its ellipse indices are set below
  const auto& lambdaIm = feti.lambdaIm();
  const auto lIm = lambdaIm.getLocalViewHost(Tpetra::Access::ReadOnly);

  // (1) The homogenised dual problem (paper (19)): c = P h, h = d~ - F lambda_Im.
  auto c = feti.createDualVector();
  feti.applyF(lambdaIm, *c);
  c->update(1.0, feti.dTilde(), -1.0);
  // Exactly: a single-precision coarse factor leaves about its relative error times h's part
  // in Im G^T in c, and that part is not bounded by c's (the loads' rigid-body part; on the
  // bricks ||h|| / ||P h|| is below 3, elsewhere it need not be). One exact solve.
  feti.projectExactly(*c, *c);

  // (2) Omega: mu_nu >= -lambda_Im,nu; ||F^-1 (mu_t + lambda_Im,t)|| <= g (an ellipse with
  // semi-axes F_j g centred at -lambda_Im,t). g lives in multiplier units: a nodal force f
  // corresponds to the multiplier f / rowScale (rows of B are scaled to unit norm).
  qp::SeparableSet omega;
  const std::array<double, 2> F{friction.F1, friction.F2};
  std::vector<double> slip(lc.node.size(), 0.0);  // g per local contact node (N-multiplier units)
  auto semiAxes = [&](size_t k, double g) {
    return std::array<double, 2>{F[0] * lc.axisScale[k][0] * g, F[1] * lc.axisScale[k][1] * g};
  };
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const LO r = lc.normalRow[k];
    omega.addBound(r, -lIm(r, 0));
    const auto& t = lc.tangentialRow[k];
    if (!frictional || (t[0] < 0 && t[1] < 0)) continue;
    if (friction.model == "Tresca") slip[k] = friction.slipBound / B.contact[lc.node[k]].rowScale;
    lc.ellipse[k] = omega.numEllipses();
    omega.addEllipse(t, {t[0] >= 0 ? -lIm(t[0], 0) : 0.0, t[1] >= 0 ? -lIm(t[1], 0) : 0.0}, semiAxes(k, slip[k]));
  }
  auto setSlipBounds = [&](const std::vector<double>& g) {
    for (size_t k = 0; k < g.size(); ++k)
      if (lc.ellipse[k] >= 0) omega.setSemiAxes(lc.ellipse[k], semiAxes(k, g[k]));
  };
  // The slip bound the current mu implies: g = max(mu_nu + lambda_Im,nu, 0).
  auto impliedSlip = [&](const qp::Vector& mu) {
    const auto m = mu.getLocalViewHost(Tpetra::Access::ReadOnly);
    std::vector<double> g(lc.node.size());
    for (size_t k = 0; k < g.size(); ++k) g[k] = std::max(m(lc.normalRow[k], 0) + lIm(lc.normalRow[k], 0), 0.0);
    return g;
  };
  // ||g_new - g_old|| / ||g_old|| (global).
  auto relativeChange = [&](const std::vector<double>& gNew, const std::vector<double>& gOld) {
    std::vector<double> dTerms(gNew.size()), nTerms(gNew.size());
    for (size_t k = 0; k < gNew.size(); ++k) {
      dTerms[k] = (gNew[k] - gOld[k]) * (gNew[k] - gOld[k]);
      nTerms[k] = gOld[k] * gOld[k];
    }
    const double d = globalSum(comm, dTerms, B.numRows), n = globalSum(comm, nTerms, B.numRows);
    return n > 0.0 ? std::sqrt(d / n) : (d > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  };

  ProjectedDualOperator A(feti);
  CoarseSpaceProjector Q(feti);
  auto mu = feti.createDualVector();
  mu->putScalar(0.0);
  const double eps = smalseSettings.tolerance;

  // Every KKT residual of the result must be below this for "converged" (step (6)); the
  // status tests use it as their relative tolerance too.
  const double kktTolerance = std::max(100.0 * eps, 1e-8);
  // max over contact nodes of (||F^-1 lambda_t|| - lambda_nu)_+ / max lambda_nu for
  // lambda = current + lambda_Im: how far the multipliers are from Coulomb's law (global).
  auto coulombExcess = [&](const qp::Vector& current) {
    const auto m = current.getLocalViewHost(Tpetra::Access::ReadOnly);
    double excess = 0.0, normalMax = 0.0;
    for (size_t k = 0; k < lc.node.size(); ++k) {
      const double lambdaNu = m(lc.normalRow[k], 0) + lIm(lc.normalRow[k], 0);
      normalMax = std::max(normalMax, std::abs(lambdaNu));
      if (lc.ellipse[k] < 0) continue;
      std::array<double, 2> lambdaT{0.0, 0.0};
      for (int j = 0; j < 2; ++j)
        if (const LO t = lc.tangentialRow[k][j]; t >= 0) lambdaT[j] = m(t, 0) + lIm(t, 0);
      const auto state = frictionState(lambdaT, lc.tangentialRow[k], lc.axisScale[k], F, std::max(lambdaNu, 0.0), 0.0);
      excess = std::max(excess, state.excess);
    }
    normalMax = globalMax(comm, normalMax);
    return normalMax > 0.0 ? globalMax(comm, excess) / normalMax : 0.0;
  };
  long long applicationsBefore = 0;  // products with A of the earlier SMALSE-M runs (exact variant)
  auto accumulate = [&](const qp::SmalseCounters& k) {
    auto& s = result.counters;
    s.outerIterations += k.outerIterations;
    s.innerIterations += k.innerIterations;
    s.cgSteps += k.cgSteps;
    s.expansionSteps += k.expansionSteps;
    s.proportioningSteps += k.proportioningSteps;
    s.operatorApplications += k.operatorApplications;
    s.preconditionerApplications += k.preconditionerApplications;
    s.seconds += k.seconds;
    s.operatorSeconds += k.operatorSeconds;
    s.productSeconds += k.productSeconds;
    s.preconditionerSeconds += k.preconditionerSeconds;
    applicationsBefore = s.operatorApplications;
    s.projectedGradient = k.projectedGradient;
    s.equalityResidual = k.equalityResidual;
    s.normA = k.normA;
    s.converged = k.converged;
    s.nonFinite = s.nonFinite || k.nonFinite;
  };

  // (3) Solve: one SMALSE-M run (None, Tresca, inexact Coulomb) or a sequence (exact Coulomb).
  // The reported products with A include those of the earlier SMALSE-M runs (exact variant).
  auto withEarlierRuns = [&](qp::SmalseProgress p) {
    p.operatorApplications += applicationsBefore;
    return p;
  };
  qp::SmalseSettings settings = smalseSettings;
  if (preconditioner != "None" && preconditioner != "Lumped" && preconditioner != "Dirichlet")
    throw core::InputError("FETI/Preconditioner: \"" + preconditioner + "\" is not a preconditioner (None, Lumped, "
                           "Dirichlet)");
  std::unique_ptr<ProjectedDualPreconditioner> M;
  if (preconditioner != "None") {
    M = std::make_unique<ProjectedDualPreconditioner>(feti, preconditioner == "Dirichlet");
    settings.preconditioner = M.get();
  }
  if (friction.progress)
    settings.monitor = [&](const qp::SmalseProgress& p) {
      friction.progress(withEarlierRuns(p), result.fixedPointChange);
    };
  if (smalseSettings.innerMonitor)
    settings.innerMonitor = [&](const qp::SmalseProgress& p) { smalseSettings.innerMonitor(withEarlierRuns(p)); };
  const qp::SmalseM smalse(settings);
  try {
    if (friction.model == "Coulomb" && friction.fixedPoint == "Inexact") {
      // Inexact successive approximations (20): g := mu_nu + lambda_Im,nu after every outer
      // iteration; SMALSE-M may stop only when g moved by at most eps.
      FixedPointWatch watch(friction.divergenceWindow);
      auto hook = [&](int, const qp::Vector& current, double, double, double) {
        const auto g = impliedSlip(current);
        const double change = relativeChange(g, slip);
        if (std::isnan(change)) {
          watch.diverges(change);
          throw FixedPointDiverged{watch.message()};
        }
        slip = g;
        setSlipBounds(slip);
        ++result.fixedPointIterations;
        result.fixedPointChange = change;
        if (watch.diverges(change)) throw FixedPointDiverged{watch.message()};
        // Stop only where Coulomb's law holds for the current multipliers too: the inner solve
        // kept lambda_t in the ellipse of the previous bound, which the update may have shrunk
        // below it. A safeguard for the final KKT test (step (6)); on the Table 1 cells checked
        // (2x1x1/2, 4x2x2/3, /5, /6) it never vetoed (same counts with and without it).
        // "Paper" leaves out the test on the change (doc/parameters.md, "The slip-bound test"),
        // but not the first update from g = 0 (change infinite): a stop there would return the
        // frictionless solution.
        const bool settled = change <= eps || (friction.slipBoundTest == "Paper" && std::isfinite(change));
        return !settled || coulombExcess(current) > 0.5 * kktTolerance;
      };
      accumulate(smalse.solve(A, Q, *c, omega, *mu, hook));
      result.converged = result.counters.converged;
      result.message = result.converged ? "converged" : "SMALSE-M reached its outer iteration limit";
    } else if (friction.model == "Coulomb") {
      // Exact variant: each Tresca problem to eps, then g := lambda_nu.
      result.converged = false;
      result.message = "the Coulomb fixed point reached its iteration limit";
      double previous = std::numeric_limits<double>::infinity();
      int growing = 0;
      // ||A|| is estimated by the first Tresca solve only: A does not change with the slip
      // bound, and the estimate is deterministic (the same bits again).
      double normA = 0.0;
      for (int it = 0; it < friction.maxFixedPointIterations; ++it) {
        accumulate(smalse.solve(A, Q, *c, omega, *mu, nullptr, normA));
        normA = result.counters.normA;
        if (!result.counters.converged) {
          result.message = "SMALSE-M did not converge on a Tresca problem of the fixed point";
          break;
        }
        const auto g = impliedSlip(*mu);
        const double change = relativeChange(g, slip);
        slip = g;
        setSlipBounds(slip);
        ++result.fixedPointIterations;
        result.fixedPointChange = change;
        if (change <= eps) {
          accumulate(smalse.solve(A, Q, *c, omega, *mu, nullptr, normA));  // final Tresca solve with the converged g
          result.converged = result.counters.converged;
          result.message = result.converged ? "converged" : "SMALSE-M did not converge on the last Tresca problem";
          break;
        }
        growing = change > previous ? growing + 1 : 0;
        previous = change;
        if (growing >= friction.divergenceWindow) {
          result.message = "the Coulomb fixed point diverges";
          break;
        }
      }
    } else {
      accumulate(smalse.solve(A, Q, *c, omega, *mu));
      result.converged = result.counters.converged;
      result.message = result.converged ? "converged" : "SMALSE-M reached its outer iteration limit";
    }
  } catch (const FixedPointDiverged& d) {
    result.converged = false;
    result.message = d.message;
  }
  if (result.counters.nonFinite) {
    result.converged = false;
    result.message = "diverged: non-finite values (NaN or Inf) in the dual iterations; check the loads, the "
                     "materials and Solver parameters for non-finite or extreme values";
  }

  // (4) lambda = mu + lambda_Im; alpha over the rows where the dual constraints are inactive
  // (ALGORITHMS.md 7); u = K^dagger (f - B^T lambda) + R alpha.
  auto lambda = feti.createDualVector();
  lambda->update(1.0, *mu, 1.0, lambdaIm, 0.0);
  const auto lam = lambda->getLocalViewHost(Tpetra::Access::ReadOnly);
  double lambdaNuMax = 0.0;
  for (size_t k = 0; k < lc.node.size(); ++k) lambdaNuMax = std::max(lambdaNuMax, std::abs(lam(lc.normalRow[k], 0)));
  lambdaNuMax = globalMax(comm, lambdaNuMax);
  // The force scale of the status tests: the largest multiplier of any row (gluing and
  // Dirichlet rows carry the internal and reaction forces) or nodal load. It is right when
  // nothing touches: then every lambda_nu is round-off against it.
  const double forceScale =
      std::max({globalMax(comm, lambda->normInf()), feti.loadNormInf(), std::numeric_limits<double>::min()});
  // Relative tolerance of the status tests (which rows are in contact, stick or slip), at most
  // 1e-3: at eps = 1e-2 the KKT tolerance is 1, so every lambda_nu counted as "no force" and
  // no row held the bodies' rigid motions (G_I G_I^T singular, "no equilibrium found" on the
  // Hertz cylinder; doc/measurements/speed_accuracy.md). The acceptance test (6) stays at kktTolerance.
  const double tau = std::min(kktTolerance, 1e-3);
  const double tinyForce = tau * forceScale;
  // The inactive rows of this rank's owned rows only (entry i: row first + i): each rank
  // masks its own rows of G, so no rank needs the n_d-sized mask of all ranks.
  const GO first = B.firstRowOfRank[rank];
  std::vector<char> inactive(B.firstRowOfRank[rank + 1] - first, 0);
  for (GO r = first; r < B.firstRowOfRank[rank + 1]; ++r) {
    const auto kind = B.kind[r];
    if (kind == feti::RowKind::Gluing || kind == feti::RowKind::Dirichlet) inactive[r - first] = 1;
  }
  auto tangential = [&](size_t k) {
    std::array<double, 2> t{0.0, 0.0};
    for (int j = 0; j < 2; ++j)
      if (lc.tangentialRow[k][j] >= 0) t[j] = lam(lc.tangentialRow[k][j], 0);
    return t;
  };
  // The bound of the friction law at node k: Coulomb's is lambda_nu itself, Tresca's the given g.
  auto bound = [&](size_t k) {
    return friction.model == "Coulomb" ? std::max(lam(lc.normalRow[k], 0), 0.0) : slip[k];
  };
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const LO r = lc.normalRow[k];
    if (lam(r, 0) > tinyForce) inactive[r] = 1;
    if (lc.ellipse[k] < 0) continue;
    const auto state = frictionState(tangential(k), lc.tangentialRow[k], lc.axisScale[k], F, slip[k], tinyForce);
    if (!state.degenerate && state.normalised < 1.0 - tau)
      for (LO t : lc.tangentialRow[k])
        if (t >= 0) inactive[t] = 1;
  }
  for (size_t i = 0; i < lam.extent(0); ++i) result.lambda.push_back(lam(i, 0));  // reactions: -lambda_r
  // A body that no constraint active at the end holds leaves G_I G_I^T singular: a load beyond
  // what contact and friction carry (no equilibrium: the iterations stagnate at the cap) or a
  // body free to slide. Reported (exit 3, doc/stability.md); alpha then over all rows, so that
  // the flagged results exist (it was an internal error without output).
  std::vector<double> alpha;
  // The projections are done: G G^T's factor goes before G_I G_I^T's is made, so that a rank
  // never holds two replicated coarse factors (doc/measurements/scalability.md, 4 000 subdomains).
  feti.releaseCoarseFactor();
  try {
    alpha = feti.rigidBodyCoefficients(*lambda, inactive);
  } catch (const feti::RigidMotionsUndetermined&) {
    alpha = feti.rigidBodyCoefficients(*lambda);
    result.converged = false;
    result.note = "no equilibrium found: the constraints active at the end hold no body against some rigid "
                  "motion (G_I G_I^T is singular): the loads may exceed what contact and friction can carry, or a "
                  "body slides freely; the rigid motions of the results are undetermined";
    result.message += "; " + result.note;
  }
  result.displacement = feti.recoverDisplacements(*lambda, alpha);
  result.energy = feti.energy(result.displacement);

  // (5) KKT residuals of the discrete problem and the contact status per node.
  auto Bu = feti.createDualVector();
  feti.applyB(result.displacement, *Bu);
  const auto bu = Bu->getLocalViewHost(Tpetra::Access::ReadOnly);
  double uInf = 0.0;
  for (const auto& us : result.displacement)
    for (double v : us) uInf = std::max(uInf, std::abs(v));
  uInf = globalMax(comm, uInf);
  const double uScale = uInf > 0.0 ? uInf : 1.0;
  const double lScale = std::max(lambdaNuMax, tinyForce);
  std::vector<double> equality, uNorm2;  // terms of the sums
  for (const auto& us : result.displacement)
    for (double v : us) uNorm2.push_back(v * v);
  for (GO r = first; r < B.firstRowOfRank[rank + 1]; ++r)
    if (B.kind[r] == feti::RowKind::Gluing || B.kind[r] == feti::RowKind::Dirichlet) {
      const double residual = bu(r - first, 0) - B.c[r];  // B_E u = c_E (prescribed values)
      equality.push_back(residual * residual);
    }
  KktReport& kkt = result.kkt;
  kkt.equilibrium = feti.equilibriumResidual(*lambda, result.displacement) /
                    std::max(feti.loadNormInf(), std::numeric_limits<double>::min());
  const double uNorm = std::sqrt(globalSum(comm, uNorm2, feti.primalDofs()));
  kkt.equality = std::sqrt(globalSum(comm, equality, B.numRows)) / (uNorm > 0.0 ? uNorm : 1.0);

  double penetration = 0.0, negative = 0.0, admissibility = 0.0, slipRule = 0.0, stickRule = 0.0;
  std::vector<double> complementarity, lambdaNu2;  // terms of the sums
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const auto& node = B.contact[lc.node[k]];
    const LO r = lc.normalRow[k];
    const double gap = bu(r, 0) - B.c[first + r];  // N u - c <= 0
    penetration = std::max(penetration, gap);
    // Multipliers below the status tests' resolution count as zero (the node is out of
    // contact): a round-off lambda_nu ~ 1e-14 over an open gap is no violation, and
    // normalised by its own size it would read as one.
    complementarity.push_back((lam(r, 0) > tinyForce ? lam(r, 0) : 0.0) * gap);
    lambdaNu2.push_back(lam(r, 0) * lam(r, 0));
    negative = std::max(negative, -lam(r, 0));
    ContactNodeResult out;
    out.slaveNode = node.slaveNode;
    out.force[0] = node.rowScale * lam(r, 0);
    out.relativeDisplacement[0] = bu(r, 0) / node.rowScale;
    out.opening = -gap / node.rowScale;
    // In contact without friction the node slides freely: "slip".
    const bool touching = lam(r, 0) > tinyForce;
    ContactStatus status = !touching ? ContactStatus::NoContact
                                     : (lc.ellipse[k] >= 0 ? ContactStatus::Stick : ContactStatus::Slip);
    if (lc.ellipse[k] >= 0) {
      const double g = bound(k);
      out.slipBound = node.rowScale * g;
      const auto lt = tangential(k);
      std::array<double, 2> v{0.0, 0.0};  // tangential slip T u (row-scaled: lambda_t^T v is the power)
      for (int j = 0; j < 2; ++j) {
        const LO t = lc.tangentialRow[k][j];
        if (t < 0) continue;
        out.force[j + 1] = node.tangentialScale[j] * lt[j];
        out.relativeDisplacement[j + 1] = bu(t, 0) / node.tangentialScale[j];
        v[j] = bu(t, 0);
      }
      const auto state = frictionState(lt, lc.tangentialRow[k], lc.axisScale[k], F, g, tinyForce);
      // The law itself, without the status tests' round-off floor (which would count the
      // whole |lambda_t| of a node whose bound is below it).
      admissibility = std::max(admissibility, frictionState(lt, lc.tangentialRow[k], lc.axisScale[k], F, g, 0.0).excess);
      const double vNorm = std::hypot(out.relativeDisplacement[1], out.relativeDisplacement[2]);
      const bool onBoundary = state.degenerate || state.normalised >= 1.0 - tau;
      if (touching && onBoundary && (state.degenerate || vNorm > tau * uScale)) {
        // On the bound and sliding, or free to slide along a zero axis (F_j = 0, g = 0): the
        // frictionless / degenerate-ellipse limits are slip, never 0/0 "stick".
        status = ContactStatus::Slip;
        // Slip rule (maximal dissipation): lambda_t maximises lambda_t^T v over the ellipse,
        // max = ||diag(a) v||; the deficit is in force x displacement units, like the
        // complementarity residual (a direction test alone is noise where v is tiny).
        const double dissipation = lt[0] * v[0] + lt[1] * v[1];
        const double best = std::hypot(state.axes[0] * v[0], state.axes[1] * v[1]);
        slipRule = std::max(slipRule, (best - dissipation) / (lScale * uScale));
      } else if (status == ContactStatus::Stick) {
        stickRule = std::max(stickRule, vNorm / uScale);
      }
    }
    out.status = status;
    result.statusCounts[static_cast<int>(status)]++;
    result.nodes.push_back(out);
  }
  kkt.nonPenetration = std::max(globalMax(comm, penetration), 0.0) / uScale;
  kkt.complementarity = std::abs(globalSum(comm, complementarity, B.numRows)) /
                        (std::max(std::sqrt(globalSum(comm, lambdaNu2, B.numRows)), tinyForce) * uScale);
  kkt.normalSign = globalMax(comm, negative) / lScale;
  kkt.frictionAdmissibility = std::max(globalMax(comm, admissibility), 0.0) / lScale;
  kkt.slipRule = globalMax(comm, slipRule);
  kkt.stickRule = globalMax(comm, stickRule);
  for (int s = 0; s < 3; ++s) {
    int global = 0;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &result.statusCounts[s], &global);
    result.statusCounts[s] = global;
  }
  // (6) "Converged" only if the discrete KKT conditions hold too (to max(100 eps, 1e-8)):
  // SMALSE-M's own tests are on the dual QP.
  result.kktTolerance = kktTolerance;
  if (result.converged) {
    const std::pair<const char*, double> residuals[] = {
        {"equilibrium", kkt.equilibrium},       {"gluing/Dirichlet", kkt.equality},
        {"penetration", kkt.nonPenetration},    {"complementarity", kkt.complementarity},
        {"normal sign", kkt.normalSign},        {"friction admissibility", kkt.frictionAdmissibility},
        {"slip rule", kkt.slipRule},            {"stick rule", kkt.stickRule}};
    for (const auto& [name, value] : residuals)
      if (!(value <= kktTolerance)) {
        result.converged = false;
        std::ostringstream why;
        why << "SMALSE-M converged but the KKT residual \"" << name << "\" = " << value
            << " exceeds max(100 eps, 1e-8) = " << kktTolerance;
        result.message = why.str();
        break;
      }
  }
  return result;
}

}  // namespace tribos::contact
