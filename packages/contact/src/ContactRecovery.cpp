#include "ContactRecovery.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace tribos::contact {

namespace {
using HostView = decltype(std::declval<const feti::DualVector&>().getLocalViewHost(Tpetra::Access::ReadOnly));

/// lambda_t of local contact node k (0 on absent rows).
std::array<double, 2> tangential(const LocalContact& lc, const HostView& lam, size_t k) {
  std::array<double, 2> t{0.0, 0.0};
  for (int j = 0; j < 2; ++j)
    if (lc.tangentialRow[k][j] >= 0) t[j] = lam(lc.tangentialRow[k][j], 0);
  return t;
}

/// The rows of this rank's owned rows (entry i: row first + i) whose dual constraints are
/// inactive: gluing and Dirichlet rows, the rows of bonded nodes, normal rows in contact,
/// tangential rows inside their ellipse. Each rank masks its own rows of G, so no rank needs the n_d-sized mask.
std::vector<char> inactiveRows(const feti::ConstraintMatrix& B, int rank, const DualContactProblem& problem,
                               const HostView& lam, double tau, double tinyForce) {
  const GO first = B.firstRowOfRank[rank];
  std::vector<char> inactive(B.firstRowOfRank[rank + 1] - first, 0);
  for (GO r = first; r < B.firstRowOfRank[rank + 1]; ++r) {
    const auto kind = B.kind[r];
    if (kind == feti::RowKind::Gluing || kind == feti::RowKind::Dirichlet) inactive[r - first] = 1;
  }
  const auto& lc = problem.contact();
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const LO r = lc.normalRow[k];
    if (lam(r, 0) > tinyForce || tiesSurfaces(lc.model[k])) inactive[r] = 1;
    if (tiesSurfaces(lc.model[k]))
      for (LO t : lc.tangentialRow[k])
        if (t >= 0) inactive[t] = 1;
    if (lc.ellipse[k] < 0) continue;
    const auto state = frictionState(tangential(lc, lam, k), lc.tangentialRow[k], lc.axisScale[k], lc.F[k],
                                     problem.slipBounds()[k], tinyForce);
    if (!state.degenerate && state.normalised < 1.0 - tau)
      for (LO t : lc.tangentialRow[k])
        if (t >= 0) inactive[t] = 1;
  }
  return inactive;
}

/// The sliding nodes' tangential rows as equalities (TotalFeti::RowCombination): at a node
/// that touches and lies on its friction ellipse, the slip is along the ellipse's outer normal
/// at lambda_t (maximal dissipation: v ~ (lambda_1 / a_1^2, lambda_2 / a_2^2) in row units), so
/// its component along the ellipse's tangent vanishes. Nodes with one tangential row, a
/// degenerate ellipse or a vanishing lambda_t give none.
std::vector<feti::TotalFeti::RowCombination> slidingCombinations(const DualContactProblem& problem,
                                                                 const HostView& lam, double tau, double tinyForce) {
  std::vector<feti::TotalFeti::RowCombination> out;
  const auto& lc = problem.contact();
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const auto& t = lc.tangentialRow[k];
    if (lc.ellipse[k] < 0 || t[0] < 0 || t[1] < 0 || !(lam(lc.normalRow[k], 0) > tinyForce)) continue;
    const auto lt = tangential(lc, lam, k);
    const auto state = frictionState(lt, t, lc.axisScale[k], lc.F[k], problem.slipBounds()[k], tinyForce);
    if (state.degenerate || state.normalised < 1.0 - tau || !(std::hypot(lt[0], lt[1]) > tinyForce)) continue;
    const double n0 = lt[0] / (state.axes[0] * state.axes[0]), n1 = lt[1] / (state.axes[1] * state.axes[1]);
    const double length = std::hypot(n0, n1);
    out.push_back({t[0], t[1], -n1 / length, n0 / length});  // the tangent: the normal turned by 90 degrees
  }
  return out;
}
}  // namespace

