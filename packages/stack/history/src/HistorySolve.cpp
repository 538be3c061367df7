#include "tribos/stack/HistorySolve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "tribos/stack/GlobalFields.hpp"
#include "tribos/stack/Pretension.hpp"

namespace tribos::stack {

std::array<double, 3> loadSum(const std::vector<std::vector<double>>& f, MPI_Comm comm) {
  std::vector<fem::SubdomainSystem> loaded(f.size());
  for (size_t i = 0; i < f.size(); ++i) loaded[i].f = f[i];
  return totalLoad(loaded, comm);
}

namespace {
/// One solve of the history at `position` (in steps: k - 1 < position <= k), warm from `last`,
/// the multipliers at `reached` (the last converged state's, or those carried from another
/// pairing: HistoryRun::startLambda), scaled to this load factor where every load follows the
/// ramp (exact for a proportional history), the slip bound they imply and its ||PFP||
/// (ALGORITHMS.md 11).
contact::ContactResult solveAt(feti::TotalFeti& feti, const feti::ConstraintMatrix& B, const ContactChain& chain,
                               const LoadHistory& history, const HistoryRun& run, double position, double reached,
                               const contact::ContactResult& last) {
  const auto loads = history.loads(position);
  *chain.load = loadSum(loads, run.comm);
  feti.setRightHandSide(loads, history.constraintValues(position));
  contact::WarmStart warm;
  if (run.warmStart) warm = {last.lambda, last.counters.normA};
  if (run.warmStart && history.proportional() && history.ramp(reached) != 0.0)
    for (double& v : warm.lambda) v *= history.ramp(position) / history.ramp(reached);
  return contact::solveContact(feti, B, chain.friction, chain.smalse, chain.preconditioner, warm);
}

/// Whether the solve's budget (Solver/Max Seconds) is spent: SMALSE-M's stop request, asked
/// between tries and steps too. Collective, as that request is.
bool budgetSpent(const ContactChain& chain) { return chain.smalse.stopRequested && chain.smalse.stopRequested(); }

/// Adds the counts of one solve to its step's record and to the history's totals.
void count(const contact::ContactResult& r, LoadStepRecord& record, qp::SmalseCounters& total, int& fixedPoint) {
  ++record.sectionSolves;
  record.outerIterations += r.counters.outerIterations;
  record.pfpApplications += r.counters.operatorApplications;
  record.fixedPointIterations += r.fixedPointIterations;
  const qp::SmalseCounters& c = r.counters;
  total.outerIterations += c.outerIterations;
  total.innerIterations += c.innerIterations;
  total.cgSteps += c.cgSteps;
  total.expansionSteps += c.expansionSteps;
  total.proportioningSteps += c.proportioningSteps;
  total.operatorApplications += c.operatorApplications;
  total.preconditionerApplications += c.preconditionerApplications;
  total.seconds += c.seconds;
  total.operatorSeconds += c.operatorSeconds;
  total.productSeconds += c.productSeconds;
  total.preconditionerSeconds += c.preconditionerSeconds;
  fixedPoint += r.fixedPointIterations;
}

/// The console line of one try: the step, where it went (a sub-step: its position), the outcome.
/// With pretension sections, each one's force and shortening, and the solves of the try.
void printTry(const LoadHistory& history, int k, double position, const contact::ContactResult& r,
              const std::vector<SectionState>& sections, int solves) {
  char at[64] = "";
  if (position != k) std::snprintf(at, sizeof at, ", cut back to %.6g of the step", position - (k - 1));
  const std::string outcome = r.converged ? "converged" : "NOT CONVERGED (" + r.message + ")";
  std::printf("  load step %d/%d (%s%s): %s, %d outer, %lld PFP; %d no contact, %d stick, %d slip", k,
              history.steps(), history.label(k).c_str(), at, outcome.c_str(),
              r.counters.outerIterations, r.counters.operatorApplications, r.statusCounts[0], r.statusCounts[1],
              r.statusCounts[2]);
  for (const auto& s : sections) std::printf("; %s %.6g at shortening %.6g", s.name.c_str(), s.force, s.shortening);
  if (solves > 1) std::printf(" (%d solves)", solves);
  std::printf("\n");
  std::fflush(stdout);
}
/// Every additive count of the summary is the sum over every try of every step; the
/// residuals, ||A|| and the flags stay the last try's.
void putTotals(const qp::SmalseCounters& total, int fixedPointIterations, contact::ContactResult& result) {
  qp::SmalseCounters& c = result.counters;
  c.outerIterations = total.outerIterations;
  c.innerIterations = total.innerIterations;
  c.cgSteps = total.cgSteps;
  c.expansionSteps = total.expansionSteps;
  c.proportioningSteps = total.proportioningSteps;
  c.operatorApplications = total.operatorApplications;
  c.preconditionerApplications = total.preconditionerApplications;
  c.seconds = total.seconds;
  c.operatorSeconds = total.operatorSeconds;
  c.productSeconds = total.productSeconds;
  c.preconditionerSeconds = total.preconditionerSeconds;
  result.fixedPointIterations = fixedPointIterations;
}
}  // namespace

contact::ContactResult solveLoadHistory(feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                                        const ContactChain& chain, LoadHistory& history, const HistoryRun& run,
                                        int rank, std::vector<LoadStepRecord>& records,
                                        const std::function<void(int, const contact::ContactResult&)>& everyStep) {
  const int steps = run.lastStep > 0 ? run.lastStep : history.steps();
  feti.keepCoarseFactor(true);  // G G^T is the same in every step: factorised once
  contact::ContactResult result, last;  // the last try; the last converged state
  qp::SmalseCounters total;             // the counts over every try
  int fixedPointIterations = 0;
  // A part solved again on a new pairing starts from the multipliers carried to it, which hold
  // the end of run.startLambdaStep (not the state it continues from) until a try converges.
  bool carried = !run.startLambda.empty();
  last.lambda = run.startLambda;
  for (int k = run.firstStep; k <= steps; ++k) {
    LoadStepRecord record{k, history.ramp(k), run.times[static_cast<size_t>(k - 1)], history.label(k),
                          history.factors(k)};
    record.attempts = 0;
    double reached = k - 1;
    int depth = 0;  // the increment is 2^-depth of a step
    for (;;) {
      const double position = std::min(static_cast<double>(k), reached + std::ldexp(1.0, -depth));
      // One try: one solve, or the pretension iterations' solves (Pretension.hpp).
      int solves = 0;
      result = solveWithSectionForces(history, position, last, run.comm, [&](const contact::ContactResult& warm) {
        const double warmAt = carried && &warm == &last ? run.startLambdaStep : reached;
        contact::ContactResult one = solveAt(feti, B, chain, history, run, position, warmAt, warm);
        count(one, record, total, fixedPointIterations);
        return one;
      }, solves);
      ++record.attempts;
      record.sections = sectionStates(history, result.lambda, run.comm);
      if (rank == 0) printTry(history, k, position, result, record.sections, solves);
      if (result.converged) {
        reached = position;
        if (position == k) break;
        history.advance(feti, result.displacement, position);  // a sub-step: remembered, not written
        last = std::move(result);
        carried = false;
      } else if (depth < run.maxCutbacks && !budgetSpent(chain)) {
        ++depth;
        ++record.cutbacks;
      } else {
        break;
      }
    }
    record.converged = result.converged;
    record.reached = reached;
    record.statusCounts = result.statusCounts;
    record.message = result.message;
    record.kkt = result.kkt;
    record.kktTolerance = result.kktTolerance;
    records.push_back(record);
    if (!result.converged || k == steps) break;  // the caller gathers the last step and names a failed one
    if (budgetSpent(chain)) {
      // Steps that each converge at once never reach SMALSE-M's budget test: the history stops
      // here, after a converged step (its results the last; a restart continues from it).
      result.converged = false;
      result.message = "stopped after this step: the budget ran out";
      break;
    }
    everyStep(k, result);
    if (run.stopAfter && run.stopAfter(k)) break;  // step k's state is the history's last
    history.advance(feti, result.displacement, k);
    last = std::move(result);
    carried = false;
  }
  putTotals(total, fixedPointIterations, result);
  feti.keepCoarseFactor(false);
  return result;
}

}  // namespace tribos::stack
