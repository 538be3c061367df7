#include "tribos/stack/ContactSolve.hpp"
#include "tribos/stack/FetiSettings.hpp"

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
#include "LoadHistory.hpp"
#include "Restart.hpp"

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

/// The note of one interface where SMALSE-M stalled: the friction it can carry, F N, against
/// the applied load along its contact plane (`normal`: the mean contact normal of its nodes).
std::string overloadNote(const InterfaceResult& i, const contact::FrictionSettings& friction,
                         const std::array<double, 3>& normal, const std::array<double, 3>& f) {
  std::ostringstream note;
  const std::string interface = i.surfaces;
  if (i.law.boundIsGiven()) {
    // Tresca's bound is the given slip bound per node, not F lambda_nu: no capacity to quote.
    note << "no equilibrium within the contact constraints at " << interface
         << ": the loads may exceed what contact and the given slip bounds (Tresca) can carry";
    return note.str();
  }
  const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  const double along = length > 0.0 ? (f[0] * normal[0] + f[1] * normal[1] + f[2] * normal[2]) / length : 0.0;
  const double tangential = std::sqrt(std::max(f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - along * along, 0.0));
  const double F = i.law.capacityCoefficient();
  const double N = i.normalForce;
  const bool beyond = F * N < tangential;
  note << (beyond ? "the loads may exceed what contact and friction can carry at "
                  : "no equilibrium within the contact constraints at ")
       << interface << ": its friction capacity F N = " << F << " x " << N << " = " << F * N
       << (beyond ? " against " : ", more than ") << "an applied load of " << tangential << " along the contact plane";
  if (beyond)
    note << " (where contact and friction alone hold the loaded body, reduce that load or raise the friction "
            "coefficient)";
  else if (i.law.boundFollowsNormalForce() && friction.fixedPoint == contact::FixedPoint::Exact)
    note << " (Contact/Fixed Point = Exact starts frictionless, where a body held by friction alone has no "
            "equilibrium: use Inexact)";
  return note.str();
}