RecoveredLambda recoverPrimal(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                              const DualContactProblem& problem, const qp::Vector& mu, double kktTolerance,
                              ContactResult& result) {
  const auto& comm = *feti.comm();
  const auto& lc = problem.contact();
  RecoveredLambda out;
  out.lambda = feti.createDualVector();
  out.lambda->update(1.0, mu, 1.0, feti.lambdaIm(), 0.0);
  const auto lam = out.lambda->getLocalViewHost(Tpetra::Access::ReadOnly);
  // The scale of the normal-sign and friction residuals: the contact forces of the inequality
  // rows (a bonded interface's tension would loosen them).
  for (size_t k = 0; k < lc.node.size(); ++k)
    if (!tiesSurfaces(lc.model[k]))
      out.lambdaNuMax = std::max(out.lambdaNuMax, std::abs(lam(lc.normalRow[k], 0)));
  out.lambdaNuMax = globalMax(comm, out.lambdaNuMax);
  // The force scale of the status tests: the largest multiplier of any row (gluing and
  // Dirichlet rows carry the internal and reaction forces) or nodal load. It is right when
  // nothing touches: then every lambda_nu is round-off against it.
  const double forceScale =
      std::max({globalMax(comm, out.lambda->normInf()), feti.loadNormInf(), std::numeric_limits<double>::min()});
  // Relative tolerance of the status tests (which rows are in contact, stick or slip), at most
  // 1e-3: at eps = 1e-2 the KKT tolerance is 1, so every lambda_nu counted as "no force" and
  // no row held the bodies' rigid motions (G_I G_I^T singular, "no equilibrium found" on the
  // Hertz cylinder; doc/measurements/speed_accuracy.md). The acceptance test (6) stays at kktTolerance.
  out.tau = std::min(kktTolerance, 1e-3);
  out.tinyForce = out.tau * forceScale;
  const auto inactive = inactiveRows(B, comm.getRank(), problem, lam, out.tau, out.tinyForce);
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
    alpha = feti.rigidBodyCoefficients(*out.lambda, inactive);
  } catch (const feti::RigidMotionsUndetermined&) {
    // A body that slides everywhere: its sliding rows hold it too (their slip has no component
    // across the friction force's direction). Only then, so that every other solve keeps its bits.
    const auto combinations = slidingCombinations(problem, lam, out.tau, out.tinyForce);
    if (globalMax(comm, static_cast<double>(combinations.size())) > 0.0) try {
        alpha = feti.rigidBodyCoefficients(*out.lambda, inactive, combinations);
      } catch (const feti::RigidMotionsUndetermined&) {
      }
  }
  if (alpha.empty()) {
    alpha = feti.rigidBodyCoefficients(*out.lambda);
    result.converged = false;
    result.note = "no equilibrium found: the constraints active at the end hold no body against some rigid "
                  "motion (G_I G_I^T is singular): the loads may exceed what contact and friction can carry, or a "
                  "body slides freely; the rigid motions of the results are undetermined";
    result.message += "; " + result.note;
  }
  result.displacement = feti.recoverDisplacements(*out.lambda, alpha);
  result.energy = feti.energy(result.displacement);
  return out;
}

