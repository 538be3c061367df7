#include "DualContactProblem.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tribos/core/ReproducibleSum.hpp"
#include "tribos/qp/Reductions.hpp"

namespace tribos::contact {

namespace {
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
}  // namespace

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

double globalSum(const Teuchos::Comm<int>& comm, const std::vector<double>& terms, long long count) {
  return core::reproducibleSum(&comm, terms.data(), terms.size(), count);
}

double globalMax(const Teuchos::Comm<int>& comm, double v) {
  double out = 0.0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, 1, &v, &out);
  return out;
}

DualContactProblem::DualContactProblem(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                                       const FrictionSettings& friction)
    : feti_(feti),
      B_(B),
      comm_(*feti.comm()),
      lc_(localContact(B, feti.comm()->getRank())) {
  for (const auto& node : B.contact)  // every node on every rank: all throw or none
    if (node.interface < 0 || static_cast<size_t>(node.interface) >= friction.laws.size())
      throw std::invalid_argument("tribos::contact: a contact node of interface " + std::to_string(node.interface) +
                                  " but " + std::to_string(friction.laws.size()) + " friction laws");
  buildRightHandSide();
  buildOmega(friction);
  buildStoppingScale();
  const bool mine = std::any_of(lc_.model.begin(), lc_.model.end(), [](FrictionModel m) { return boundFollowsNormalForce(m); });
  coulombNodes_ = globalMax(comm_, mine ? 1.0 : 0.0) > 0.0;
}

// (1) The homogenised dual problem (paper (19)): c = P h, h = d~ - F lambda_Im.
void DualContactProblem::buildRightHandSide() {
  c_ = feti_.createDualVector();
  feti_.applyF(feti_.lambdaIm(), *c_);
  c_->update(1.0, feti_.dTilde(), -1.0);
  // Exactly: a single-precision coarse factor leaves about its relative error times h's part
  // in Im G^T in c, and that part is not bounded by c's (the loads' rigid-body part; on the
  // bricks ||h|| / ||P h|| is below 3, elsewhere it need not be). One exact solve.
  feti_.projectExactly(*c_, *c_);
}

// The scale of epsilon (issue 30). ||P h|| grows with the open gaps d > 0 of the contact rows
// (h = d~ - F lambda_Im, d~ = B K^+ f - c), but a gap that stays open drives nothing: with 1 mm
// gaps next to 0.01 mm displacements, epsilon ||P h|| let the displacements err by 2e-3 at
// epsilon = 1e-5 (doc/stability.md). h_d = h + (rowScale max(d, 0) on the normal rows) keeps the
// loads, the prescribed displacements, the overlaps (d < 0 drives) and bonded rows' gaps. Scenes without an open
// gap keep ||P h|| itself (0 here), bit for bit.
void DualContactProblem::buildStoppingScale() {
  auto open = feti_.createDualVector();
  open->putScalar(0.0);
  double largest = 0.0;
  {
    auto v = open->getLocalViewHost(Tpetra::Access::ReadWrite);
    for (size_t k = 0; k < lc_.node.size(); ++k) {
      if (tiesSurfaces(lc_.model[k])) continue;  // tied: its gap is held, it drives
      const auto& node = B_.contact[lc_.node[k]];
      const double gap = node.rowScale * std::max(node.gap, 0.0);
      v(lc_.normalRow[k], 0) = gap;
      largest = std::max(largest, gap);
    }
  }
  if (!(globalMax(comm_, largest) > 0.0)) return;
  feti_.projectExactly(*open, *open);
  open->update(1.0, *c_, 1.0);
  stoppingScale_ = qp::norm2(*open);  // reproducible: the same bits on any number of ranks
}

// (2) Omega: mu_nu >= -lambda_Im,nu; ||F^-1 (mu_t + lambda_Im,t)|| <= g (an ellipse with
// semi-axes F_j g centred at -lambda_Im,t), each node with the law of its interface; a
// Bonded node's rows stay free (equalities: tied). g lives in multiplier units: a nodal force
// f corresponds to the multiplier f / rowScale (rows of B are scaled to unit norm).
void DualContactProblem::buildOmega(const FrictionSettings& friction) {
  const auto lIm = feti_.lambdaIm().getLocalViewHost(Tpetra::Access::ReadOnly);
  slip_.assign(lc_.node.size(), 0.0);
  for (size_t k = 0; k < lc_.node.size(); ++k) {
    const FrictionLaw& law = friction.laws[B_.contact[lc_.node[k]].interface];
    lc_.model.push_back(law.model);
    lc_.F.push_back({law.F1, law.F2});
    // A node whose slip along t_j is prescribed (feti::ContactNode::slipPrescribed) slides along
    // t_j by the prescribed difference, and Coulomb's force follows the slip: it takes the whole
    // F_j lambda_nu along t_j (added after the solve, stack/ContactFields.hpp), and its free
    // tangential row none. Exact where the node's free slip is small against the prescribed one
    // (a push-out); a step that holds the prescribed difference still leaves that node no friction.
    const auto& prescribedSlip = B_.contact[lc_.node[k]].slipPrescribed;
    for (int j = 0; j < 2; ++j)
      if (prescribedSlip[j] && !prescribedSlip[1 - j]) lc_.F.back()[1 - j] = 0.0;
    if (law.tiesSurfaces()) continue;
    const LO r = lc_.normalRow[k];
    omega_.addBound(r, -lIm(r, 0));
    const auto& t = lc_.tangentialRow[k];
    if (!law.hasTangentialRows() || (t[0] < 0 && t[1] < 0)) continue;
    if (law.boundIsGiven()) slip_[k] = law.slipBound / B_.contact[lc_.node[k]].rowScale;
    lc_.ellipse[k] = omega_.numEllipses();
    omega_.addEllipse(t, {t[0] >= 0 ? -lIm(t[0], 0) : 0.0, t[1] >= 0 ? -lIm(t[1], 0) : 0.0}, semiAxes(k, slip_[k]));
  }
}

