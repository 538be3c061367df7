#include "tribos/stack/RunReport.hpp"

#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "tribos/stack/OutputRegistry.hpp"

namespace tribos::stack {

namespace {
/// Rank 0's operator counts and times (TotalFeti::profile; doc/measurements/coarse_problem.md).
nlohmann::json profileJson(const feti::OperatorProfile& p) {
  return {{"f_applications", p.fApplications},
          {"projections", p.projections},
          {"coarse_solves", p.coarseSolves},
          {"coarse_coordinates", p.coarseCoordinates},
          {"preconditioner_applications", p.preconditionerApplications},
          {"f_s", p.fSeconds},
          {"g_s", p.gSeconds},
          {"coarse_reduce_s", p.coarseReduceSeconds},
          {"coarse_solve_s", p.coarseSolveSeconds},
          {"preconditioner_s", p.preconditionerSeconds},
          {"coarse_factor_s", p.coarseFactorSeconds},
          {"coarse_factorizations", p.coarseFactorizations},
          {"rigid_coefficients_s", p.rigidCoefficientsSeconds},
          {"coarse_factor_nonzeros", p.coarseFactorNonzeros},
          {"coarse_subtrees", p.coarseSubtrees},
          {"coarse_rank_subtrees", p.coarseRankSubtrees},
          {"coarse_split_depth", p.coarseSplitDepth},
          {"coarse_values_per_solve", p.coarseValuesPerSolve},
          {"coarse_single", p.coarseSingle},
          {"coarse_single_error", p.coarseSingleError},
          {"coarse_refinement_steps", p.coarseRefinementSteps},
          {"coarse_to_f_bytes", p.coarseToFBytes},
          {"g_entries", p.gEntries},
          {"g_rows", p.gRows},
          {"projection_bytes", p.projectionBytes},
          {"preconditioner_bytes", p.preconditionerBytes}};
}

/// The coarse factor's precision when it is not plain double (FETI/Coarse Factor
/// Precision): a progress line for the user, empty otherwise.
std::string coarseFactorLine(const feti::OperatorProfile& p) {
  std::ostringstream line;
  if (p.coarseSingleError > 0.0)
    line << "  coarse factor: "
         << (p.coarseSingle ? "single precision" : "double (the single one was not accurate enough)")
         << ", one solve " << p.coarseSingleError << " from the double one (relative)\n";
  // Measured on the bricks at n = 324 000 (doc/measurements/scalability.md): 4 000 subdomains (ratio 3.8)
  // take 2.3 times as long as 500 (ratio 0.10).
  if (p.coarseToFBytes >= 2.0)
    line << "  note: the coarse problem dominates (two coarse solves read " << std::setprecision(2)
         << p.coarseToFBytes << std::setprecision(6)
         << "x the bytes of an F application's subdomain solves): fewer, larger subdomains would be faster "
            "(doc/measurements/coarse_problem.md)\n";
  return line.str();
}

// One object per SMALSE-M outer iteration: what the progress lines showed.
nlohmann::json historyJson(const std::vector<OuterIterationRecord>& history) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& h : history)
    list.push_back({{"outer", h.outer},
                    {"inner", h.inner},
                    {"projected_gradient", h.projectedGradient},
                    {"equality_residual", h.equalityResidual},
                    {"M", h.M},
                    {"slip_bound_change", h.slipBoundChange},
                    {"pfp_applications", h.pfpApplications},
                    {"elapsed_s", h.elapsedSeconds}});
  return list;
}

// The contact solve's part of the summary.
nlohmann::json factorsJson(const std::vector<std::pair<std::string, double>>& factors) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [name, factor] : factors) out[name] = factor;
  return out;
}

/// Load Steps: one entry per step solved, with its interfaces' resultants (the results of
/// earlierSteps, then of the last state).
nlohmann::json stepsJson(const ContactSolveResult& c) {
  nlohmann::json list = nlohmann::json::array();
  for (size_t i = 0; i < c.steps.size(); ++i) list.push_back(stepSummary(c, i));
  return list;
}

