// tribos: the main driver. Reads a Teuchos XML scene, builds the mesh and its T-FETI
// decomposition, assembles every subdomain, and writes the Exodus results and a JSON
// summary. Sample runs:
//   tribos --input input/two_bricks.xml --dry-run
//   tribos --input input/two_bricks.xml --set "Mesh/H Over h=4" --summary s.json --output r.exo
//   mpirun --allow-run-as-root -np 4 tribos --input input/two_bricks.xml --dry-run
//
// Scenes without contact, or with Contact/Friction Model = "Bonded", are solved by linear
// T-FETI (projected CG); contact scenes (None, Tresca, Coulomb) by T-FETI + SMALSE-M + MPGP
// (+ successive approximations on the slip bound for Coulomb).
#include <mpi.h>

#include <Tpetra_Core.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <iomanip>
#include <sstream>
#include <vector>

#include "CommandLine.hpp"
#include "RunFiles.hpp"
#include "RunOutcome.hpp"
#include "tribos/stack/SubdomainSetup.hpp"
#include "tribos/core/Deadline.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/Solvability.hpp"
#include "tribos/stack/ContactSolve.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/RankData.hpp"
#include "tribos/stack/Results.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SceneSize.hpp"

namespace {
using namespace tribos;

nlohmann::json summaryJson(const stack::Scene& scene, const stack::SetupReport& report,
                           const feti::ConstraintMatrix& B, const driver::CommandLine& cl) {
  nlohmann::json j;
  j["input"] = cl.input;
  j["dry_run"] = cl.dryRun;
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
  j["contact_nodes_paired"] = B.contact.size();
  j["contact_nodes_unpaired"] = B.unpairedSlaveNodes;
  j["contact_initial_overlaps"] = B.overlappingPairs;
  j["contact_largest_initial_overlap"] = B.largestOverlap;
  j["times"] = {{"mesh_s", scene.meshSeconds},
                {"decomposition_s", scene.decompositionSeconds},
                {"assembly_s", report.assemblySeconds}};
  return j;
}

// One object per SMALSE-M outer iteration: what the progress lines showed.
/// Rank 0's operator counts and times (TotalFeti::profile; doc/measurements/coarse_problem.md).
nlohmann::json profileJson(const feti::OperatorProfile& p) {
  return {{"f_applications", p.fApplications},
          {"projections", p.projections},
          {"coarse_solves", p.coarseSolves},
          {"coarse_solves_reused", p.coarseSolvesReused},
          {"projections_reused", p.projectionsReused},
          {"coarse_coordinates", p.coarseCoordinates},
          {"coarse_coordinates_reused", p.coarseCoordinatesReused},
          {"preconditioner_applications", p.preconditionerApplications},
          {"f_s", p.fSeconds},
          {"g_s", p.gSeconds},
          {"coarse_reduce_s", p.coarseReduceSeconds},
          {"coarse_solve_s", p.coarseSolveSeconds},
          {"preconditioner_s", p.preconditionerSeconds},
          {"coarse_factor_s", p.coarseFactorSeconds},
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

nlohmann::json historyJson(const std::vector<stack::OuterIterationRecord>& history) {
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

/// Everything the Exodus result shows besides the mesh; null pointers: not computed (dry run).
struct OutputData {
  const std::vector<std::array<double, 3>>* displacement = nullptr;
  const std::vector<std::array<double, 3>>* reaction = nullptr;
  const stack::StressResults* stress = nullptr;
  const stack::ContactSolveResult* contact = nullptr;  ///< contact scenes
  std::vector<mesh::GlobalValue> globals;
  std::vector<std::string> info;
};

/// Three nodal fields <prefix>x, <prefix>y, <prefix>z from one vector per node.
void addVectorField(const std::string& prefix, const std::vector<std::array<double, 3>>& v, mesh::TimeStep& step) {
  for (int c = 0; c < 3; ++c) {
    mesh::Field f{prefix + "xyz"[c], std::vector<double>(v.size())};
    for (size_t n = 0; n < v.size(); ++n) f.values[n] = v[n][c];
    step.nodal.push_back(std::move(f));
  }
}

void addStressFields(const stack::StressResults& stress, mesh::TimeStep& step) {
  for (int k = 0; k < 6; ++k) {
    step.element.push_back({std::string("stress_") + stack::kStressComponents[k], stress.element[k]});
    step.nodal.push_back({std::string("nodal_stress_") + stack::kStressComponents[k], stress.nodal[k]});
  }
  step.element.push_back({"von_mises", stress.elementVonMises});
  step.nodal.push_back({"nodal_von_mises", stress.nodalVonMises});
}

void addContactFields(const stack::ContactSolveResult& c, mesh::TimeStep& step) {
  const std::pair<const char*, const std::vector<double>*> fields[] = {
      {"contact_normal", &c.contactNormal}, {"contact_t1", &c.contactT1},         {"contact_t2", &c.contactT2},
      {"contact_status", &c.contactStatus}, {"contact_pressure", &c.contactPressure}, {"contact_gap", &c.contactGap},
      {"contact_opening", &c.contactOpening}, {"contact_nx", &c.contactNx},       {"contact_ny", &c.contactNy},
      {"contact_nz", &c.contactNz},         {"contact_master", &c.contactMaster}};
  for (const auto& [name, values] : fields) step.nodal.push_back({name, *values});
}

void writeOutput(const std::string& path, const stack::Scene& scene, const OutputData& data) {
  mesh::TimeStep step;
  step.time = data.displacement ? 1.0 : 0.0;
  if (data.displacement) addVectorField("displ_", *data.displacement, step);
  if (data.reaction) addVectorField("reaction_", *data.reaction, step);
  if (data.stress) addStressFields(*data.stress, step);
  if (data.contact) addContactFields(*data.contact, step);
  mesh::Field subdomain{"subdomain", std::vector<double>(scene.mesh.numElements())};
  for (LO e = 0; e < scene.mesh.numElements(); ++e) subdomain.values[e] = scene.decomposition.elementPart[e];
  step.element.push_back(std::move(subdomain));
  step.global = data.globals;
  mesh::writeExodus(path, scene.mesh, {step}, data.info);
}

/// The result file says how it was made: the command line and the effective parameter list
/// (defaults filled in) as XML, one info record per line.
std::vector<std::string> infoRecords(int argc, char** argv, const Teuchos::ParameterList& params) {
  std::string command = "tribos";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  std::vector<std::string> info = {"Tribos result", command};
  std::istringstream lines(core::parameterListToXml(params));
  for (std::string line; std::getline(lines, line);) info.push_back(line);
  return info;
}

/// Per-step global variables: the summary's counts and KKT residuals (numbers only).
std::vector<mesh::GlobalValue> globalValues(const nlohmann::json& summary) {
  std::vector<mesh::GlobalValue> out;
  for (const char* key : {"converged", "outer_iterations", "inner_iterations", "pfp_applications",
                          "fixed_point_iterations", "strain_energy", "force_balance"})
    if (summary.contains(key))
      out.push_back({key, summary[key].is_boolean() ? double(summary[key].get<bool>()) : summary[key].get<double>()});
  if (summary.contains("kkt"))
    for (const auto& [name, value] : summary["kkt"].items())
      if (value.is_number()) out.push_back({"kkt_" + name, value.get<double>()});
  return out;
}

/// Stresses, strain energy, reactions and the force balance (rank 0) into the summary.
void addResultsToSummary(const stack::StressResults& stress, const stack::ForceBalance& balance,
                         nlohmann::json& summary) {
  summary["strain_energy"] = stress.strainEnergy;
  summary["reactions"] = nlohmann::json::object();
  for (const auto& r : balance.reactions) summary["reactions"][r.name] = r.force;
  summary["reaction_total"] = balance.totalReaction;
  summary["applied_load"] = balance.appliedLoad;
  summary["force_balance"] = balance.relativeImbalance;
}

// This process's peak resident set size in KiB (getrusage: ru_maxrss is in KiB on Linux).
long peakRssKb() {
  struct rusage usage {};
  return getrusage(RUSAGE_SELF, &usage) == 0 ? static_cast<long>(usage.ru_maxrss) : 0L;
}

// Every rank's peak resident set size so far, gathered on rank 0 (collective; empty elsewhere).
std::vector<long> gatherPeakRssKb(int rank) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const long mine = peakRssKb();
  std::vector<long> all(rank == 0 ? static_cast<size_t>(size) : 0);
  MPI_Gather(&mine, 1, MPI_LONG, all.data(), 1, MPI_LONG, 0, MPI_COMM_WORLD);
  return all;
}

// The scene on every rank, or an input error on every rank: a rank that cannot read the mesh
// file (replaced while the job started) must not leave the others waiting for it, and ranks
// that read different meshes must not go on (stack/SameMeshOnEveryRank.hpp).
stack::Scene buildSceneOnEveryRank(const Teuchos::ParameterList& params, const std::string& input,
                                   const std::string& meshFile) {
  stack::Scene scene;
  core::onEveryRankOrNone([&] { scene = stack::buildScene(params, input, MPI_COMM_WORLD); },
                          (meshFile.empty() ? input : meshFile) + ": another rank could not build the scene",
                          MPI_COMM_WORLD);
  return scene;
}

/// What steps (1) and (2) settle before any work: the command line, the parameters, the
/// result files (checked) and the run's deadline.
struct RunStart {
  driver::CommandLine cl;
  Teuchos::ParameterList params;
  std::string meshFile;  ///< empty for a generated mesh
  driver::ResultFiles files;
  core::Deadline deadline;
  core::Stopwatch total;  ///< from the start of the run
};

// A limit reached before the solve could end (Solver/Max Seconds during the set-up): no
// results to write, but the summary still says what happened.
void writeStoppedSummary(const RunStart& start, const std::string& message) {
  nlohmann::json summary;
  summary["input"] = start.cl.input;
  summary["converged"] = false;
  summary["message"] = message;
  summary["times"] = {{"total_s", start.total.seconds()}};
  start.files.summary->writeText(summary.dump(2) + "\n");
}

int solveAndReport(int argc, char** argv, int rank, const RunStart& start);

int run(int argc, char** argv, int rank) {
  core::Stopwatch total;
  // (1) Command line.
  driver::CommandLine cl = driver::parseCommandLine(argc, argv);
  const auto valid = stack::sceneValidParameters();
  if (cl.help || cl.version || cl.kokkosHelp) {  // Kokkos has printed its help for --kokkos-help
    if (rank == 0 && cl.help) std::cout << driver::usage();
    if (rank == 0 && cl.version) std::cout << driver::versionText();
    return core::kExitOk;
  }
  if (cl.listParameters) {
    if (rank == 0) std::cout << core::describeParameters(*valid);
    return core::kExitOk;
  }

  // (2) Scene parameters: XML, command-line overrides, validation against every component;
  // the result files checked and the deadline set, before any work.
  Teuchos::ParameterList params = driver::readSceneXml(cl.input, rank);
  core::validateAndSetDefaults(params, *valid, cl.input);
  // Each override is validated on its own, so that a bad value names the --set that gave it.
  for (const auto& assignment : cl.overrides) {
    core::applyOverride(params, *valid, assignment);
    core::validateAndSetDefaults(params, *valid, "--set \"" + assignment + "\"");
  }
  stack::requireSceneFitsInMemory(params, cl.input, MPI_COMM_WORLD, !cl.dryRun);
  if (const int threads = params.sublist("Parallel").get<int>("Threads"); threads > 0)
    core::setNumThreads(threads);
  const std::string meshFile = stack::meshFilePath(params, cl.input);
  driver::ResultFiles files = driver::prepareResultFiles(cl, {cl.input, meshFile}, rank);
  const core::Deadline deadline(params.sublist("Solver").get<double>("Max Seconds"), total);
  const RunStart start{std::move(cl), std::move(params), meshFile, std::move(files), deadline, total};
  try {
    return solveAndReport(argc, argv, rank, start);
  } catch (const core::LimitReached& e) {  // thrown on every rank together
    try {
      if (rank == 0 && start.files.summary) writeStoppedSummary(start, e.what());
    } catch (const core::IoError& io) {
      throw core::IoError(std::string(e.what()) + "; and the summary: " + io.what());
    }
    throw;
  }
}

/// Steps (3) to (5): the set-up, the solve and the results.
int solveAndReport(int argc, char** argv, int rank, const RunStart& start) {
  const auto& [cl, params, meshFile, resultFiles, deadline, total] = start;
  // (3) Mesh, decomposition, per-subdomain assembly, constraint matrix B.
  core::Stopwatch setup;
  stack::Scene scene = buildSceneOnEveryRank(params, cl.input, meshFile);
  deadline.check("reading the mesh", MPI_COMM_WORLD);
  std::vector<fem::SubdomainSystem> systems;
  const stack::SetupReport report = stack::assembleOwnedSubdomains(scene, MPI_COMM_WORLD, systems);
  deadline.check("the assembly", MPI_COMM_WORLD);
  int numRanks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &numRanks);
  core::Stopwatch constraintWatch;
  // Only this rank's blocks of B (its subdomains, its rows), never the whole of it.
  feti::ConstraintMatrix B =
      feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), numRanks, rank);
  // Before any solve: every rigid motion of every body must meet a row of B (exit 2 naming
  // the body and its free motions otherwise).
  {
    const Teuchos::MpiComm<int> world(MPI_COMM_WORLD);
    feti::requireRestrainedBodies(scene.mesh, scene.decomposition, B, &world);
  }
  const double constraintSeconds = constraintWatch.seconds();
  const double setupSeconds = setup.seconds();
  deadline.check("the constraints", MPI_COMM_WORLD);

