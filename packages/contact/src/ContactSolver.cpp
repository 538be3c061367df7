#include "tribos/contact/ContactSolver.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "tribos/core/Errors.hpp"

namespace tribos::contact {

namespace {
using feti::DualVector;

/// A = P F P: one F application per product (what the paper counts as n_PFP).
class ProjectedDualOperator : public qp::SymmetricOperator {
 public:
  explicit ProjectedDualOperator(const feti::TotalFeti& feti) : feti_(feti), tmp_(feti.createDualVector()) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override {
    feti_.project(x, *tmp_);
    feti_.applyF(*tmp_, y);
    feti_.project(y, y);
  }

 private:
  const feti::TotalFeti& feti_;
  Teuchos::RCP<DualVector> tmp_;
};

/// Q = I - P = G^T (G G^T)^{-1} G.
class CoarseSpaceProjector : public qp::EqualityProjector {
 public:
  explicit CoarseSpaceProjector(const feti::TotalFeti& feti) : feti_(feti) {}
  void applyQ(const qp::Vector& x, qp::Vector& y) const override {
    feti_.project(x, y);
    y.update(1.0, x, -1.0);
  }

 private:
  const feti::TotalFeti& feti_;
};

/// The contact nodes whose rows this rank owns, with local row indices.
struct LocalContact {
  std::vector<int> node;       ///< index into B.contact
  std::vector<LO> normalRow;   ///< local index of N_r (T1 = +1, T2 = +2)
};

LocalContact localContact(const feti::ConstraintMatrix& B, int rank) {
  LocalContact lc;
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  for (size_t i = 0; i < B.contact.size(); ++i)
    if (B.contact[i].normalRow >= first && B.contact[i].normalRow < end) {
      lc.node.push_back(static_cast<int>(i));
      lc.normalRow.push_back(static_cast<LO>(B.contact[i].normalRow - first));
    }
  return lc;
}

double globalSum(const Teuchos::Comm<int>& comm, double v) {
  double out = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &v, &out);
  return out;
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
                           const FrictionSettings& friction, const qp::SmalseSettings& smalseSettings) {
  const auto& comm = *feti.comm();
  const int rank = comm.getRank();
  const bool frictional = friction.model != "None";
  if (friction.model != "None" && friction.model != "Tresca" && friction.model != "Coulomb")
    throw core::InputError("Contact/Friction Model: \"" + friction.model +
                           "\" is not a contact model (None, Tresca, Coulomb)");
  if (frictional && B.count(feti::RowKind::ContactT1) != static_cast<GO>(B.contact.size()))
    throw std::invalid_argument("tribos::contact::solveContact: B has no tangential rows; build it with "
                                "tangentialRows = true for friction");
  ContactResult result;
  const LocalContact lc = localContact(B, rank);
  const auto& lambdaIm = feti.lambdaIm();
  const auto lIm = lambdaIm.getLocalViewHost(Tpetra::Access::ReadOnly);

  // (1) The homogenised dual problem (paper (19)): c = P h, h = d~ - F lambda_Im.
  auto c = feti.createDualVector();
  feti.applyF(lambdaIm, *c);
  c->update(1.0, feti.dTilde(), -1.0);
  feti.project(*c, *c);

  // (2) Omega: mu_nu >= -lambda_Im,nu; ||F^-1 (mu_t + lambda_Im,t)|| <= g (an ellipse with
  // semi-axes F_j g centred at -lambda_Im,t). g lives in multiplier units: a nodal force f
  // corresponds to the multiplier f / rowScale (rows of B are scaled to unit norm).
  qp::SeparableSet omega;
  std::vector<double> slip(lc.node.size(), 0.0);  // g per local contact node (multiplier units)
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const LO r = lc.normalRow[k];
    omega.addBound(r, -lIm(r, 0));
    if (!frictional) continue;
    if (friction.model == "Tresca") slip[k] = friction.slipBound / B.contact[lc.node[k]].rowScale;
    omega.addEllipse({r + 1, r + 2}, {-lIm(r + 1, 0), -lIm(r + 2, 0)},
                     {friction.F1 * slip[k], friction.F2 * slip[k]});
  }
  auto setSlipBounds = [&](const std::vector<double>& g) {
    for (size_t k = 0; k < g.size(); ++k) omega.setSemiAxes(static_cast<int>(k), {friction.F1 * g[k], friction.F2 * g[k]});
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
    double d = 0.0, n = 0.0;
    for (size_t k = 0; k < gNew.size(); ++k) {
      d += (gNew[k] - gOld[k]) * (gNew[k] - gOld[k]);
      n += gOld[k] * gOld[k];
    }
    d = globalSum(comm, d);
    n = globalSum(comm, n);
    return n > 0.0 ? std::sqrt(d / n) : (d > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  };

  ProjectedDualOperator A(feti);
  CoarseSpaceProjector Q(feti);
  auto mu = feti.createDualVector();
  mu->putScalar(0.0);
  const double eps = smalseSettings.tolerance;

  long long applicationsBefore = 0;  // products with A of the earlier SMALSE-M runs (exact variant)
  auto accumulate = [&](const qp::SmalseCounters& k) {
    auto& s = result.counters;
    s.outerIterations += k.outerIterations;
    s.innerIterations += k.innerIterations;
    s.cgSteps += k.cgSteps;
    s.expansionSteps += k.expansionSteps;
    s.proportioningSteps += k.proportioningSteps;
    s.operatorApplications += k.operatorApplications;
    applicationsBefore = s.operatorApplications;
    s.projectedGradient = k.projectedGradient;
    s.equalityResidual = k.equalityResidual;
    s.normA = k.normA;
    s.converged = k.converged;
  };

  // (3) Solve: one SMALSE-M run (None, Tresca, inexact Coulomb) or a sequence (exact Coulomb).
  qp::SmalseSettings settings = smalseSettings;
  if (friction.progress)
    settings.monitor = [&](const qp::SmalseProgress& p) {
      qp::SmalseProgress total = p;
      total.operatorApplications += applicationsBefore;
      friction.progress(total, result.fixedPointChange);
    };
  const qp::SmalseM smalse(settings);
  try {
    if (friction.model == "Coulomb" && friction.fixedPoint == "Inexact") {
      // Inexact successive approximations (20): g := mu_nu + lambda_Im,nu after every outer
      // iteration; SMALSE-M may stop only when g moved by at most eps.
      std::vector<double> changes;
      auto hook = [&](int, const qp::Vector& current, double, double, double) {
        const auto g = impliedSlip(current);
        const double change = relativeChange(g, slip);
        slip = g;
        setSlipBounds(slip);
        ++result.fixedPointIterations;
        result.fixedPointChange = change;
        changes.push_back(change);
        const int w = friction.divergenceWindow;
        if (static_cast<int>(changes.size()) > w + 3) {
          bool growing = true;
          for (int i = 0; i < w; ++i) growing = growing && changes[changes.size() - 1 - i] > changes[changes.size() - 2 - i];
          if (growing)
            throw FixedPointDiverged{"the Coulomb fixed point diverges: the slip bound change grew in " +
                                     std::to_string(w) + " consecutive updates (last " + std::to_string(change) +
                                     "); the friction coefficient may be too large for a unique solution"};
        }
        return change > eps;
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
      for (int it = 0; it < friction.maxFixedPointIterations; ++it) {
        accumulate(smalse.solve(A, Q, *c, omega, *mu));
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
          accumulate(smalse.solve(A, Q, *c, omega, *mu));  // final Tresca solve with the converged g
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

  // (4) lambda = mu + lambda_Im; alpha over the rows where the dual constraints are inactive
  // (ALGORITHMS.md 7); u = K^dagger (f - B^T lambda) + R alpha.
  auto lambda = feti.createDualVector();
  lambda->update(1.0, *mu, 1.0, lambdaIm, 0.0);
  const auto lam = lambda->getLocalViewHost(Tpetra::Access::ReadOnly);
  double lambdaNuMax = 0.0;
  for (size_t k = 0; k < lc.node.size(); ++k) lambdaNuMax = std::max(lambdaNuMax, std::abs(lam(lc.normalRow[k], 0)));
  lambdaNuMax = globalMax(comm, lambdaNuMax);
  const double tau = std::max(100.0 * eps, 1e-8);  // relative tolerance of the status tests
  const GO first = B.firstRowOfRank[rank];
  std::vector<char> inactive(B.numRows, 0);
  for (GO r = first; r < B.firstRowOfRank[rank + 1]; ++r) {
    const auto kind = B.kind[r];
    if (kind == feti::RowKind::Gluing || kind == feti::RowKind::Dirichlet) inactive[r] = 1;
  }
  auto tangentialRatio = [&](size_t k) {  // ||F^-1 lambda_t|| / g, or 0 when g = 0
    const LO r = lc.normalRow[k];
    if (!(slip[k] > 0.0)) return 0.0;
    const double a = lam(r + 1, 0) / friction.F1, b = lam(r + 2, 0) / friction.F2;
    return std::sqrt(a * a + b * b) / slip[k];
  };
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const LO r = lc.normalRow[k];
    if (lam(r, 0) > tau * lambdaNuMax) inactive[first + r] = 1;
    if (frictional && slip[k] > 0.0 && tangentialRatio(k) < 1.0 - tau) {
      inactive[first + r + 1] = 1;
      inactive[first + r + 2] = 1;
    }
  }
  std::vector<char> mask(B.numRows, 0);
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, static_cast<int>(B.numRows), inactive.data(), mask.data());
  const auto alpha = feti.rigidBodyCoefficients(*lambda, mask);
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
  const double lScale = lambdaNuMax > 0.0 ? lambdaNuMax : 1.0;
  double equality = 0.0, uNorm2 = 0.0;
  for (const auto& us : result.displacement)
    for (double v : us) uNorm2 += v * v;
  for (GO r = first; r < B.firstRowOfRank[rank + 1]; ++r)
    if (B.kind[r] == feti::RowKind::Gluing || B.kind[r] == feti::RowKind::Dirichlet)
      equality += bu(r - first, 0) * bu(r - first, 0);
  KktReport& kkt = result.kkt;
  kkt.equilibrium = feti.equilibriumResidual(*lambda, result.displacement) /
                    std::max(feti.loadNormInf(), std::numeric_limits<double>::min());
  const double uNorm = std::sqrt(globalSum(comm, uNorm2));
  kkt.equality = std::sqrt(globalSum(comm, equality)) / (uNorm > 0.0 ? uNorm : 1.0);

  double penetration = 0.0, complementarity = 0.0, lambdaNu2 = 0.0, negative = 0.0, admissibility = 0.0,
         slipRule = 0.0, stickRule = 0.0;
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const auto& node = B.contact[lc.node[k]];
    const LO r = lc.normalRow[k];
    const double gap = bu(r, 0) - B.c[first + r];  // N u - c <= 0
    penetration = std::max(penetration, gap);
    complementarity += lam(r, 0) * gap;
    lambdaNu2 += lam(r, 0) * lam(r, 0);
    negative = std::max(negative, -lam(r, 0));
    ContactNodeResult out;
    out.slaveNode = node.slaveNode;
    out.force[0] = node.rowScale * lam(r, 0);
    out.relativeDisplacement[0] = bu(r, 0) / node.rowScale;
    // In contact without friction the node slides freely: "slip".
    ContactStatus status = lam(r, 0) > tau * lScale ? (frictional ? ContactStatus::Stick : ContactStatus::Slip)
                                                    : ContactStatus::NoContact;
    if (frictional) {
      // Coulomb's law bounds lambda_t by lambda_nu itself; Tresca by the given g.
      const double g = friction.model == "Coulomb" ? std::max(lam(r, 0), 0.0) : slip[k];
      out.slipBound = node.rowScale * g;
      for (int j = 1; j < 3; ++j) {
        out.force[j] = node.rowScale * lam(r + j, 0);
        out.relativeDisplacement[j] = bu(r + j, 0) / node.rowScale;
      }
      const double a = lam(r + 1, 0) / friction.F1, b = lam(r + 2, 0) / friction.F2;
      const double ratio = std::sqrt(a * a + b * b);  // ||F^-1 lambda_t||
      admissibility = std::max(admissibility, ratio - g);
      // Tangential slip v = T u (multiplier scaling drops out of the direction tests).
      const double v1 = bu(r + 1, 0), v2 = bu(r + 2, 0), vNorm = std::hypot(v1, v2);
      const bool onBoundary = g > 0.0 && ratio >= (1.0 - tau) * g;
      if (status != ContactStatus::NoContact && onBoundary && vNorm > tau * uScale) {
        status = ContactStatus::Slip;
        // Slip rule: F^-1 lambda_t parallel to F v, same sense (the maximiser of lambda_t^T v).
        const double fv1 = friction.F1 * v1, fv2 = friction.F2 * v2;
        const double cosine = (a * fv1 + b * fv2) / (ratio * std::hypot(fv1, fv2));
        slipRule = std::max(slipRule, 1.0 - cosine);
      } else if (status == ContactStatus::Stick) {
        stickRule = std::max(stickRule, vNorm / uScale);
      }
    }
    out.status = status;
    result.statusCounts[static_cast<int>(status)]++;
    result.nodes.push_back(out);
  }
  kkt.nonPenetration = std::max(globalMax(comm, penetration), 0.0) / uScale;
  kkt.complementarity = std::abs(globalSum(comm, complementarity)) /
                        (std::sqrt(globalSum(comm, lambdaNu2)) * uScale + std::numeric_limits<double>::min());
  kkt.normalSign = globalMax(comm, negative) / lScale;
  kkt.frictionAdmissibility = std::max(globalMax(comm, admissibility), 0.0) / lScale;
  kkt.slipRule = globalMax(comm, slipRule);
  kkt.stickRule = globalMax(comm, stickRule);
  for (int s = 0; s < 3; ++s) {
    int global = 0;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &result.statusCounts[s], &global);
    result.statusCounts[s] = global;
  }
  return result;
}

}  // namespace tribos::contact