/// The console line of each interface (interfaceSummary's numbers).
std::string interfaceLine(const ContactFields& c) {
  std::ostringstream line;
  for (const auto& i : interfaceSummary(c.interfaces))
    line << "  interface " << (i["name"].get<std::string>().empty() ? "" : i["name"].get<std::string>() + " ")
         << i["interface"].get<std::string>() << ": " << i["no_contact"].get<int>() << " no contact, "
         << i["stick"].get<int>() << " stick, " << i["slip"].get<int>() << " slip, normal force " << i["normal_force"].get<double>()
         << ", friction force " << i["friction_force"].get<double>() << ", peak pressure "
         << i["peak_pressure"].get<double>() << ", largest opening " << i["largest_opening"].get<double>()
         << ", largest overlap " << i["largest_overlap"].get<double>() << "\n";
  return line.str();
}

void addContactSummary(const ContactSolveResult& contactSolve, double tolerance, nlohmann::json& summary) {
  const auto& r = contactSolve.contact;
  summary["solver"] = contactSolve.chain;
  addStepNumbers(outcomeOf(contactSolve), summary);  // counts, KKT residuals, interfaces (OutputRegistry.hpp)
  summary["message"] = r.message;
  summary["tolerance"] = tolerance;
  summary["cg_steps"] = r.counters.cgSteps;
  summary["expansion_steps"] = r.counters.expansionSteps;
  summary["proportioning_steps"] = r.counters.proportioningSteps;
  summary["f_applications"] = contactSolve.fApplications;
  summary["factor_nonzeros"] = contactSolve.factorNonzeros;
  summary["bytes_per_f_application"] = contactSolve.bytesPerFApplication;
  summary["fixed_point_change"] = r.fixedPointChange;
  summary["energy"] = r.energy;
  summary["contact_nodes"] = {{"no_contact", r.statusCounts[0]}, {"stick", r.statusCounts[1]},
                              {"slip", r.statusCounts[2]}};
  summary["history"] = historyJson(contactSolve.history);
  summary["total_normal_force"] = contactSolve.totalNormalForce;
  summary["total_contact_force"] = contactSolve.totalContactForce;
  summary["contact_force_on_master"] = contactSolve.totalContactForce;
  if (!contactSolve.steps.empty()) summary["steps"] = stepsJson(contactSolve);
  // The pairings on the deformed bodies after each solve (Solver/Pairing Updates).
  summary["pairing_updates"] = nlohmann::json::array();
  for (const auto& u : contactSolve.pairingUpdates)
    summary["pairing_updates"].push_back({{"update", u.update}, {"paired", u.paired}, {"newly_inside", u.newlyInside},
                                          {"moved_on", u.movedOn}, {"relinearised", u.relinearised},
                                          {"solved_again", u.solvedAgain}});
  if (!contactSolve.restartFile.empty())
    summary["restart"] = {{"file", contactSolve.restartFile}, {"step", contactSolve.restartStep}};
  summary["times"]["factorization_s"] = contactSolve.factorizationSeconds;
  summary["times"]["solve_s"] = contactSolve.solveSeconds;
  // Of solve_s: the SMALSE-M runs, and of them the work outside A, M^-1, Q and the
  // Coulomb hook (MPGP's vector updates, projections onto Omega, reductions; issue 9).
  summary["times"]["smalse_s"] = r.counters.seconds;
  summary["times"]["vector_s"] = r.counters.seconds - r.counters.operatorSeconds;
  // Of smalse_s: the products with A_rho = PFP + rho Q (pfp_applications of them, the norm
  // estimate's included) and the inner preconditioner's applications, each with its
  // projections: issue 9's time per PFP application is products_s / pfp_applications.
  summary["times"]["products_s"] = r.counters.productSeconds;
  summary["times"]["preconditioning_s"] = r.counters.preconditionerSeconds;
  summary["operator_profile"] = profileJson(contactSolve.profile);
}