namespace {
/// Step (5)'s sums and maxima over this rank's contact nodes, before they are reduced.
struct ContactResiduals {
  double penetration = 0.0, negative = 0.0, admissibility = 0.0, slipRule = 0.0, stickRule = 0.0;
  std::vector<double> complementarity, lambdaNu2;  // terms of the sums
};

/// What the KKT report of one contact node reads.
struct NodeContext {
  const LocalContact& lc;
  const std::vector<double>& c;  ///< c on this rank's rows (TotalFeti::ownedC)
  const std::vector<double>& slip;
  const HostView& lam;
  const HostView& bu;
  double tau, tinyForce, uScale, lScale;
};

/// Tangential forces and relative displacements of contact node k into `out`; returns the
/// tangential slip T u - c (row-scaled: lambda_t^T v is the power), prescribed components
/// included: a row keeps a slave held along its tangent where the master is free (a roller on
/// one body), and the prescribed part lives in c = -scale known (0 without one).
std::array<double, 2> tangentialSlip(const NodeContext& x, const feti::ContactNode& node, size_t k,
                                     const std::array<double, 2>& lt,
                                     ContactNodeResult& out) {
  std::array<double, 2> v{0.0, 0.0};
  for (int j = 0; j < 2; ++j) {
    const LO t = x.lc.tangentialRow[k][j];
    if (t < 0) continue;
    out.force[j + 1] = node.tangentialScale[j] * lt[j];
    v[j] = x.bu(t, 0) - x.c[t];
    out.relativeDisplacement[j + 1] = v[j] / node.tangentialScale[j];
  }
  return v;
}

/// A bonded node (tied: every row an equality): its residuals are those of B u = c, its
/// status "stick".
ContactNodeResult bondedNodeResult(const NodeContext& x, const feti::ContactNode& node, size_t k,
                                   ContactResiduals& res) {
  const LO r = x.lc.normalRow[k];
  const double gap = x.bu(r, 0) - x.c[r];
  res.penetration = std::max(res.penetration, std::abs(gap));
  ContactNodeResult out;
  out.slaveNode = node.slaveNode;
  out.force[0] = node.rowScale * x.lam(r, 0);
  out.relativeDisplacement[0] = x.bu(r, 0) / node.rowScale;
  out.opening = -gap / node.rowScale;
  out.status = ContactStatus::Stick;
  const auto v = tangentialSlip(x, node, k, tangential(x.lc, x.lam, k), out);
  res.stickRule = std::max(res.stickRule, std::hypot(v[0], v[1]) / x.uScale);
  return out;
}

/// Contact node k: its forces, relative displacements, opening and status, and its terms of
/// the contact residuals.
ContactNodeResult contactNodeResult(const NodeContext& x, const feti::ContactNode& node, size_t k,
                                    ContactResiduals& res) {
  const auto& lc = x.lc;
  if (tiesSurfaces(lc.model[k])) return bondedNodeResult(x, node, k, res);
  const LO r = lc.normalRow[k];
  const double gap = x.bu(r, 0) - x.c[r];  // N u - c <= 0
  res.penetration = std::max(res.penetration, gap);
  // Multipliers below the status tests' resolution count as zero (the node is out of
  // contact): a round-off lambda_nu ~ 1e-14 over an open gap is no violation, and
  // normalised by its own size it would read as one.
  res.complementarity.push_back((x.lam(r, 0) > x.tinyForce ? x.lam(r, 0) : 0.0) * gap);
  res.lambdaNu2.push_back(x.lam(r, 0) * x.lam(r, 0));
  res.negative = std::max(res.negative, -x.lam(r, 0));
  ContactNodeResult out;
  out.slaveNode = node.slaveNode;
  out.force[0] = node.rowScale * x.lam(r, 0);
  out.relativeDisplacement[0] = x.bu(r, 0) / node.rowScale;
  out.opening = -gap / node.rowScale;
  // In contact without friction the node slides freely: "slip". A frictional node without
  // tangential rows is held along both tangents on both sides (a symmetry axis): "stick".
  const bool touching = x.lam(r, 0) > x.tinyForce;
  const bool heldAlongTangents = lc.ellipse[k] >= 0 || hasTangentialRows(lc.model[k]);
  out.status = !touching ? ContactStatus::NoContact : (heldAlongTangents ? ContactStatus::Stick : ContactStatus::Slip);
  if (lc.ellipse[k] < 0) return out;
  // The bound of the friction law: Coulomb's is lambda_nu itself, Tresca's the given g.
  const double g = boundFollowsNormalForce(lc.model[k]) ? std::max(x.lam(r, 0), 0.0) : x.slip[k];
  out.slipBound = node.rowScale * g;
  const auto lt = tangential(lc, x.lam, k);
  const auto v = tangentialSlip(x, node, k, lt, out);
  const auto state = frictionState(lt, lc.tangentialRow[k], lc.axisScale[k], lc.F[k], g, x.tinyForce);
  // The law itself, without the status tests' round-off floor (which would count the
  // whole |lambda_t| of a node whose bound is below it).
  res.admissibility =
      std::max(res.admissibility, frictionState(lt, lc.tangentialRow[k], lc.axisScale[k], lc.F[k], g, 0.0).excess);
  const double vNorm = std::hypot(out.relativeDisplacement[1], out.relativeDisplacement[2]);
  const bool onBoundary = state.degenerate || state.normalised >= 1.0 - x.tau;
  if (touching && onBoundary && (state.degenerate || vNorm > x.tau * x.uScale)) {
    // On the bound and sliding, or free to slide along a zero axis (F_j = 0, g = 0): the
    // frictionless / degenerate-ellipse limits are slip, never 0/0 "stick".
    out.status = ContactStatus::Slip;
    // Slip rule (maximal dissipation): lambda_t maximises lambda_t^T v over the ellipse,
    // max = ||diag(a) v||; the deficit is in force x displacement units, like the
    // complementarity residual (a direction test alone is noise where v is tiny).
    const double dissipation = lt[0] * v[0] + lt[1] * v[1];
    const double best = std::hypot(state.axes[0] * v[0], state.axes[1] * v[1]);
    res.slipRule = std::max(res.slipRule, (best - dissipation) / (x.lScale * x.uScale));
  } else if (out.status == ContactStatus::Stick) {
    res.stickRule = std::max(res.stickRule, vNorm / x.uScale);
  }
  return out;
}

/// The displacement scale of the residuals that measure displacements: ||u||_inf over all
/// subdomains, at least ||B K^+ f||_inf (= d~ + c), the jumps the loads alone open between the
/// floating subdomains, which the solver's accuracy is relative to; 1 when both are 0. Without
/// that floor a solution that is zero (a pressed block gripped at its top: the grip carries the
/// load, nothing moves) read its round-off as a relative error of 0.79. Also the equilibrium and
/// equality residuals (the latter over ||u||_2, at least ||B K^+ f||_2).
double equalityResiduals(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B, const feti::DualVector& lambda,
                         const HostView& bu, ContactResult& result) {
  const auto& comm = *feti.comm();
  const int rank = comm.getRank();
  const GO first = B.firstRowOfRank[rank];
  double uInf = 0.0, loadInf = 0.0;
  for (const auto& us : result.displacement)
    for (double v : us) uInf = std::max(uInf, std::abs(v));
  std::vector<double> loadJump2;  // (B K^+ f)_r^2 over the owned rows
  {
    const auto d = feti.dTilde().getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t r = 0; r < feti.ownedC().size(); ++r) {
      const double jump = d(r, 0) + feti.ownedC()[r];
      loadInf = std::max(loadInf, std::abs(jump));
      loadJump2.push_back(jump * jump);
    }
  }
  uInf = std::max(globalMax(comm, uInf), globalMax(comm, loadInf));
  std::vector<double> equality, uNorm2;  // terms of the sums
  for (const auto& us : result.displacement)
    for (double v : us) uNorm2.push_back(v * v);
  for (GO r = first; r < B.firstRowOfRank[rank + 1]; ++r)
    if (B.kind[r] == feti::RowKind::Gluing || B.kind[r] == feti::RowKind::Dirichlet) {
      const double residual = bu(r - first, 0) - feti.ownedC()[r - first];  // B_E u = c_E (prescribed values)
      equality.push_back(residual * residual);
    }
  // Relative to the largest force, applied or constraint (non-zero when only prescribed
  // displacements drive the scene; the load alone would divide by zero).
  double forceScale = 0.0;
  const double equilibrium = feti.equilibriumResidual(lambda, result.displacement, &forceScale);
  result.kkt.equilibrium = forceScale > 0.0 ? equilibrium / forceScale : equilibrium;
  const double uNorm = std::max(std::sqrt(globalSum(comm, uNorm2, feti.primalDofs())),
                                std::sqrt(globalSum(comm, loadJump2, B.numRows)));
  result.kkt.equality = std::sqrt(globalSum(comm, equality, B.numRows)) / (uNorm > 0.0 ? uNorm : 1.0);
  return uInf > 0.0 ? uInf : 1.0;
}
}  // namespace