  if (rank == 0) {
    std::cout << "tribos: " << cl.input << "\n"
              << "  mesh: " << scene.mesh.numNodes() << " nodes, " << scene.mesh.numElements()
              << " tetrahedra, " << scene.mesh.numBlocks() << " bodies\n"
              << "  subdomains: " << report.nSubdomains << " on " << report.nRanks << " rank(s) x "
              << report.nThreads << " thread(s)\n"
              << "  n_primal = " << report.nPrimal << ", n_dual = " << B.numRows << " (removed "
              << B.removedRedundantRows << " redundant rows), n_rigid = " << report.nRigid << "\n"
              << (scene.contact.hasContact()
                      ? "  contact: " + std::to_string(B.contact.size()) + " slave nodes paired, " +
                            std::to_string(B.unpairedSlaveNodes) +
                            " out of reach (no master face facing them within Contact/Search Distance: no rows), " +
                            std::to_string(B.overlappingPairs) + " with initial overlap" +
                            (B.overlappingPairs > 0 ? " (largest " + std::to_string(B.largestOverlap) + ")" : "") + "\n"
                      : std::string("  contact: none (linear T-FETI)\n"))
              << "  set-up: " << setupSeconds << " s (assembly " << report.assemblySeconds << " s, B "
              << constraintSeconds << " s)\n";
  }
  nlohmann::json summary = summaryJson(scene, report, B, cl);
  summary["times"]["constraints_s"] = constraintSeconds;
  summary["times"]["setup_s"] = setupSeconds;
  // From here on a rank holds its own subdomains, its rows of B and (rank 0) the global mesh
  // for the results: what the set-up alone needed is freed before the factorisation.
  stack::keepRankData(scene, B, rank, numRanks);
  int status = core::kExitOk;
  stack::LinearFetiResult linear;
  stack::ContactSolveResult contactSolve;
  OutputData output;
  std::array<double, 3> appliedLoad{};