// The linear solve's part of the summary.
void addLinearSummary(const LinearFetiResult& linear, const std::string& chain, double tolerance,
                      nlohmann::json& summary) {
  summary["solver"] = chain;
  addStepNumbers(outcomeOf(linear), summary);  // counts, KKT residuals, bonded interfaces (OutputRegistry.hpp)
  summary["message"] = linear.message;
  summary["tolerance"] = tolerance;
  summary["factor_nonzeros"] = linear.factorNonzeros;
  summary["bytes_per_f_application"] = linear.bytesPerFApplication;
  summary["condition_estimate"] = linear.conditionEstimate;
  if (!linear.interfaces.empty()) {  // bonded interfaces
    summary["total_normal_force"] = linear.totalNormalForce;
    summary["total_contact_force"] = linear.totalContactForce;
  }
  summary["times"]["factorization_s"] = linear.factorizationSeconds;
  summary["times"]["solve_s"] = linear.solveSeconds;
}

std::string contactReport(const ContactSolveResult& contactSolve) {
  const auto& r = contactSolve.contact;
  std::ostringstream out;
  out << "  SMALSE-M: " << (r.converged ? "converged" : "NOT CONVERGED (" + r.message + ")") << ": "
      << r.counters.outerIterations << " outer, " << r.counters.innerIterations << " inner iterations, "
      << r.counters.operatorApplications << " PFP applications, " << r.fixedPointIterations
      << " slip-bound updates\n"
      << "  contact nodes" << (r.converged ? "" : " (of the last iterate, not a solution)") << ": "
      << r.statusCounts[0] << " no contact, " << r.statusCounts[1] << " stick, " << r.statusCounts[2]
      << " slip; total normal force " << contactSolve.totalNormalForce << "\n"
      << interfaceLine(contactSolve)
      << "  KKT (each <= " << r.kktTolerance << " for \"converged\"): equilibrium " << r.kkt.equilibrium
      << ", gluing/Dirichlet " << r.kkt.equality << ", penetration " << r.kkt.nonPenetration
      << ", complementarity " << r.kkt.complementarity << ", normal sign " << r.kkt.normalSign
      << ", friction " << r.kkt.frictionAdmissibility << ", slip rule " << r.kkt.slipRule << ", stick rule "
      << r.kkt.stickRule << "\n"
      << coarseFactorLine(contactSolve.profile)
      << "  times: factorization " << contactSolve.factorizationSeconds << " s, solve "
      << contactSolve.solveSeconds << " s\n";
  return out.str();
}

std::string linearReport(const LinearFetiResult& linear) {
  std::ostringstream out;
  out << "  projected CG: " << (linear.converged ? "converged" : "NOT CONVERGED (" + linear.message + ")") << " in "
      << linear.iterations << " iterations (" << linear.fApplications << " F applications), "
      << "||Pr||/||Ph|| = " << linear.relativeResidual << ", kappa ~ " << linear.conditionEstimate
      << "\n  KKT: equilibrium " << linear.equilibriumResidual << ", ||Bu - c||/||u|| "
      << linear.constraintResidual << "\n" << interfaceLine(linear) << "  times: factorization " << linear.factorizationSeconds
      << " s, solve " << linear.solveSeconds << " s\n";
  return out.str();
}

}  // namespace

nlohmann::json stepSummary(const ContactSolveResult& c, size_t i) {
  const auto& k = c.steps[i];
  nlohmann::json entry = {{"time", k.time},
                          {"ramp", k.factor},
                          {"factors", factorsJson(k.factors)},
                          {"attempts", k.attempts},
                          {"cutbacks", k.cutbacks},
                          {"reached", k.reached},
                          {"no_contact", k.statusCounts[0]},
                          {"stick", k.statusCounts[1]},
                          {"slip", k.statusCounts[2]},
                          {"message", k.message}};
  // Its step number, counts, KKT residuals, interfaces and (pretension sections: each one's
  // tension and shortening at the step's end) sections: OutputRegistry.hpp.
  addStepNumbers(outcomeOf(c, i), entry);
  // The solves of the step's tries (more than its attempts where a section's Force was iterated).
  if (!k.sections.empty()) entry["solves"] = k.sectionSolves;
  return entry;
}

