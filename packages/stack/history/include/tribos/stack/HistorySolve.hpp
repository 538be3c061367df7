#pragma once
// Internal to stack/: the steps of a quasi-static load history solved one after another on the
// same operators (LoadHistory gives each step's right-hand side), with step cutback: a step
// that does not converge is retried from the last converged state in halves of the increment.
#include <mpi.h>

#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/qp/SmalseM.hpp"
#include "tribos/stack/SolveResults.hpp"
#include "tribos/stack/LoadHistory.hpp"

namespace tribos::stack {

/// The contact solver's settings, as every solve of a scene takes them.
struct ContactChain {
  contact::FrictionSettings friction;
  qp::SmalseSettings smalse;
  feti::DualPreconditioner preconditioner = feti::DualPreconditioner::None;
  /// The applied load of the state being solved (every rank), which friction.overloaded reads.
  std::shared_ptr<std::array<double, 3>> load = std::make_shared<std::array<double, 3>>();
};

/// How the steps of a history run: their times (Load Steps/Times), warm or cold (Load Steps/Warm
/// Start), the first step (after a restart: the step after the file's last) and the deepest
/// cutback (Load Steps/Max Cutbacks: the smallest increment is 2^-maxCutbacks of a step).
struct HistoryRun {
  MPI_Comm comm;
  const std::vector<double>& times;
  bool warmStart = true;
  int firstStep = 1;
  int maxCutbacks = 0;
  int lastStep = 0;  ///< the last step solved (0: the history's last; ConditionSteps.hpp's parts end before)
  /// Asked after each converged step k before the last, once `everyStep` has its results: true
  /// ends the history there, with step k its last state (a pairing that step changed:
  /// HistoryPairing.cpp). The same answer on every rank.
  std::function<bool(int)> stopAfter;
  /// The multipliers the first try starts from (HistoryPart::startLambda) and the step whose
  /// end they hold; empty: cold, as a history's first step.
  std::vector<double> startLambda;
  int startLambdaStep = 0;
};

/// The sum of the loads `f` (owned subdomains) in x, y, z. Collective.
std::array<double, 3> loadSum(const std::vector<std::vector<double>>& f, MPI_Comm comm);

/// The steps of a load history: each a contact solve with its right-hand side, warm from the
/// last converged state. A step that does not converge is cut back: retried from the last
/// converged state (a step's end, or a sub-step's) at half the increment, at most
/// run.maxCutbacks halvings deep; a converged sub-step is a state of the history (its slip is
/// remembered) but not a result. The history stops at the first step that still fails (its last
/// try returned). One record per step (its tries' counts summed, LoadStepRecord::attempts,
/// cutbacks, reached); `everyStep` gathers the results of each converged step before the last
/// (the caller gathers the last). A spent budget (Solver/Max Seconds) stops the history after
/// the step it ends in, not converged, and is never cut back. The counters are summed over
/// every try of every step. G G^T
/// is factorised once for the whole history (TotalFeti::keepCoarseFactor).
contact::ContactResult solveLoadHistory(feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                                        const ContactChain& chain, LoadHistory& history, const HistoryRun& run,
                                        int rank, std::vector<LoadStepRecord>& records,
                                        const std::function<void(int, const contact::ContactResult&)>& everyStep);

}  // namespace tribos::stack