/// Where SMALSE-M stalled on the bodies' balance: per interface, the friction it can carry
/// against the applied load along its contact plane, in the message (every rank the same
/// numbers: the normal forces from rank 0, the mean contact normals summed over the ranks'
/// nodes). The whole scene's applied load is compared with each interface: with several
/// interfaces in series, the load passes through each.
void addOverloadNote(const feti::ConstraintMatrix& B, const contact::FrictionSettings& friction, MPI_Comm comm,
                     ContactSolveResult& out) {
  if (!out.contact.counters.stalled) return;
  const size_t n = out.interfaces.size();
  std::vector<double> normalForce(n), mine(3 * n, 0.0), normals(3 * n, 0.0);
  for (size_t i = 0; i < n; ++i) normalForce[i] = out.interfaces[i].normalForce;
  MPI_Bcast(normalForce.data(), static_cast<int>(n), MPI_DOUBLE, 0, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  for (const auto& node : B.contact)
    if (B.firstRowOfRank.empty() || (node.normalRow >= B.firstRowOfRank[rank] && node.normalRow < B.firstRowOfRank[rank + 1]))
      for (int c = 0; c < 3; ++c) mine[3 * node.interface + c] += node.normal[c];
  MPI_Allreduce(mine.data(), normals.data(), static_cast<int>(3 * n), MPI_DOUBLE, MPI_SUM, comm);
  std::string notes;
  for (size_t i = 0; i < n; ++i) {
    InterfaceResult interface = out.interfaces[i];
    if (interface.law.tiesSurfaces()) continue;  // tied: no capacity to exceed
    interface.normalForce = normalForce[i];
    const std::array<double, 3> normal{normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]};
    if (!(std::abs(normal[0]) + std::abs(normal[1]) + std::abs(normal[2]) > 0.0)) continue;
    notes += (notes.empty() ? "" : "; ") + overloadNote(interface, friction, normal, out.appliedLoad);
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
/// increments since `before`, a history's totals before this state, or null). Collective over
/// `comm`.
void gatherStateResults(const Scene& scene, const feti::ConstraintMatrix& B, const feti::TotalFeti& feti,
                        const contact::ContactResult& result, MPI_Comm comm, const ContactFields* before,
                        StepResults& out) {
  out.displacement = gatherDisplacement(scene, feti.firstOwnedSubdomain(), result.displacement, comm);
  out.reaction = gatherReactions(scene, B, result.lambda, comm);
  gatherContactFields(scene, B, result.nodes, comm, out);
  addKinematicSlip(scene, B, out.displacement.value, before, out);
}

/// The applied load of a state: the sum and the magnitude of the loads `f` (owned subdomains).
void setAppliedLoad(const std::vector<std::vector<double>>& f, MPI_Comm comm, StepResults& out) {
  std::vector<fem::SubdomainSystem> loaded(f.size());
  for (size_t i = 0; i < f.size(); ++i) loaded[i].f = f[i];
  out.appliedLoad = totalLoad(loaded, comm);
  out.appliedLoadMagnitude = loadMagnitude(loaded, comm);
}

/// The contact solver's settings, as every solve of a scene takes them.
struct ContactChain {
  contact::FrictionSettings friction;
  qp::SmalseSettings smalse;
  feti::DualPreconditioner preconditioner = feti::DualPreconditioner::None;
};

/// How the steps of a history run: their times (Load Steps/Times), warm or cold (Load Steps/Warm
/// Start), and the first step (after a restart: the step after the file's last).
struct HistoryRun {
  const std::vector<double>& times;
  bool warmStart = true;
  int firstStep = 1;
};

/// The steps of a load history (LoadHistory): each a contact solve on the same operators with
/// its right-hand side; the history stops at the first step that does not converge (its result
/// returned). `everyStep` gathers the results of each converged step before the last (the
/// caller gathers the last). The counters are summed over the steps.
contact::ContactResult solveLoadHistory(feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                                        const ContactChain& chain, LoadHistory& history, const HistoryRun& run,
                                        int rank, std::vector<LoadStepRecord>& records,
                                        const std::function<void(int, const contact::ContactResult&)>& everyStep) {
  const int steps = history.steps();
  contact::ContactResult result;
  qp::SmalseCounters total;  // the counts over every step
  int fixedPointIterations = 0;
  for (int k = run.firstStep; k <= steps; ++k) {
    const double factor = history.ramp(k);
    feti.setRightHandSide(history.loads(k), history.constraintValues(k));
    // Warm: the last step's multipliers (scaled to this step's load factor where every load
    // follows the ramp: exact for a proportional history), the slip bound they imply and the
    // last ||PFP|| (ALGORITHMS.md 11).
    contact::WarmStart warm;
    if (run.warmStart) warm = {result.lambda, result.counters.normA};
    if (run.warmStart && history.proportional())
      for (double& v : warm.lambda) v *= factor / history.ramp(k - 1);
    result = contact::solveContact(feti, B, chain.friction, chain.smalse, chain.preconditioner, warm);
    total.outerIterations += result.counters.outerIterations;
    total.innerIterations += result.counters.innerIterations;
    total.operatorApplications += result.counters.operatorApplications;
    total.seconds += result.counters.seconds;
    fixedPointIterations += result.fixedPointIterations;
    records.push_back({k, factor, run.times[static_cast<size_t>(k - 1)], history.label(k), history.factors(k),
                       result.converged, result.counters.outerIterations, result.counters.operatorApplications,
                       result.fixedPointIterations, result.statusCounts, result.message, result.kkt,
                       result.kktTolerance});
    if (rank == 0) {
      std::printf("  load step %d/%d (%s): %s, %d outer, %lld PFP; %d no contact, %d stick, %d slip\n", k, steps,
                  history.label(k).c_str(), result.converged ? "converged" : "NOT CONVERGED",
                  result.counters.outerIterations,
                  result.counters.operatorApplications, result.statusCounts[0], result.statusCounts[1],
                  result.statusCounts[2]);
      std::fflush(stdout);
    }
    if (!result.converged || k == steps) break;  // the caller gathers the last step and names a failed one
    everyStep(k, result);
    history.advance(feti, result.displacement, k);
  }
  result.counters.outerIterations = total.outerIterations;
  result.counters.innerIterations = total.innerIterations;
  result.counters.operatorApplications = total.operatorApplications;
  result.counters.seconds = total.seconds;
  result.fixedPointIterations = fixedPointIterations;
  return result;
}

/// A load history (Scene::loadHistory) on the factorised operators, from step 1 or after the
/// restart file's last step: each step's record and results (out.steps, out.earlierSteps), the
/// last state's contact result and applied load in `out`. Returns the totals before the last
/// state (accumulated slip, dissipated energy): the last earlier step's, the file's, or none.
const ContactFields* solveHistory(const Scene& scene, const feti::ConstraintMatrix& B,
                                  const Teuchos::ParameterList& stepsList, feti::TotalFeti& feti,
                                  const ContactChain& chain, LoadHistory& loads, const RestartState& restart,
                                  MPI_Comm comm, ContactSolveResult& out) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  HistoryRun run{scene.stepTimes, stepsList.get<bool>("Warm Start")};
  if (!restart.file.empty()) {
    loads.restore(B, rank, restart.totals.contactTangentialT1, restart.totals.contactTangentialT2);
    run.firstStep = restart.step + 1;
    out.restartFile = restart.file;
    out.restartStep = restart.step;
  }
  auto previous = [&]() -> const ContactFields* {
    if (!out.earlierSteps.empty()) return &out.earlierSteps.back();
    return restart.file.empty() ? nullptr : &restart.totals;
  };
  auto everyStep = [&](int k, const contact::ContactResult& step) {
    const ContactFields* before = previous();
    StepResults results;
    setAppliedLoad(loads.loads(k), comm, results);
    gatherStateResults(scene, B, feti, step, comm, before, results);
    if (before) addEarlierSteps(*before, results);
    out.earlierSteps.push_back(std::move(results));
  };
  out.contact = solveLoadHistory(feti, B, chain, loads, run, rank, out.steps, everyStep);
  setAppliedLoad(loads.loads(out.steps.back().step), comm, out);  // the last step solved (B2)
  return previous();
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
  ContactChain chain{frictionSettings(scene, tribos), smalseSettings(tribos), dualPreconditioner(fetiList)};
  const core::Deadline deadline(tribos.sublist("Solver").get<double>("Max Seconds"), runStart);
  settings.deadline = &deadline;
  WallClockBudget budget(deadline, comm);
  chain.smalse.stopRequested = budget.stopRequest();
  if (rank == 0) attachProgress(tribos.sublist("Solver"), chain.friction, chain.smalse, out.history);
  auto runs = std::make_shared<RunRecord>();
  attachRunRecord(runs, chain.smalse.mpgp.maxIterations, chain.friction);
  out.chain = describeContactChain(scene, tribos);

  out.appliedLoad = totalLoad(owned, comm);
  out.appliedLoadMagnitude = loadMagnitude(owned, comm);
  const bool history = scene.loadHistory;  // several steps, or a table on one step too
  const auto& stepsList = tribos.sublist("Load Steps");
  RestartState restart;  // read before the factorisation: a file that cannot serve costs nothing
  if (history && !stepsList.get<std::string>("Restart From").empty())
    restart = readRestart(stepsList.get<std::string>("Restart From"), scene, B);
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
    totalsBefore = solveHistory(scene, B, stepsList, feti, chain, *loads, restart, comm, out);
  else
    out.contact = contact::solveContact(feti, B, chain.friction, chain.smalse, chain.preconditioner);
  out.solveSeconds = watch.seconds();
  nameTheLimit(budget, *runs, chain.smalse, chain.friction, out.contact);
  if (!out.steps.empty() && !out.contact.converged) {
    const auto& last = out.steps.back();
    out.contact.message = "load step " + std::to_string(last.step) + " of " + std::to_string(scene.loadSteps) +
                          " (" + last.label + "): " + out.contact.message;
  }
  out.fApplications = feti.fApplications();
  out.profile = feti.profile();
  out.factorNonzeros = feti.factorNonzeros();
  out.bytesPerFApplication = feti.bytesPerFApplication();
  gatherStateResults(scene, B, feti, out.contact, comm, totalsBefore, out);
  if (totalsBefore) addEarlierSteps(*totalsBefore, out);
  addOverloadNote(B, chain.friction, comm, out);
  return out;
}

}  // namespace tribos::stack