nlohmann::json setupSummary(const Scene& scene, const SetupReport& report, const feti::ConstraintMatrix& B,
                            const std::string& input, bool dryRun) {
  nlohmann::json j;
  j["input"] = input;
  j["dry_run"] = dryRun;
  j["n_primal"] = report.nPrimal;
  j["n_dual"] = B.numRows;
  j["removed_redundant_rows"] = B.removedRedundantRows;
  j["n_rigid"] = report.nRigid;
  j["n_subdomains"] = report.nSubdomains;
  j["n_ranks"] = report.nRanks;
  j["n_threads"] = report.nThreads;
  j["n_nodes"] = scene.mesh.numNodes();
  j["n_elements"] = scene.mesh.numElements();
  j["stiffness_nonzeros"] = report.nnz;
  // Over every interface (sums, maxima); each interface's own in "contact_search".
  GO overlaps = 0, limited = 0;
  double largestOverlap = 0.0, largestLimit = 0.0;
  j["contact_search"] = nlohmann::json::array();
  for (const auto& i : B.interfaces) {
    overlaps += i.overlappingPairs;
    limited += i.limitedMortarGaps;
    largestOverlap = std::max(largestOverlap, i.largestOverlap);
    largestLimit = std::max(largestLimit, i.largestGapLimit);
    j["contact_search"].push_back({{"interface", i.label},
                                   {"paired", i.pairedSlaveNodes},
                                   {"unpaired", i.unpairedSlaveNodes},
                                   {"paired_inside_beyond_search_distance", i.pairedInside},
                                   {"interference", i.interference},
                                   {"given_to_another_interface", i.sharedSlaveNodes},
                                   {"initial_overlaps", i.overlappingPairs},
                                   {"largest_initial_overlap", i.largestOverlap},
                                   {"limited_mortar_gaps", i.limitedMortarGaps},
                                   {"largest_gap_limit", i.largestGapLimit},
                                   {"largest_facet_sag", i.largestFacetSag},
                                   {"surface_geometry", i.smoothedSurfaces ? "Smoothed" : "Faceted"},
                                   {"unsettled_projections", i.unsettledProjections}});
  }
  j["contact_nodes_paired"] = B.contact.size();
  j["contact_nodes_unpaired"] = B.unpairedSlaveNodes();
  j["contact_initial_overlaps"] = overlaps;
  j["contact_limited_mortar_gaps"] = limited;
  j["contact_largest_gap_limit"] = largestLimit;
  j["contact_largest_initial_overlap"] = largestOverlap;
  j["times"] = {{"mesh_s", scene.meshSeconds},
                {"decomposition_s", scene.decompositionSeconds},
                {"assembly_s", report.assemblySeconds}};
  return j;
}