  // (4) Solve: linear T-FETI for bonded / contact-free scenes.
  const bool linearProblem = !scene.contact.hasContact() || scene.contact.frictionModel == contact::FrictionModel::Bonded;
  if (cl.dryRun) {
    summary["solver"] = "dry run: not solved";
  } else if (!linearProblem) {
    if (rank == 0) std::cout << "  solver chain: " << stack::describeContactChain(params) << "\n";
    contactSolve = stack::solveContactScene(scene, std::move(systems), B, params, MPI_COMM_WORLD, total);
    const auto& r = contactSolve.contact;
    output.displacement = &contactSolve.displacement.value;
    output.reaction = &contactSolve.reaction;
    output.contact = &contactSolve;
    appliedLoad = contactSolve.appliedLoad;
    status = r.converged ? core::kExitOk : core::kExitNotConverged;
    summary["solver"] = contactSolve.chain;
    summary["converged"] = r.converged;
    summary["message"] = r.message;
    summary["tolerance"] = params.sublist("Solver").get<double>("Tolerance");
    summary["outer_iterations"] = r.counters.outerIterations;
    summary["inner_iterations"] = r.counters.innerIterations;
    summary["cg_steps"] = r.counters.cgSteps;
    summary["expansion_steps"] = r.counters.expansionSteps;
    summary["proportioning_steps"] = r.counters.proportioningSteps;
    summary["pfp_applications"] = r.counters.operatorApplications;
    summary["f_applications"] = contactSolve.fApplications;
    summary["factor_nonzeros"] = contactSolve.factorNonzeros;
    summary["bytes_per_f_application"] = contactSolve.bytesPerFApplication;
    summary["fixed_point_iterations"] = r.fixedPointIterations;
    summary["fixed_point_change"] = r.fixedPointChange;
    summary["energy"] = r.energy;
    summary["kkt"] = {{"projected_gradient", r.counters.projectedGradient},
                      {"equality_constraint", r.counters.equalityResidual},
                      {"equilibrium", r.kkt.equilibrium},
                      {"gluing_dirichlet", r.kkt.equality},
                      {"non_penetration", r.kkt.nonPenetration},
                      {"complementarity", r.kkt.complementarity},
                      {"normal_sign", r.kkt.normalSign},
                      {"friction_admissibility", r.kkt.frictionAdmissibility},
                      {"slip_rule", r.kkt.slipRule},
                      {"stick_rule", r.kkt.stickRule},
                      {"max_copy_jump", contactSolve.displacement.maxCopyJump},
                      {"tolerance", r.kktTolerance}};
    summary["contact_nodes"] = {{"no_contact", r.statusCounts[0]}, {"stick", r.statusCounts[1]},
                                {"slip", r.statusCounts[2]}};
    summary["history"] = historyJson(contactSolve.history);
    summary["total_normal_force"] = contactSolve.totalNormalForce;
    summary["total_contact_force"] = contactSolve.totalContactForce;
    summary["contact_force_on_master"] = contactSolve.totalContactForce;
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
    if (rank == 0)
      std::cout << "  SMALSE-M: " << (r.converged ? "converged" : "NOT CONVERGED (" + r.message + ")") << ": "
                << r.counters.outerIterations << " outer, " << r.counters.innerIterations << " inner iterations, "
                << r.counters.operatorApplications << " PFP applications, " << r.fixedPointIterations
                << " slip-bound updates\n"
                << "  contact nodes: " << r.statusCounts[0] << " no contact, " << r.statusCounts[1] << " stick, "
                << r.statusCounts[2] << " slip; total normal force " << contactSolve.totalNormalForce << "\n"
                << "  KKT (each <= " << r.kktTolerance << " for \"converged\"): equilibrium " << r.kkt.equilibrium
                << ", gluing/Dirichlet " << r.kkt.equality << ", penetration " << r.kkt.nonPenetration
                << ", complementarity " << r.kkt.complementarity << ", normal sign " << r.kkt.normalSign
                << ", friction " << r.kkt.frictionAdmissibility << ", slip rule " << r.kkt.slipRule << ", stick rule "
                << r.kkt.stickRule << "\n"
                << coarseFactorLine(contactSolve.profile)
                << "  times: factorization " << contactSolve.factorizationSeconds << " s, solve "
                << contactSolve.solveSeconds << " s\n";
  } else {
    const double tolerance = params.sublist("Solver").get<double>("Tolerance");
    linear = stack::solveLinearFeti(scene, std::move(systems), B, params.sublist("FETI"), tolerance, MPI_COMM_WORLD,
                                    params.sublist("Solver").get<double>("Max Seconds"), total);
    output.displacement = &linear.displacement;
    output.reaction = &linear.reaction;
    appliedLoad = linear.appliedLoad;
    status = linear.converged ? core::kExitOk : core::kExitNotConverged;
    summary["solver"] = "linear T-FETI (projected CG, preconditioner " +
                        params.sublist("FETI").get<std::string>("Preconditioner") + ")";
    summary["converged"] = linear.converged;
    summary["message"] = linear.message;
    summary["tolerance"] = tolerance;
    summary["outer_iterations"] = linear.iterations;
    summary["pfp_applications"] = linear.fApplications;
    summary["factor_nonzeros"] = linear.factorNonzeros;
    summary["bytes_per_f_application"] = linear.bytesPerFApplication;
    summary["condition_estimate"] = linear.conditionEstimate;
    summary["kkt"] = {{"projected_residual", linear.relativeResidual},
                      {"equilibrium", linear.equilibriumResidual},
                      {"equality_constraints", linear.constraintResidual},
                      {"max_copy_jump", linear.maxCopyJump}};
    summary["times"]["factorization_s"] = linear.factorizationSeconds;
    summary["times"]["solve_s"] = linear.solveSeconds;
    if (rank == 0)
      std::cout << "  projected CG: " << (linear.converged ? "converged" : "NOT CONVERGED (" + linear.message + ")") << " in "
                << linear.iterations << " iterations (" << linear.fApplications << " F applications), "
                << "||Pr||/||Ph|| = " << linear.relativeResidual << ", kappa ~ " << linear.conditionEstimate
                << "\n  KKT: equilibrium " << linear.equilibriumResidual << ", ||Bu - c||/||u|| "
                << linear.constraintResidual << "\n  times: factorization " << linear.factorizationSeconds
                << " s, solve " << linear.solveSeconds << " s\n";
  }
  summary["times"]["total_s"] = total.seconds();
  if (rank == 0 && !cl.dryRun) {
    // The timing table of the run (slowest rank where the phase is parallel).
    std::printf("  %-16s %10s\n", "phase", "seconds");
    for (const char* phase : {"mesh_s", "decomposition_s", "assembly_s", "constraints_s", "factorization_s", "solve_s",
                              "total_s"})
      if (summary["times"].contains(phase))
        std::printf("  %-16s %10.4f\n", std::string(phase).substr(0, std::string(phase).size() - 2).c_str(),
                    summary["times"][phase].get<double>());
  }