void reportKkt(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
               const DualContactProblem& problem, const RecoveredLambda& recovered, ContactResult& result) {
  const auto& comm = *feti.comm();
  const auto& lc = problem.contact();
  auto Bu = feti.createDualVector();
  feti.applyB(result.displacement, *Bu);
  const auto bu = Bu->getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto lam = recovered.lambda->getLocalViewHost(Tpetra::Access::ReadOnly);
  const double uScale = equalityResiduals(feti, B, *recovered.lambda, bu, result);
  const double lScale = std::max(recovered.lambdaNuMax, recovered.tinyForce);
  const NodeContext context{lc,    feti.ownedC(),       problem.slipBounds(), lam, bu, recovered.tau,
                            recovered.tinyForce, uScale, lScale};
  ContactResiduals res;
  for (size_t k = 0; k < lc.node.size(); ++k) {
    const auto out = contactNodeResult(context, B.contact[lc.node[k]], k, res);
    result.statusCounts[static_cast<int>(out.status)]++;
    result.nodes.push_back(out);
  }
  KktReport& kkt = result.kkt;
  kkt.nonPenetration = std::max(globalMax(comm, res.penetration), 0.0) / uScale;
  kkt.complementarity = std::abs(globalSum(comm, res.complementarity, B.numRows)) /
                        (std::max(std::sqrt(globalSum(comm, res.lambdaNu2, B.numRows)), recovered.tinyForce) * uScale);
  kkt.normalSign = globalMax(comm, res.negative) / lScale;
  kkt.frictionAdmissibility = std::max(globalMax(comm, res.admissibility), 0.0) / lScale;
  kkt.slipRule = globalMax(comm, res.slipRule);
  kkt.stickRule = globalMax(comm, res.stickRule);
  for (int s = 0; s < 3; ++s) {
    int global = 0;
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, 1, &result.statusCounts[s], &global);
    result.statusCounts[s] = global;
  }
}

void gateOnKkt(double kktTolerance, ContactResult& result) {
  result.kktTolerance = kktTolerance;
  if (!result.converged) return;
  const KktReport& kkt = result.kkt;
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
      return;
    }
}

}  // namespace tribos::contact