namespace {
/// A line where mortar gaps were kept within the gap between the surfaces
/// (ConstraintMatrix::limitedMortarGaps), naming the interface; empty where none were.
/// Compare the change with the displacements expected: where it is not small against them,
/// the slave mesh is too coarse for the master's curvature.
std::string limitedGapsWarning(const feti::ContactInterfaceRows& i) {
  if (i.limitedMortarGaps == 0) return "";
  std::ostringstream line;
  line << "  " << i.label << ": " << i.limitedMortarGaps
       << " mortar gaps kept within the gap between the surfaces (changed by up to " << i.largestGapLimit
       << "): the slave elements are coarse for the master's curvature there; if that is not small against "
          "the displacements, refine the slave side or use "
       << i.list << "/Discretization = Node To Surface\n";
  return line.str();
}

/// A line where a faceted interface's master sags between its nodes by a tenth of its largest
/// initial overlap or more (ContactInterfaceRows::largestFacetSag): if the surfaces were meshed
/// on a curved body, the facets' sag counts as gap (a shrink fit from CAD in linear elements:
/// the fit force 26-43 % high), which Surface Geometry = Smoothed removes; empty otherwise.
std::string facetSagWarning(const feti::ContactInterfaceRows& i) {
  if (i.smoothedSurfaces || i.overlappingPairs == 0 || !(i.largestFacetSag >= 0.1 * i.largestOverlap)) return "";
  std::ostringstream line;
  line << "  " << i.label << ": the master's facets lie up to " << i.largestFacetSag
       << " from the smooth surface through its nodes where slave nodes pair, against initial overlaps of up to "
       << i.largestOverlap << ": if the surfaces are meant to be curved (meshed on a cylinder or sphere), that "
       << "sag counts as gap; set " << i.list << "/Surface Geometry = Smoothed (doc/contact_surfaces.md)\n";
  return line.str();
}

/// A line where Surface Geometry = Automatic measured the gaps on the smoothed surfaces
/// (ContactInterfaceRows::smoothedByChoice), with the sag that decided it; empty otherwise.
std::string smoothedByChoiceLine(const feti::ContactInterfaceRows& i) {
  if (!i.smoothedByChoice) return "";
  std::ostringstream line;
  line << "  " << i.label << ": the master's facets sag up to " << i.largestFacetSag
       << " between its nodes, a tenth or more of the fit to close: gaps measured on the smoothed surfaces ("
       << i.list << "/Surface Geometry = Automatic; Faceted keeps the faces, doc/contact_surfaces.md)\n";
  return line.str();
}

/// A line where projections on curved master faces did not settle (geometry/FaceProjection.hpp),
/// naming the interface and the first slave node; empty where all settled.
std::string unsettledProjectionsWarning(const feti::ContactInterfaceRows& i) {
  if (i.unsettledProjections == 0) return "";
  std::ostringstream line;
  line << "  " << i.label << ": warning: " << i.unsettledProjections
       << " projections on curved master faces did not settle (slave nodes and mortar quadrature points; "
       << (i.firstUnsettled.empty() ? std::string("all of them quadrature points") : "first " + i.firstUnsettled)
       << "); their pairs and weights use the last point reached: check the master faces there (warped, "
          "degenerate or strongly curved)\n";
  return line.str();
}

/// One line per contact interface: its pairs, out-of-reach slave nodes and initial overlaps.
std::string contactSearchLines(const feti::ConstraintMatrix& B) {
  if (B.interfaces.empty()) return "  contact: none (linear T-FETI)\n";
  std::ostringstream out;
  for (const auto& i : B.interfaces) {
    out << "  " << i.label << ": " << i.pairedSlaveNodes << " slave nodes paired";
    if (i.pairedInside > 0)
      out << " (" << i.pairedInside << " of them inside the master body, beyond " << i.list << "/Search Distance)";
    out << ", " << i.unpairedSlaveNodes
        << " out of reach (no master face facing them within " << i.list << "/Search Distance: no rows), "
        << i.overlappingPairs << " with initial overlap";
    if (i.overlappingPairs > 0) out << " (largest " << i.largestOverlap << ")";
    if (i.interference != 0.0)
      out << "; " << i.list << "/Interference " << i.interference << " subtracted from every gap"
          << (i.interference > 0.0 ? " (an overlap to close)" : " (a clearance)");
    if (i.sharedSlaveNodes > 0)
      out << "; " << i.sharedSlaveNodes << " more paired here have the rows of another interface, where their gap "
          << "is smaller (a slave node has the rows of one interface)";
    out << "\n" << limitedGapsWarning(i) << facetSagWarning(i) << smoothedByChoiceLine(i)
        << unsettledProjectionsWarning(i);
  }
  return out.str();
}
}  // namespace

