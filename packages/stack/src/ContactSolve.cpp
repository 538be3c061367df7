#include "tribos/stack/ContactSolve.hpp"
#include "tribos/stack/FetiSettings.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <memory>
#include <sstream>

#include "tribos/core/Timer.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/qp/SolverParameters.hpp"
#include "tribos/stack/RootGather.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SolveBudget.hpp"

namespace tribos::stack {

contact::FrictionSettings frictionSettings(const Teuchos::ParameterList& tribos) {
  return readFrictionParameters(tribos.sublist("Contact"));
}

qp::SmalseSettings smalseSettings(const Teuchos::ParameterList& tribos) {
  return qp::readSolverParameters(tribos.sublist("Solver"));
}

std::string describeContactChain(const Teuchos::ParameterList& tribos) {
  const auto& fetiList = tribos.sublist("FETI");
  const auto friction = frictionSettings(tribos);
  const auto smalse = smalseSettings(tribos);
  std::ostringstream chain;
  chain << "T-FETI (" << fetiList.get<std::string>("Factorization") << " K_reg, "
        << fetiList.get<std::string>("Dual Operator") << " F, coarse projector P = I - G^T (G G^T)^-1 G) -> SMALSE-M (eps "
        << smalse.tolerance << ", rho " << smalse.rho << " ||PFP||, M0 " << smalse.M0 << " ||PFP||, eta " << smalse.eta
        << " ||Ph||, beta " << smalse.betaM << ", " << core::nameOf(qp::kEqualityTestNames, smalse.equalityTest)
        << " test) -> MPGP (alpha_bar "
        << smalse.mpgp.stepScale << "/||A||, Gamma " << smalse.mpgp.gamma << ", preconditioned in face: "
        << fetiList.get<std::string>("Preconditioner") << (smalse.mpgp.choppedProportioning ? ", chopped proportioning" : "")
        << ") -> " << core::nameOf(contact::kFrictionModelNames, friction.model);
  if (friction.model == contact::FrictionModel::Coulomb)
    chain << " (" << core::nameOf(contact::kFixedPointNames, friction.fixedPoint) << " successive approximations, F1 "
          << friction.F1 << ", F2 " << friction.F2
          << (friction.fixedPoint == contact::FixedPoint::Inexact
                  ? std::string(", slip-bound test ") + core::nameOf(contact::kSlipBoundTestNames, friction.slipBoundTest)
                  : std::string())
          << ")";
  if (friction.model == contact::FrictionModel::Tresca) chain << " (g = " << friction.slipBound << ", F1 " << friction.F1 << ", F2 "
                                        << friction.F2 << ")";
  return chain.str();
}

namespace {
// Rank 0's view of the solve: the history for the summary, one line per outer iteration
// and, inside a long inner solve, a line whenever `Progress Interval` seconds passed without
// one (a user watching a 2-minute inner solve needs to see that it moves). Set on rank 0
// only, so nothing in here may communicate.
struct ProgressClock {
  core::Stopwatch watch;  ///< from the set-up of the solver stack (factorisation included)
  double lastLine = 0.0;
};

std::function<void(const qp::SmalseProgress&, double)> outerProgress(std::shared_ptr<ProgressClock> clock,
                                                                     bool verbose,
                                                                     std::vector<OuterIterationRecord>& history) {
  return [clock, verbose, &history](const qp::SmalseProgress& p, double slipChange) {
    const double now = clock->watch.seconds();
    const int outer = static_cast<int>(history.size()) + 1;  // counted over every SMALSE-M run
    history.push_back({outer, p.innerIterations, p.projectedGradient, p.equalityResidual, p.M, slipChange,
                       p.operatorApplications, now});
    if (!verbose) return;
    std::printf("  outer %3d  inner %6d  |gP|/|Ph| %.3e  |Gmu|/|Ph| %.3e  M %.2e  dg %.3e  F %7lld  %.2f s\n",
                outer, p.innerIterations, p.projectedGradient, p.equalityResidual, p.M, slipChange,
                p.operatorApplications, now);
    std::fflush(stdout);
    clock->lastLine = now;
  };
}

std::function<void(const qp::SmalseProgress&)> innerProgress(std::shared_ptr<ProgressClock> clock, double interval,
                                                             const std::vector<OuterIterationRecord>& history) {
  return [clock, interval, &history](const qp::SmalseProgress& p) {
    const double now = clock->watch.seconds();
    if (now - clock->lastLine < interval) return;
    std::printf("  outer %3d  in progress: MPGP %6d  |gP|/|Ph| %.3e (inner target %.3e)  |Gmu|/|Ph| %.3e  "
                "F %7lld  %.2f s\n",
                static_cast<int>(history.size()) + 1, p.innerIterations, p.projectedGradient, p.innerTarget,
                p.equalityResidual, p.operatorApplications, now);
    std::fflush(stdout);
    clock->lastLine = now;
  };
}

void attachProgress(const Teuchos::ParameterList& solver, contact::FrictionSettings& friction,
                    qp::SmalseSettings& smalse, std::vector<OuterIterationRecord>& history) {
  const bool verbose = solver.get<bool>("Verbose");
  auto clock = std::make_shared<ProgressClock>();
  friction.progress = outerProgress(clock, verbose, history);
  if (!verbose) return;
  smalse.mpgp.progressEvery = 10;  // a clock read every 10 MPGP iterations costs nothing against F
  smalse.innerMonitor = innerProgress(clock, solver.get<double>("Progress Interval"), history);
}

// What every rank records of the SMALSE-M runs, to say which limit ended a solve that did
// not converge: the outer iteration the last run reached, and the inner solves that ended at
// the MPGP cap.
struct RunRecord {
  int lastOuterIteration = 0;
  int innerSolvesAtCap = 0;
};

void attachRunRecord(std::shared_ptr<RunRecord> runs, int mpgpCap, contact::FrictionSettings& friction) {
  friction.progress = [runs, mpgpCap, print = friction.progress](const qp::SmalseProgress& p, double change) {
    runs->lastOuterIteration = p.outerIteration;
    if (p.innerIterations >= mpgpCap) ++runs->innerSolvesAtCap;
    if (print) print(p, change);
  };
}

std::string relativeResiduals(const qp::SmalseCounters& c, double eps) {
  std::ostringstream text;
  text << "(||g^P||/||Ph|| = " << c.projectedGradient << ", ||G mu||/||Ph|| = " << c.equalityResidual
       << ", epsilon = " << eps << ")";
  return text.str();
}

// A solve that a budget or an iteration cap ended says which one, in the words of its
// parameter (the contact solver's own message says only that a limit was reached). Every
// rank reaches the same message: the counts are global.
void nameTheLimit(const WallClockBudget& budget, const RunRecord& runs, const qp::SmalseSettings& smalse,
                  const contact::FrictionSettings& friction, contact::ContactResult& result) {
  if (result.converged || result.counters.nonFinite) return;
  const bool exact =
      friction.model == contact::FrictionModel::Coulomb && friction.fixedPoint == contact::FixedPoint::Exact;
  std::string message;
  if (budget.ranOut()) {
    message = budget.message();
  } else if (!result.counters.converged && runs.lastOuterIteration >= smalse.maxOuterIterations) {
    message = capMessage("Solver/Max Outer Iterations", smalse.maxOuterIterations,
                         relativeResiduals(result.counters, smalse.tolerance));
  } else if (result.counters.stalled) {
    message = "stopped: ||G mu|| stalled (not halved over Solver/SMALSE-M/stall window = " +
              std::to_string(smalse.stallWindow) + " outer iterations) " +
              relativeResiduals(result.counters, smalse.tolerance);
  } else if (exact && result.counters.converged && result.fixedPointIterations >= friction.maxFixedPointIterations) {
    std::ostringstream detail;
    detail << "(slip bound change " << result.fixedPointChange << ", epsilon = " << smalse.tolerance << ")";
    message = capMessage("Contact/Max Fixed Point Iterations", friction.maxFixedPointIterations, detail.str());
  } else {
    return;  // another reason (divergence, a KKT residual): the contact solver's message says it
  }
  if (runs.innerSolvesAtCap > 0)
    message += "; " + std::to_string(runs.innerSolvesAtCap) + " inner solve(s) ended at Solver/MPGP/max iterations = " +
               std::to_string(smalse.mpgp.maxIterations);
  result.message = result.note.empty() ? message : message + "; " + result.note;
}

/// Where SMALSE-M stalled on the bodies' balance: the friction the interface can carry against
/// the applied load along the contact plane, in the message (every rank the same numbers:
/// the normal force from rank 0, the mean contact normal summed over the ranks' nodes).
void addOverloadNote(const Scene& scene, const feti::ConstraintMatrix& B, const contact::FrictionSettings& friction,
                     MPI_Comm comm, ContactSolveResult& out) {
  if (!out.contact.counters.stalled) return;
  double normalForce = out.totalNormalForce;
  MPI_Bcast(&normalForce, 1, MPI_DOUBLE, 0, comm);
  std::array<double, 3> mine{0.0, 0.0, 0.0}, normal{0.0, 0.0, 0.0};
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  for (const auto& node : B.contact)
    if (B.firstRowOfRank.empty() || (node.normalRow >= B.firstRowOfRank[rank] && node.normalRow < B.firstRowOfRank[rank + 1]))
      for (int c = 0; c < 3; ++c) mine[c] += node.normal[c];
  MPI_Allreduce(mine.data(), normal.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
  const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  if (!(length > 0.0)) return;
  const auto& f = out.appliedLoad;
  const double along = (f[0] * normal[0] + f[1] * normal[1] + f[2] * normal[2]) / length;
  const double total2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
  const double tangential = std::sqrt(std::max(total2 - along * along, 0.0));
  const std::string interface = scene.contact.slaveSideSet + " -> " + scene.contact.masterSideSet;
  std::ostringstream note;
  if (friction.model == contact::FrictionModel::Tresca) {
    // Tresca's bound is the given slip bound per node, not F lambda_nu: no capacity to quote.
    note << "no equilibrium within the contact constraints at " << interface
         << ": the loads may exceed what contact and the given slip bounds (Tresca) can carry";
  } else {
    const double F = friction.model == contact::FrictionModel::None ? 0.0 : std::max(friction.F1, friction.F2);
    const bool beyond = F * normalForce < tangential;
    note << (beyond ? "the loads may exceed what contact and friction can carry at "
                    : "no equilibrium within the contact constraints at ")
         << interface << ": its friction capacity F N = " << F << " x " << normalForce << " = " << F * normalForce
         << (beyond ? " against " : ", more than ") << "an applied load of " << tangential
         << " along the contact plane";
    if (beyond)
      note << " (where contact and friction alone hold the loaded body, reduce that load or raise the friction "
              "coefficient)";
    else if (friction.model == contact::FrictionModel::Coulomb && friction.fixedPoint == contact::FixedPoint::Exact)
      note << " (Contact/Fixed Point = Exact starts frictionless, where a body held by friction alone has no "
              "equilibrium: use Inexact)";
  }
  out.contact.note = out.contact.note.empty() ? note.str() : out.contact.note + "; " + note.str();
  out.contact.message += "; " + note.str();
}

/// Contact fields on the global mesh (rank 0): every contact node's rows belong to one rank,
/// which sends its forces, status and opening; the geometry (gap, normal, master) is in B on
/// every rank.
void gatherContactFields(const Scene& scene, const feti::ConstraintMatrix& B, MPI_Comm comm, ContactSolveResult& out) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const size_t numNodes = static_cast<size_t>(scene.mesh.numNodes());
  constexpr int kPerNode = 5;  // force (nu, t1, t2), status, opening
  Records mine;  // one per contact node of this rank's rows
  mine.width = kPerNode;
  for (const auto& node : out.contact.nodes) {
    const double f[kPerNode] = {node.force[0], node.force[1], node.force[2], static_cast<double>(node.status),
                                node.opening};
    mine.add(node.slaveNode, f);
  }
  const Records gathered = gatherToRoot(mine, comm);
  if (rank != 0) return;
  std::vector<double> all(kPerNode * numNodes, 0.0);
  for (size_t k = 0; k < gathered.size(); ++k)
    std::copy_n(&gathered.values[kPerNode * k], kPerNode, &all[kPerNode * static_cast<size_t>(gathered.index[k])]);
  for (auto* field : {&out.contactNormal, &out.contactT1, &out.contactT2, &out.contactStatus, &out.contactPressure,
                      &out.contactGap, &out.contactOpening, &out.contactNx, &out.contactNy, &out.contactNz,
                      &out.contactMaster})
    field->assign(numNodes, 0.0);
  const auto area = scene.contact.hasContact() ? tributaryArea(scene.mesh, scene.contact.slaveSideSet)
                                               : std::vector<double>(numNodes, 0.0);
  for (const auto& c : B.contact) {
    const size_t g = static_cast<size_t>(c.slaveNode);
    const double* f = all.data() + kPerNode * g;
    out.contactNormal[g] = f[0];
    out.contactT1[g] = f[1];
    out.contactT2[g] = f[2];
    out.contactStatus[g] = f[3];
    out.contactOpening[g] = f[4];
    out.contactPressure[g] = area[g] > 0.0 ? f[0] / area[g] : 0.0;
    out.contactGap[g] = c.gap;
    out.contactNx[g] = c.normal[0];
    out.contactNy[g] = c.normal[1];
    out.contactNz[g] = c.normal[2];
    out.contactMaster[g] = static_cast<double>(c.masterNode + 1);
    out.totalNormalForce += f[0];
    for (int x = 0; x < 3; ++x) out.totalContactForce[x] += f[0] * c.normal[x] + f[1] * c.t1[x] + f[2] * c.t2[x];
  }
}
}  // namespace

ContactSolveResult solveContactScene(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                     const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos,
                                     MPI_Comm comm, core::Stopwatch runStart) {
  ContactSolveResult out;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const auto& fetiList = tribos.sublist("FETI");
  feti::TotalFetiSettings settings = totalFetiSettings(fetiList, false);
  const feti::DualPreconditioner preconditioner = dualPreconditioner(fetiList);
  auto friction = frictionSettings(tribos);
  auto smalse = smalseSettings(tribos);
  const core::Deadline deadline(tribos.sublist("Solver").get<double>("Max Seconds"), runStart);
  settings.deadline = &deadline;
  WallClockBudget budget(deadline, comm);
  smalse.stopRequested = budget.stopRequest();
  if (rank == 0) attachProgress(tribos.sublist("Solver"), friction, smalse, out.history);
  auto runs = std::make_shared<RunRecord>();
  attachRunRecord(runs, smalse.mpgp.maxIterations, friction);
  out.chain = describeContactChain(tribos);
  out.interfaceName = scene.contact.slaveSideSet + " -> " + scene.contact.masterSideSet;

  out.appliedLoad = totalLoad(owned, comm);
  out.appliedLoadMagnitude = loadMagnitude(owned, comm);
  const feti::TotalFeti feti(scene.mesh, scene.decomposition, std::move(owned), B,
                             Teuchos::rcp(new Teuchos::MpiComm<int>(comm)), settings);
  out.factorizationSeconds = feti.factorizationSeconds();
  core::Stopwatch watch;
  out.contact = contact::solveContact(feti, B, friction, smalse, preconditioner);
  out.solveSeconds = watch.seconds();
  nameTheLimit(budget, *runs, smalse, friction, out.contact);
  out.fApplications = feti.fApplications();
  out.profile = feti.profile();
  out.factorNonzeros = feti.factorNonzeros();
  out.bytesPerFApplication = feti.bytesPerFApplication();
  out.displacement = gatherDisplacement(scene, feti.firstOwnedSubdomain(), out.contact.displacement, comm);

  out.reaction = gatherReactions(scene, B, out.contact.lambda, comm);
  gatherContactFields(scene, B, comm, out);
  addOverloadNote(scene, B, friction, comm, out);
  return out;
}

}  // namespace tribos::stack
