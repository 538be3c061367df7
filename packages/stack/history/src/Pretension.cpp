#include "tribos/stack/Pretension.hpp"

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/core/ReproducibleSum.hpp"

namespace tribos::stack {

double sectionForce(const LoadHistory& history, size_t p, const std::vector<double>& lambda, MPI_Comm comm) {
  std::vector<double> terms;
  for (const auto& [row, scale] : history.sectionRows(p))
    terms.push_back(row < lambda.size() ? -scale * lambda[row] : 0.0);  // a failed solve may hold none
  const Teuchos::MpiComm<int> world(comm);
  return core::reproducibleSum(&world, terms.data(), terms.size(), history.sectionRowCount(p));
}

std::vector<SectionState> sectionStates(const LoadHistory& history, const std::vector<double>& lambda,
                                        MPI_Comm comm) {
  std::vector<SectionState> states;
  for (size_t p = 0; p < history.sections(); ++p)
    states.push_back({history.section(p).name, sectionForce(history, p, lambda, comm), history.shortening(p)});
  return states;
}

namespace {
/// The Force sections acting at `position` (within their steps) and their targets there.
std::vector<std::pair<size_t, double>> forceTargets(const LoadHistory& history, double position) {
  std::vector<std::pair<size_t, double>> targets;
  for (size_t p = 0; p < history.sections(); ++p) {
    const PretensionSection& s = history.section(p);
    if (s.byForce && position <= s.steps + 1e-12) targets.push_back({p, s.target * std::min(position / s.steps, 1.0)});
  }
  return targets;
}

/// Whether every target is met (the solve converged, each force within its tolerance); else the
/// first section that is not, in words.
std::string unmet(const LoadHistory& history, const std::vector<std::pair<size_t, double>>& targets,
                  const std::vector<double>& force) {
  for (size_t i = 0; i < targets.size(); ++i) {
    const PretensionSection& s = history.section(targets[i].first);
    if (std::abs(force[i] - targets[i].second) > s.forceTolerance * s.target)
      return "Pretension/" + s.name + " carries " + core::formatNumber(force[i]) + " of its " +
             core::formatNumber(targets[i].second) + " at shortening " +
             core::formatNumber(history.shortening(targets[i].first));
  }
  return "";
}

/// The next shortening of each section: a secant step on its slope dF/ds, or, where none is
/// known yet, a probe at twice s: F is linear in s where the scene is, nearly so with contact,
/// and a probe as large as s itself measures the slope far above the solver's round-off (a probe
/// of 1e-3 s measured it to 1 %, and the iterations crept: 12 solves to 1e-3 of the force).
void nextShortenings(LoadHistory& history, const std::vector<std::pair<size_t, double>>& targets,
                     const std::vector<double>& force) {
  for (size_t i = 0; i < targets.size(); ++i) {
    const size_t p = targets[i].first;
    const double k = history.slope(p), s = history.shortening(p);
    history.setShortening(p, k > 0.0 ? s + (targets[i].second - force[i]) / k
                                     : s + std::max(std::abs(s), 1e-3 * history.sectionSize(p)));
  }
}
}  // namespace

contact::ContactResult solveWithSectionForces(
    LoadHistory& history, double position, const contact::ContactResult& start, MPI_Comm comm,
    const std::function<contact::ContactResult(const contact::ContactResult& warm)>& solve, int& solves) {
  history.setSectionsAt(position);
  const auto targets = forceTargets(history, position);
  // A section that has neither a shortening nor a slope yet starts from a probe, 1e-3 of its
  // size: at s = 0 a bolt that alone clamps its plates holds nothing, and a plate held by the
  // clamping only would be free (the bolted joint's first solve stopped at 100 outer iterations).
  for (const auto& [p, target] : targets)
    if (history.shortening(p) == 0.0 && history.slope(p) == 0.0)
      history.setShortening(p, 1e-3 * history.sectionSize(p));
  contact::ContactResult result = solve(start);
  solves = 1;
  if (targets.empty()) return result;
  for (;;) {
    std::vector<double> force;
    for (const auto& [p, target] : targets) force.push_back(sectionForce(history, p, result.lambda, comm));
    const std::string missed = unmet(history, targets, force);
    if (!result.converged || missed.empty()) return result;
    if (solves == kMaxSectionSolves) {
      result.converged = false;
      result.message = missed + " after " + std::to_string(solves) + " solves (the pretension iterations' limit)";
      return result;
    }
    std::vector<double> before;
    for (const auto& [p, target] : targets) before.push_back(history.shortening(p));
    nextShortenings(history, targets, force);
    const contact::ContactResult next = solve(result);
    ++solves;
    for (size_t i = 0; i < targets.size(); ++i) {  // the secant's slope, dF/ds
      const size_t p = targets[i].first;
      const double ds = history.shortening(p) - before[i];
      // A last correction (ds below 1e-3 of s) measures the slope mostly in the solver's round-off:
      // the slope of the larger steps stays.
      if (ds != 0.0 && (std::abs(ds) >= 1e-3 * std::abs(history.shortening(p)) || history.slope(p) <= 0.0))
        history.setSlope(p, (sectionForce(history, p, next.lambda, comm) - force[i]) / ds);
    }
    result = next;
  }
}

}  // namespace tribos::stack