namespace {
/// "1600 HEX8, 32 WEDGE6": how many elements of each type the mesh has.
std::string elementTypeCounts(const mesh::Mesh& mesh) {
  LO count[mesh::kNumElementTypes] = {};
  for (mesh::ElementType t : mesh.elements.types()) count[static_cast<int>(t)]++;
  std::string text;
  for (int t = 0; t < mesh::kNumElementTypes; ++t)
    if (count[t] > 0)
      text += (text.empty() ? "" : ", ") + std::to_string(count[t]) + " " +
              mesh::elementShape(static_cast<mesh::ElementType>(t)).exodusName;
  return text;
}
}  // namespace

std::string setupReport(const std::string& input, const Scene& scene, const SetupReport& report,
                        const feti::ConstraintMatrix& B, double setupSeconds, double constraintSeconds) {
  std::ostringstream out;
  out << "tribos: " << input << "\n"
      << "  mesh: " << scene.mesh.numNodes() << " nodes, " << scene.mesh.numElements() << " elements ("
      << elementTypeCounts(scene.mesh) << "), " << scene.mesh.numBlocks() << " bodies\n"
      << "  subdomains: " << report.nSubdomains
      << (scene.subdomainChoice.empty() ? "" : " (" + scene.subdomainChoice + ")") << " on " << report.nRanks
      << " rank(s) x " << report.nThreads << " thread(s)\n"
      << "  n_primal = " << report.nPrimal << ", n_dual = " << B.numRows << " (removed " << B.removedRedundantRows
      << " redundant rows), n_rigid = " << report.nRigid << "\n"
      << contactSearchLines(B)
      << "  set-up: " << setupSeconds << " s (assembly " << report.assemblySeconds << " s, B " << constraintSeconds
      << " s)\n";
  return out.str();
}

void addSolveSummary(const SceneSolveResult& result, const Teuchos::ParameterList& tribos, nlohmann::json& summary) {
  const double tolerance = tribos.sublist("Solver").get<double>("Tolerance");
  if (result.contactProblem)
    addContactSummary(result.contactSolve, tolerance, summary);
  else
    addLinearSummary(result.linear, result.chain, tolerance, summary);
}

std::string solveReport(const SceneSolveResult& result) {
  return result.contactProblem ? contactReport(result.contactSolve) : linearReport(result.linear);
}

std::string timingTable(const std::vector<core::PhaseTime>& phases) {
  // The phases as StackedTimer nested them: "tribos@Set-up@Set-up: mesh" is printed as
  // "Set-up: mesh" two levels in.
  std::string table;
  char line[160];
  std::snprintf(line, sizeof line, "  %-44s %10s %6s\n", "phase (slowest rank)", "seconds", "calls");
  table += line;
  for (const auto& phase : phases) {
    const size_t depth = static_cast<size_t>(std::count(phase.path.begin(), phase.path.end(), '@'));
    const std::string name = std::string(2 * depth, ' ') + phase.path.substr(phase.path.rfind('@') + 1);
    std::snprintf(line, sizeof line, "  %-44s %10.4f %6lld\n", name.c_str(), phase.maxSeconds, phase.calls);
    table += line;
  }
  return table;
}

void addTimersToSummary(const std::vector<core::PhaseTime>& phases, nlohmann::json& summary) {
  summary["timers"] = nlohmann::json::array();
  for (const auto& phase : phases)
    summary["timers"].push_back(
        {{"phase", phase.path}, {"max_s", phase.maxSeconds}, {"min_s", phase.minSeconds}, {"calls", phase.calls}});
}

/// Stresses, strain energy, reactions and the force balance (rank 0) into the summary.
void addResultsToSummary(const StressResults& stress, const ForceBalance& balance,
                         nlohmann::json& summary) {
  addStepNumbers(withStresses({}, stress, balance), summary);  // strain energy, force balance
  summary["reactions"] = nlohmann::json::object();
  for (const auto& r : balance.reactions) summary["reactions"][r.name] = r.force;
  summary["reaction_total"] = balance.totalReaction;
  summary["applied_load"] = balance.appliedLoad;
}

}  // namespace tribos::stack