  // (5) Results on rank 0, which holds the global displacement and reactions.
  stack::StressResults stress;
  if (rank == 0 && output.displacement) {
    stress = stack::evaluateStresses(scene, *output.displacement);
    const auto balance = stack::forceBalance(scene, *output.reaction, appliedLoad);
    addResultsToSummary(stress, balance, summary);
    output.stress = &stress;
    std::cout << "  strain energy " << stress.strainEnergy << "; applied load (" << appliedLoad[0] << ", "
              << appliedLoad[1] << ", " << appliedLoad[2] << "), |reactions + load| / |load| = "
              << balance.relativeImbalance << "\n";
  }
  // Peak memory per rank (KiB) after the solve and the stresses; rank 0's own figure is read
  // again after writing the Exodus result, just before the summary.
  std::vector<long> maxRssPerRankKb = gatherPeakRssKb(rank);
  if (rank == 0) {
    // A result that cannot be written (disk full, read-only, a file size limit) leaves no
    // partial file; the summary is still written where it can be and records the failure.
    std::string writeError;
    if (resultFiles.exodus) {
      output.globals = globalValues(summary);
      output.info = infoRecords(argc, argv, params);
      try {
        resultFiles.exodus->writeWith([&](const std::string& path) { writeOutput(path, scene, output); });
        std::cout << "  wrote " << cl.output << "\n";
      } catch (const core::IoError& e) {
        writeError = e.what();
        summary["output_error"] = {{"option", "--output"}, {"file", cl.output}, {"error", writeError}};
      }
    }
    if (resultFiles.summary) {
      maxRssPerRankKb[0] = std::max(maxRssPerRankKb[0], peakRssKb());
      summary["max_rss_per_rank_kb"] = maxRssPerRankKb;
      try {
        resultFiles.summary->writeText(summary.dump(2) + "\n");
        std::cout << "  wrote " << cl.summary << "\n";
      } catch (const core::IoError& e) {
        writeError += (writeError.empty() ? "" : "; ") + std::string(e.what());
      }
    }
    if (!writeError.empty()) throw core::IoError(writeError);
  }
  return status;
}