std::array<double, 2> DualContactProblem::semiAxes(size_t k, double g) const {
  return {lc_.F[k][0] * lc_.axisScale[k][0] * g, lc_.F[k][1] * lc_.axisScale[k][1] * g};
}

void DualContactProblem::setSlipBounds(const std::vector<double>& g) {
  slip_ = g;
  for (size_t k = 0; k < g.size(); ++k)
    if (lc_.ellipse[k] >= 0) omega_.setSemiAxes(lc_.ellipse[k], semiAxes(k, g[k]));
}

std::vector<double> DualContactProblem::impliedSlip(const qp::Vector& mu) const {
  const auto m = mu.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto lIm = feti_.lambdaIm().getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> g(slip_);
  for (size_t k = 0; k < g.size(); ++k)
    if (boundFollowsNormalForce(lc_.model[k]))
      g[k] = std::max(m(lc_.normalRow[k], 0) + lIm(lc_.normalRow[k], 0), 0.0);
  return g;
}

std::vector<double> DualContactProblem::interfaceNormalForces(const qp::Vector& mu) const {
  const auto m = mu.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto lIm = feti_.lambdaIm().getLocalViewHost(Tpetra::Access::ReadOnly);
  const size_t n = B_.interfaces.size();
  std::vector<double> mine(n, 0.0), out(n, 0.0);
  for (size_t k = 0; k < lc_.node.size(); ++k) {
    const auto& node = B_.contact[lc_.node[k]];
    const LO r = lc_.normalRow[k];
    mine[static_cast<size_t>(node.interface)] += node.rowScale * std::max(m(r, 0) + lIm(r, 0), 0.0);
  }
  if (n > 0) Teuchos::reduceAll(comm_, Teuchos::REDUCE_SUM, static_cast<int>(n), mine.data(), out.data());
  return out;
}

double DualContactProblem::relativeChange(const std::vector<double>& gNew, const std::vector<double>& gOld) const {
  std::vector<double> dTerms(gNew.size(), 0.0), nTerms(gNew.size(), 0.0);
  for (size_t k = 0; k < gNew.size(); ++k) {
    if (!boundFollowsNormalForce(lc_.model[k])) continue;
    dTerms[k] = (gNew[k] - gOld[k]) * (gNew[k] - gOld[k]);
    nTerms[k] = gOld[k] * gOld[k];
  }
  const double d = globalSum(comm_, dTerms, B_.numRows), n = globalSum(comm_, nTerms, B_.numRows);
  return n > 0.0 ? std::sqrt(d / n) : (d > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
}

double DualContactProblem::coulombExcess(const qp::Vector& current) const {
  const auto m = current.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto lIm = feti_.lambdaIm().getLocalViewHost(Tpetra::Access::ReadOnly);
  double excess = 0.0, normalMax = 0.0;
  for (size_t k = 0; k < lc_.node.size(); ++k) {
    if (!boundFollowsNormalForce(lc_.model[k])) continue;
    const double lambdaNu = m(lc_.normalRow[k], 0) + lIm(lc_.normalRow[k], 0);
    normalMax = std::max(normalMax, std::abs(lambdaNu));
    if (lc_.ellipse[k] < 0) continue;
    std::array<double, 2> lambdaT{0.0, 0.0};
    for (int j = 0; j < 2; ++j)
      if (const LO t = lc_.tangentialRow[k][j]; t >= 0) lambdaT[j] = m(t, 0) + lIm(t, 0);
    const auto state =
        frictionState(lambdaT, lc_.tangentialRow[k], lc_.axisScale[k], lc_.F[k], std::max(lambdaNu, 0.0), 0.0);
    excess = std::max(excess, state.excess);
  }
  normalMax = globalMax(comm_, normalMax);
  return normalMax > 0.0 ? globalMax(comm_, excess) / normalMax : 0.0;
}

}  // namespace tribos::contact
