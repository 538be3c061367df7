#include "tribos/stack/ContactSolve.hpp"

#include "tribos/feti/CarriedMultipliers.hpp"

#include "PairingUpdate.hpp"
#include "tribos/stack/FetiSettings.hpp"
#include "tribos/stack/PenetrationCheck.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>

#include "tribos/core/Format.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/qp/SolverParameters.hpp"
#include "tribos/stack/RootGather.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SolveBudget.hpp"
#include "tribos/stack/HistorySolve.hpp"
#include "tribos/stack/LoadHistory.hpp"
#include "tribos/stack/Restart.hpp"

namespace tribos::stack {

contact::FrictionSettings frictionSettings(const Scene& scene, const Teuchos::ParameterList& tribos) {
  return readFrictionParameters(scene.contacts, tribos.sublist("Contact"));
}

qp::SmalseSettings smalseSettings(const Teuchos::ParameterList& tribos) {
  return qp::readSolverParameters(tribos.sublist("Solver"));
}

std::string describeContactChain(const Scene& scene, const Teuchos::ParameterList& tribos) {
  const auto& fetiList = tribos.sublist("FETI");
  const auto friction = frictionSettings(scene, tribos);
  const auto smalse = smalseSettings(tribos);
  std::ostringstream chain;
  chain << "T-FETI (" << fetiList.get<std::string>("Factorization") << " K_reg, "
        << fetiList.get<std::string>("Dual Operator") << " F, coarse projector P = I - G^T (G G^T)^-1 G) -> SMALSE-M (eps "
        << smalse.tolerance << ", rho " << smalse.rho << " ||PFP||, M0 " << smalse.M0 << " ||PFP||, eta " << smalse.eta
        << " ||Ph||, beta " << smalse.betaM << ", " << core::nameOf(qp::kEqualityTestNames, smalse.equalityTest)
        << " test) -> MPGP (alpha_bar "
        << smalse.mpgp.stepScale << "/||A||, Gamma " << smalse.mpgp.gamma << ", preconditioned in face: "
        << fetiList.get<std::string>("Preconditioner") << (smalse.mpgp.choppedProportioning ? ", chopped proportioning" : "")
        << ") -> ";
  const auto& interfaces = scene.contacts;
  for (size_t i = 0; i < friction.laws.size(); ++i) {
    const auto& law = friction.laws[i];
    chain << (i > 0 ? "; " : "") << (interfaces.size() > 1 ? interfaces[i].rows.list() + ": " : std::string())
          << core::nameOf(contact::kFrictionModelNames, law.model);
    if (law.boundFollowsNormalForce())
      chain << " (" << core::nameOf(contact::kFixedPointNames, friction.fixedPoint) << " successive approximations, F1 "
            << law.F1 << ", F2 " << law.F2
            << (friction.fixedPoint == contact::FixedPoint::Inexact
                    ? std::string(", slip-bound test ") +
                          core::nameOf(contact::kSlipBoundTestNames, friction.slipBoundTest)
                    : std::string())
            << ")";
    if (law.boundIsGiven())
      chain << " (g = " << law.slipBound << ", F1 " << law.F1 << ", F2 " << law.F2 << ")";
  }
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
  const bool exact = friction.successiveApproximations() && friction.fixedPoint == contact::FixedPoint::Exact;
  std::string message;
  if (budget.ranOut()) {
    message = budget.message();
  } else if (result.fixedPointDiverged) {
    return;  // the contact solver's message says it, the capacity note follows (addOverloadNote)
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

/// The length of the load f's part along a contact plane of (mean) normal `normal`.
double alongContactPlane(const std::array<double, 3>& normal, const std::array<double, 3>& f) {
  const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  const double along = length > 0.0 ? (f[0] * normal[0] + f[1] * normal[1] + f[2] * normal[2]) / length : 0.0;
  return std::sqrt(std::max(f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - along * along, 0.0));
}

/// Per interface, the sum of its contact nodes' normals (the mean normal's direction), every
/// rank the same: each rank sums the nodes whose rows it owns. Collective.
std::vector<std::array<double, 3>> interfaceNormals(const feti::ConstraintMatrix& B, MPI_Comm comm) {
  const size_t n = B.interfaces.size();
  std::vector<double> mine(3 * n, 0.0), all(3 * n, 0.0);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  for (const auto& node : B.contact)
    if (B.firstRowOfRank.empty() || (node.normalRow >= B.firstRowOfRank[rank] && node.normalRow < B.firstRowOfRank[rank + 1]))
      for (int c = 0; c < 3; ++c) mine[3 * node.interface + c] += node.normal[c];
  MPI_Allreduce(mine.data(), all.data(), static_cast<int>(3 * n), MPI_DOUBLE, MPI_SUM, comm);
  std::vector<std::array<double, 3>> out(n);
  for (size_t i = 0; i < n; ++i) out[i] = {all[3 * i], all[3 * i + 1], all[3 * i + 2]};
  return out;
}

/// contact::FrictionSettings::overloaded: whether, at the normal forces N of the current
/// iterate, the load `*load` along some interface's contact plane exceeds its friction capacity
/// F N (each interface against the whole load, as addOverloadNote). A given slip bound (Tresca)
/// has no capacity to compare: every stall stops there, as without the test.
std::function<bool(const std::vector<double>&)> overloadTest(const contact::FrictionSettings& friction,
                                                             std::vector<std::array<double, 3>> normals,
                                                             std::shared_ptr<const std::array<double, 3>> load) {
  return [&friction, normals = std::move(normals), load](const std::vector<double>& N) {
    for (size_t i = 0; i < normals.size(); ++i) {
      const auto& law = friction.laws.at(i);
      if (law.boundIsGiven()) return true;
      if (law.tiesSurfaces() || !(std::abs(normals[i][0]) + std::abs(normals[i][1]) + std::abs(normals[i][2]) > 0.0))
        continue;
      if (law.capacityCoefficient() * N.at(i) < alongContactPlane(normals[i], *load)) return true;
    }
    return false;
  };
}

/// The note of one interface of a contact solve that did not converge: the friction it can
/// carry, F N, against the applied load along its contact plane (`normal`: the mean contact
/// normal of its nodes). Only a load beyond the capacity is called an overload; below it the
/// note states both numbers, and why the stop may have come all the same.
std::string overloadNote(const InterfaceResult& i, const contact::FrictionSettings& friction,
                         const std::array<double, 3>& normal, const std::array<double, 3>& f, bool diverged) {
  std::ostringstream note;
  const std::string interface = i.surfaces;
  if (i.law.boundIsGiven()) {
    // Tresca's bound is the given slip bound per node, not F lambda_nu: no capacity to quote.
    note << "no equilibrium within the contact constraints at " << interface
         << ": the loads may exceed what contact and the given slip bounds (Tresca) can carry";
    return note.str();
  }
  const double tangential = alongContactPlane(normal, f);
  const double F = i.law.capacityCoefficient();
  const double N = i.normalForce;
  const bool beyond = F * N < tangential;
  note << (beyond ? "the loads may exceed what contact and friction can carry at " : "at ") << interface
       << ": its friction capacity F N = " << F << " x " << N << " = " << F * N
       << (beyond ? " against " : " exceeds ") << "an applied load of " << tangential << " along the contact plane";
  if (beyond)
    note << " (where contact and friction alone hold the loaded body, reduce that load or raise the friction "
            "coefficient)";
  else if (i.law.boundFollowsNormalForce() && friction.fixedPoint == contact::FixedPoint::Exact)
    note << " (Contact/Fixed Point = Exact starts frictionless, where a body held by friction alone has no "
            "equilibrium: use Inexact)";
  else if (diverged)
    note << " (the friction coefficient may be too large for a unique solution)";
  return note.str();
}

/// Where a contact solve with friction did not converge because SMALSE-M stalled on the
/// bodies' balance or the Coulomb fixed point diverged (not a budget's stop): per interface, the friction it can carry against the applied load along its
/// contact plane, in the message (every rank the same numbers: the normal forces from rank 0,
/// the mean contact normals summed over the ranks' nodes). The whole scene's applied load is
/// compared with each interface: with several interfaces in series, the load passes through each.
void addOverloadNote(const feti::ConstraintMatrix& B, const contact::FrictionSettings& friction, bool budgetStop,
                     MPI_Comm comm, ContactSolveResult& out) {
  const contact::ContactResult& result = out.contact;
  if (result.converged || result.counters.nonFinite || budgetStop) return;
  // The stops of an overload; not an iteration cap (the whole load against each interface means
  // little where supports carry part of it, as on the paper's clamped bricks).
  if (!result.counters.stalled && !result.fixedPointDiverged) return;
  const size_t n = out.interfaces.size();
  std::vector<double> normalForce(n);
  for (size_t i = 0; i < n; ++i) normalForce[i] = out.interfaces[i].normalForce;
  MPI_Bcast(normalForce.data(), static_cast<int>(n), MPI_DOUBLE, 0, comm);
  const auto normals = interfaceNormals(B, comm);
  std::string notes;
  for (size_t i = 0; i < n; ++i) {
    InterfaceResult interface = out.interfaces[i];
    if (interface.law.tiesSurfaces()) continue;  // tied: no capacity to exceed
    interface.normalForce = normalForce[i];
    const std::array<double, 3>& normal = normals[i];
    if (!(std::abs(normal[0]) + std::abs(normal[1]) + std::abs(normal[2]) > 0.0)) continue;
    notes += (notes.empty() ? "" : "; ") +
             overloadNote(interface, friction, normal, out.appliedLoad, result.fixedPointDiverged);
  }
  if (notes.empty()) return;
  if (n > 1) notes += " (each interface compared with the whole applied load, as if the load passed through each)";
  out.contact.note = out.contact.note.empty() ? notes : out.contact.note + "; " + notes;
  out.contact.message += "; " + notes;
}

/// Each named load on its own on the owned subdomains (SubdomainSystem::loadParts), as
/// LoadHistory takes them: [load][owned subdomain].
std::vector<std::vector<std::vector<double>>> namedLoadVectors(std::vector<fem::SubdomainSystem>& owned,
                                                               size_t numLoads) {
  std::vector<std::vector<std::vector<double>>> out(numLoads);
  for (auto& system : owned) {
    for (size_t l = 0; l < numLoads; ++l) out[l].push_back(std::move(system.loadParts.at(l)));
    system.loadParts.clear();
  }
  return out;
}

/// What the results show of the state `result`: displacement, reactions, contact fields (the
/// increments since `before`, a history's totals before this state, or null). Returns, on
/// every rank, the change of the contact status counts that the friction of prescribed slips
/// made (addPrescribedSlipFriction), for the state's counts. Collective over `comm`.
std::array<int, 3> gatherStateResults(const Scene& scene, const feti::ConstraintMatrix& B,
                                      const feti::TotalFeti& feti, const contact::ContactResult& result,
                                      MPI_Comm comm, const ContactFields* before, StepResults& out) {
  out.displacement = gatherDisplacement(scene, feti.firstOwnedSubdomain(), result.displacement, comm);
  out.reaction = gatherReactions(scene, B, feti.eliminatedReactions(result.displacement), result.lambda, comm);
  gatherContactFields(scene, B, result.nodes, comm, out);
  addKinematicSlip(scene, B, out.displacement.value, before, out);
  std::array<int, 3> change = addPrescribedSlipFriction(scene, B, out.displacement.value, before, out.reaction, out);
  MPI_Bcast(change.data(), 3, MPI_INT, 0, comm);
  return change;
}

/// Adds a change of the status counts (gatherStateResults) to `counts`.
void addStatusChange(const std::array<int, 3>& change, std::array<int, 3>& counts) {
  for (int s = 0; s < 3; ++s) counts[s] += change[s];
}

/// The applied load of a state: the sum and the magnitude of the loads `f` (owned subdomains).
void setAppliedLoad(const std::vector<std::vector<double>>& f, MPI_Comm comm, StepResults& out) {
  std::vector<fem::SubdomainSystem> loaded(f.size());
  for (size_t i = 0; i < f.size(); ++i) loaded[i].f = f[i];
  out.appliedLoad = totalLoad(loaded, comm);
  out.appliedLoadMagnitude = loadMagnitude(loaded, comm);
}

}  // namespace

namespace {

/// A load history (Scene::loadHistory) on the factorised operators, from step 1 or after the
/// restart file's last step: each step's record and results (out.steps, out.earlierSteps), the
/// last state's contact result and applied load in `out`. Returns the totals before the last
/// state (accumulated slip, dissipated energy): the last earlier step's, the file's, or none.
/// Where a history solve starts (a restart file's state, or one in memory; none: step 1) and the
/// part it solves (HistoryPart: its last step, when it stops before, the multipliers it starts
/// from).
struct HistorySpan {
  const RestartState& restart;
  const HistoryPart& part;
};

const ContactFields* solveHistory(const ContactRun& contactRun, const feti::ConstraintMatrix& B, feti::TotalFeti& feti,
                                  const ContactChain& chain, LoadHistory& loads, const HistorySpan& span,
                                  ContactSolveResult& out) {
  const Scene& scene = contactRun.scene;
  const Teuchos::ParameterList& stepsList = contactRun.tribos.sublist("Load Steps");
  MPI_Comm comm = contactRun.comm;
  const StepObserver& afterStep = contactRun.afterStep;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const RestartState& restart = span.restart;
  HistoryRun run{comm, scene.stepTimes, stepsList.get<bool>("Warm Start"), 1, stepsList.get<int>("Max Cutbacks"),
                 span.part.lastStep};
  run.startLambda = span.part.startLambda;
  run.startLambdaStep = span.part.startLambdaStep;
  if (!restart.file.empty()) {
    // Warm from the forces of the state it continues from, unless a pairing change carried the
    // multipliers of a later state (HistoryPart::startLambda).
    if (run.startLambda.empty() && !restart.totals.contactNormal.empty()) {
      const ContactFields& t = restart.totals;
      run.startLambda = feti::multipliersFromNodalForces(B, t.contactNormal, t.contactT1, t.contactT2, rank);
      run.startLambdaStep = restart.step;
    }
    loads.restore(B, rank, restart.totals.contactTangentialT1, restart.totals.contactTangentialT2);
    for (size_t p = 0; p < restart.sectionShortening.size(); ++p) loads.setShortening(p, restart.sectionShortening[p]);
    run.firstStep = restart.step + 1;
    out.restartFile = restart.file;
    out.restartStep = restart.step;
  }
  auto previous = [&]() -> const ContactFields* {
    if (!out.earlierSteps.empty()) return &out.earlierSteps.back();
    return restart.file.empty() ? nullptr : &restart.totals;
  };
  auto everyStep = [&](int k, const contact::ContactResult& step) {
    // The steps before the last were taken by the observer (a step the stop rule ends the part
    // at is never followed by another): only the last, which this one continues, is kept.
    if (afterStep) releaseWrittenSteps(out);
    const ContactFields* before = previous();
    StepResults results;
    setAppliedLoad(loads.loads(k), comm, results);
    addStatusChange(gatherStateResults(scene, B, feti, step, comm, before, results), out.steps.back().statusCounts);
    if (before) addEarlierSteps(*before, results);
    out.earlierSteps.push_back(std::move(results));
    if (afterStep) afterStep(out);
  };
  bool stopped = false;
  if (span.part.stopWhen) run.stopAfter = [&](int) { return stopped = span.part.stopWhen(out); };
  out.contact = solveLoadHistory(feti, B, chain, loads, run, rank, out.steps, everyStep);
  // Stopped after step k: its results are the last state's, which the caller gathers (as a last
  // step's are); the totals before it are the step before's.
  if (stopped) out.earlierSteps.pop_back();
  setAppliedLoad(loads.loads(out.steps.back().step), comm, out);  // the last step solved (B2)
  return previous();
}

/// The check after the solve (PenetrationCheck.hpp) on rank 0, which holds the displacement and
/// the side sets; its verdict on every rank: a result with bodies inside each other is not
/// converged (exit 3), whatever the solver said.
void checkPenetration(const Scene& scene, const feti::ConstraintMatrix& B, MPI_Comm comm, ContactSolveResult& out) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string message;
  if (rank == 0) {
    const auto found = penetrationsAfterSolve(scene, B, out.displacement.value);
    if (!found.empty()) message = describe(found.front());
    if (found.size() > 1) message += " (and on " + std::to_string(found.size() - 1) + " more interface(s))";
  }
  int length = static_cast<int>(message.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  message.resize(length);
  MPI_Bcast(message.data(), length, MPI_CHAR, 0, comm);
  out.penetrated = !message.empty();
  if (message.empty() || !out.contact.converged) return;
  out.contact.converged = false;
  out.contact.message = message;
}
}  // namespace

ContactSolveResult solveOnePairing(const ContactRun& contactRun, std::vector<fem::SubdomainSystem> owned,
                                   const feti::ConstraintMatrix& B, const HistoryPart& part) {
  const Scene& scene = contactRun.scene;
  const Teuchos::ParameterList& tribos = contactRun.tribos;
  MPI_Comm comm = contactRun.comm;
  ContactSolveResult out;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const auto& fetiList = tribos.sublist("FETI");
  feti::TotalFetiSettings settings = totalFetiSettings(fetiList, false);
  ContactChain chain{frictionSettings(scene, tribos), smalseSettings(tribos), dualPreconditioner(fetiList)};
  const core::Deadline deadline(tribos.sublist("Solver").get<double>("Max Seconds"), contactRun.runStart);
  settings.deadline = &deadline;
  WallClockBudget budget(deadline, comm);
  chain.smalse.stopRequested = budget.stopRequest();
  if (rank == 0) attachProgress(tribos.sublist("Solver"), chain.friction, chain.smalse, out.history);
  auto runs = std::make_shared<RunRecord>();
  attachRunRecord(runs, chain.smalse.mpgp.maxIterations, chain.friction);
  out.chain = describeContactChain(scene, tribos);

  out.appliedLoad = totalLoad(owned, comm);
  out.appliedLoadMagnitude = loadMagnitude(owned, comm);
  *chain.load = out.appliedLoad;
  chain.friction.overloaded = overloadTest(chain.friction, interfaceNormals(B, comm), chain.load);
  const bool history = scene.loadHistory;  // several steps, or a table on one step too
  const auto& stepsList = tribos.sublist("Load Steps");
  RestartState restart;  // read before the factorisation: a file that cannot serve costs nothing
  if (part.continueFrom)
    restart = *part.continueFrom;
  else if (history && !stepsList.get<std::string>("Restart From").empty())
    restart = readRestartOnRoot(stepsList.get<std::string>("Restart From"), scene, B, comm);
  std::optional<LoadHistory> loads;
  if (history) {
    std::vector<size_t> dofs;
    for (const auto& system : owned) dofs.push_back(system.f.size());
    loads.emplace(B, rank, scene, namedLoadVectors(owned, scene.namedLoads.size()), std::move(dofs));
  }
  feti::TotalFeti feti(scene.mesh, scene.decomposition, std::move(owned), B,
                       Teuchos::rcp(new Teuchos::MpiComm<int>(comm)), settings);
  out.factorizationSeconds = feti.factorizationSeconds();
  core::Stopwatch watch;
  const ContactFields* totalsBefore = nullptr;  // a history's totals before its last state
  if (history)
    totalsBefore = solveHistory(contactRun, B, feti, chain, *loads, {restart, part}, out);
  else  // warm where the multipliers of another pairing were carried to B (PairingUpdate.cpp)
    out.contact = contact::solveContact(feti, B, chain.friction, chain.smalse, chain.preconditioner,
                                        {part.startLambda, 0.0});
  out.solveSeconds = watch.seconds();
  nameTheLimit(budget, *runs, chain.smalse, chain.friction, out.contact);
  if (!out.steps.empty() && !out.contact.converged) {
    const auto& last = out.steps.back();
    std::string cut;
    if (last.cutbacks > 0) {
      std::ostringstream text;
      text << ", after " << last.cutbacks << " cutback(s) (Load Steps/Max Cutbacks = " << stepsList.get<int>("Max Cutbacks")
           << "; the history reached " << last.reached - (last.step - 1) << " of the step)";
      cut = text.str();
    }
    out.contact.message = "load step " + std::to_string(last.step) + " of " + std::to_string(scene.loadSteps) +
                          " (" + last.label + ")" + cut + ": " + out.contact.message;
  }
  out.fApplications = feti.fApplications();
  out.profile = feti.profile();
  out.factorNonzeros = feti.factorNonzeros();
  out.bytesPerFApplication = feti.bytesPerFApplication();
  const auto change = gatherStateResults(scene, B, feti, out.contact, comm, totalsBefore, out);
  addStatusChange(change, out.contact.statusCounts);
  if (!out.steps.empty()) addStatusChange(change, out.steps.back().statusCounts);
  if (totalsBefore) addEarlierSteps(*totalsBefore, out);
  addOverloadNote(B, chain.friction, budget.ranOut(), comm, out);
  checkPenetration(scene, B, comm, out);
  return out;
}

}  // namespace tribos::stack