// Idle OpenMP threads must sleep, not spin: with more ranks x threads than free cores the
// spinning threads starve the working ones (input/two_bricks.xml, 2 threads, the other core
// busy: 3.1 s median, up to 20 s, against 0.7 s when they sleep). libgomp reads
// OMP_WAIT_POLICY once, in its load-time constructor, before main runs; so when the user
// has not chosen a policy, set PASSIVE and execute this binary
// again (before MPI_Init, so mpirun sees one process; it costs about 0.05 s). One thread
// never waits, so OMP_NUM_THREADS=1 skips it. If the exec fails, run as we are.
void sleepWhileWaiting(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return;
  if (const char* threads = std::getenv("OMP_NUM_THREADS"); threads && std::string(threads) == "1") return;
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 0) != 0) return;
  execv("/proc/self/exe", argv);
}

// Progress must reach a log file as it happens (the header at once, then every line): line
// buffering when stdout is not a terminal (a terminal is line-buffered already).
void lineBufferedOutput() {
  if (!isatty(fileno(stdout))) std::setvbuf(stdout, nullptr, _IOLBF, BUFSIZ);
}

// A command-line error says what is wrong, then how to call tribos.
void reportCommandLineError(const driver::CommandLineError& e, int rank) {
  if (rank == 0) std::cerr << "tribos: error: " << e.what() << "\n\n" << driver::usage();
}
// Kokkos parses its options inside initialize() and throws std::invalid_argument on a bad
// count (--kokkos-threads=abc): std::terminate, signal 6. Check them first (exit 2 naming
// the option), and turn whatever Kokkos still refuses into the same command-line error.
int startKokkos(std::optional<Tpetra::ScopeGuard>& guard, int& kokkosArgc, char**& kokkosArgv, int argc,
                char** argv, int rank) {
  try {
    driver::requireValidKokkosArguments(argc, argv);
    guard.emplace(&kokkosArgc, &kokkosArgv);
  } catch (const driver::CommandLineError& e) {
    reportCommandLineError(e, rank);
    return core::kExitBadInput;
  } catch (const std::exception& e) {
    reportCommandLineError(driver::CommandLineError(std::string("command line: Kokkos refused its options: ") +
                                                    e.what()),
                           rank);
    return core::kExitBadInput;
  }
  return core::kExitOk;
}
}  // namespace

