#pragma once
/// \file RunReport.hpp
/// What a run reports, built from its results: the JSON summary (DESIGN.md's keys) and the
/// console lines, for the linear and the contact stack alike (SceneSolveResult). Rank 0
/// prints them and writes the summary; nothing here communicates.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "tribos/core/PhaseTimer.hpp"
#include "tribos/stack/Results.hpp"
#include "tribos/stack/SceneSolve.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

namespace tribos::stack {

/// The summary of the set-up: dimensions, counts of the contact search, the set-up's times.
nlohmann::json setupSummary(const Scene& scene, const SetupReport& report, const feti::ConstraintMatrix& B,
                            const std::string& input, bool dryRun);
/// The console lines of the set-up.
std::string setupReport(const std::string& input, const Scene& scene, const SetupReport& report,
                        const feti::ConstraintMatrix& B, double setupSeconds, double constraintSeconds);

/// The solve's part of the summary: the chain, convergence, counts, KKT residuals, times
/// and (contact) the history, statuses and operator profile.
void addSolveSummary(const SceneSolveResult& result, const Teuchos::ParameterList& tribos, nlohmann::json& summary);
/// Step i of a load history as the summary's `steps` lists it (the step's record; its counts,
/// KKT residuals and interfaces from the output registry, OutputRegistry.hpp).
nlohmann::json stepSummary(const ContactSolveResult& c, size_t i);
/// The console lines of the solve.
std::string solveReport(const SceneSolveResult& result);
/// The table of the run's phases (core/PhaseTimer.hpp): one line per phase, indented by its
/// depth, the slowest rank's seconds and the calls.
std::string timingTable(const std::vector<core::PhaseTime>& phases);
/// The phases into the summary's "timers": per phase its path, max_s and min_s over the
/// ranks, calls.
void addTimersToSummary(const std::vector<core::PhaseTime>& phases, nlohmann::json& summary);

/// Stresses, strain energy, reactions and the force balance (rank 0) into the summary.
void addResultsToSummary(const StressResults& stress, const ForceBalance& balance, nlohmann::json& summary);

}  // namespace tribos::stack