int main(int argc, char** argv) {
  sleepWhileWaiting(argv);
  lineBufferedOutput();
  // A file size limit (ulimit -f) makes a write fail with EFBIG, an I/O error the run reports
  // (exit 4, nothing partial left), instead of killing the process in the middle of a write.
  std::signal(SIGXFSZ, SIG_IGN);
  // A pipe or FIFO whose reader went away makes the write fail with EPIPE (exit 4, said as
  // such) instead of killing rank 0 without a word.
  std::signal(SIGPIPE, SIG_IGN);
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int status = core::kExitOk;
  {
    core::RankErrors rankErrors;  // before any work (it duplicates MPI_COMM_WORLD), gone before MPI_Finalize
    // Kokkos gets only its --kokkos-* options (--kokkos-help included).
    std::vector<char*> kokkosArgv = driver::kokkosArguments(argc, argv);
    int kokkosArgc = static_cast<int>(kokkosArgv.size()) - 1;
    char** kokkosArgvData = kokkosArgv.data();
    std::optional<Tpetra::ScopeGuard> tpetra;  // Kokkos too; MPI is already up
    status = startKokkos(tpetra, kokkosArgc, kokkosArgvData, argc, argv, rank);
    // Every rank sees the same argv: a bad Kokkos option stops them all here, together.
    if (status == core::kExitOk) {
      core::warmUpKokkosForThreads();
      // Every rank exits with the same status and each message is printed once, with the rank
      // when not every rank had it; a rank that failed alone aborts the job only if the others
      // do not reach this point within seconds (core/RankErrors.hpp).
      status = rankErrors.finish(driver::runCatchingErrors([&] { return run(argc, argv, rank); }), "tribos");
    }
  }
  MPI_Finalize();
  return status;
}
