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
#include <functional>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <iomanip>
#include <sstream>
#include <vector>

#include "CommandLine.hpp"
#include "ProcessStart.hpp"
#include "RunFiles.hpp"
#include "HistoryResults.hpp"
#include "ResultFile.hpp"
#include "RunOutcome.hpp"
#include "tribos/stack/SubdomainSetup.hpp"
#include "tribos/core/Deadline.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/SingletonStart.hpp"
#include "tribos/core/PhaseTimer.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/Solvability.hpp"
#include "tribos/stack/RankData.hpp"
#include "tribos/stack/Results.hpp"
#include "tribos/stack/OutputRegistry.hpp"
#include "tribos/stack/RunReport.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SceneSize.hpp"

namespace {
using namespace tribos;
using driver::infoRecords;
using driver::OutputData;
using driver::OutputStep;
using driver::writeOutput;

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
  // A restart file is an input too (issue 44: --output equal to it overwrote the steps it
  // restarted from).
  const std::string restartFile = params.sublist("Load Steps").get<std::string>("Restart From");
  driver::ResultFiles files = driver::prepareResultFiles(cl, {cl.input, meshFile, restartFile}, rank);
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
/// What step (3) leaves for the solve.
struct SetUpScene {
  stack::Scene scene;
  std::vector<fem::SubdomainSystem> systems;
  stack::SetupReport report;
  feti::ConstraintMatrix B;
  nlohmann::json summary;
};

// (3) Mesh, decomposition, per-subdomain assembly, constraint matrix B; then only what the
// solve needs is kept.
SetUpScene setUpScene(int rank, const RunStart& start) {
  const auto& [cl, params, meshFile, resultFiles, deadline, total] = start;
  SetUpScene set;
  core::ScopedPhase phase("Set-up");
  core::Stopwatch setup;
  {
    core::ScopedPhase mesh("Set-up: mesh and decomposition");
    set.scene = buildSceneOnEveryRank(params, cl.input, meshFile);
  }
  deadline.check("reading the mesh", MPI_COMM_WORLD);
  if (!cl.dryRun)
    stack::requireHistoryFitsInMemory(set.scene.loadSteps, MPI_COMM_WORLD);
  if (!cl.dryRun)
    requireRoomForTheResult(resultFiles, set.scene.loadSteps, set.scene.mesh.numNodes(), set.scene.mesh.numElements(),
                            rank);
  {
    core::ScopedPhase assembly("Set-up: assembly");
    set.report = stack::assembleOwnedSubdomains(set.scene, MPI_COMM_WORLD, set.systems);
  }
  deadline.check("the assembly", MPI_COMM_WORLD);
  int numRanks = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &numRanks);
  core::ScopedPhase constraints("Set-up: constraints");
  core::Stopwatch constraintWatch;
  // Only this rank's blocks of B (its subdomains, its rows), never the whole of it.
  set.B = feti::buildConstraintMatrix(set.scene.mesh, set.scene.decomposition, stack::constraintSpec(set.scene),
                                      numRanks, rank);
  // Before any solve: every rigid motion of every body must meet a row of B (exit 2 naming
  // the body and its free motions otherwise).
  {
    const Teuchos::MpiComm<int> world(MPI_COMM_WORLD);
    feti::requireRestrainedBodies(set.scene.mesh, set.scene.decomposition, set.B, &world);
  }
  const double constraintSeconds = constraintWatch.seconds();
  const double setupSeconds = setup.seconds();
  deadline.check("the constraints", MPI_COMM_WORLD);
  if (rank == 0)
    std::cout << stack::setupReport(cl.input, set.scene, set.report, set.B, setupSeconds, constraintSeconds);
  set.summary = stack::setupSummary(set.scene, set.report, set.B, cl.input, cl.dryRun);
  set.summary["times"]["constraints_s"] = constraintSeconds;
  set.summary["times"]["setup_s"] = setupSeconds;
  // From here on a rank holds its own subdomains, its rows of B and (rank 0) the global mesh
  // for the results: what the set-up alone needed is freed before the factorisation.
  stack::keepRankData(set.scene, set.B, rank, numRanks);
  return set;
}

// (6) The result files (rank 0). A result that cannot be written (disk full, read-only, a
// file size limit) leaves no partial file; the summary is still written where it can be and
// records the failure. A load history's steps taken as it went (`taken`) are in their draft
// already: `output` holds the rest, which the draft gets before it replaces the target.
void writeResults(int argc, char** argv, const RunStart& start, const stack::Scene& scene, OutputData& output,
                  driver::HistoryResults* taken, std::vector<long>& maxRssPerRankKb, nlohmann::json& summary) {
  const auto& [cl, params, meshFile, resultFiles, deadline, total] = start;
  std::string writeError;
  if (resultFiles.exodus) {
    output.info = infoRecords(argc, argv, params);
    try {
      if (taken)
        taken->finish(output.steps);
      else
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

/// (5) The time steps of the result (rank 0): each state's stresses and force balance, written
/// into the summary (a load history: into each step's entry, and the last state's into the
/// summary itself). One state, or one per load step solved: the earlier steps' results, then the
/// last state; of a history, only the steps `taken` has not (their entries get what it kept).
/// `stress` holds what the steps point to.
std::vector<OutputStep> resultSteps(const stack::Scene& scene, const stack::SceneSolveResult& solve,
                                    const driver::HistoryResults* taken, nlohmann::json& summary,
                                    std::vector<stack::StressResults>& stress) {
  static const std::vector<stack::StepResults> none;
  const auto& earlier = solve.contactProblem ? solve.contactSolve.earlierSteps : none;
  const size_t n = earlier.size() + 1;
  const bool history = summary.contains("steps");
  const size_t first = taken ? std::min(taken->taken(), earlier.size()) : 0;
  for (size_t k = 0; k < first; ++k) summary["steps"][k].update(taken->summaryOfStep(k));
  stress.resize(n - first);
  std::vector<OutputStep> steps(n - first);
  for (size_t k = first; k < n; ++k) {
    const bool last = k + 1 == n;
    OutputStep& out = steps[k - first];
    stack::StressResults& s = stress[k - first];
    const stack::ContactFields* lastFields =
        solve.contactProblem ? static_cast<const stack::ContactFields*>(&solve.contactSolve) : &solve.linear;
    out.displacement = last ? &solve.displacement() : &earlier[k].displacement.value;
    out.reaction = last ? &solve.reaction() : &earlier[k].reaction;
    if (!scene.contacts.empty()) out.contact = last ? lastFields : &earlier[k];
    const auto& appliedLoad = last ? solve.appliedLoad() : earlier[k].appliedLoad;
    const double magnitude = last ? solve.appliedLoadMagnitude() : earlier[k].appliedLoadMagnitude;
    s = stack::evaluateStresses(scene, *out.displacement);
    out.stress = &s;
    const auto balance = stack::forceBalance(scene, *out.reaction, appliedLoad, magnitude);
    out.time = history ? summary["steps"][k]["time"].get<double>() : 1.0;
    if (history) stack::addResultsToSummary(s, balance, summary["steps"][k]);
    // The step's global variables (stack/OutputRegistry.hpp), from its results.
    const stack::StepOutcome outcome = !solve.contactProblem ? stack::outcomeOf(solve.linear)
                                       : history             ? stack::outcomeOf(solve.contactSolve, k)
                                                             : stack::outcomeOf(solve.contactSolve);
    out.globals = stack::globalVariables(stack::withStresses(outcome, s, balance));
    if (!last) continue;
    stack::addResultsToSummary(s, balance, summary);
    std::cout << "  strain energy " << s.strainEnergy << "; applied load (" << appliedLoad[0] << ", "
              << appliedLoad[1] << ", " << appliedLoad[2] << "), force balance |reactions + load| / scale = "
              << balance.relativeImbalance << "\n";
  }
  return steps;
}

/// Steps (3) to (6): the set-up, the solve, the results and their files.
int solveAndReport(int argc, char** argv, int rank, const RunStart& start) {
  const auto& [cl, params, meshFile, resultFiles, deadline, total] = start;
  core::startPhaseTimers("tribos");
  SetUpScene set = setUpScene(rank, start);  // (3)
  nlohmann::json& summary = set.summary;

  // (4) Solve: the stack the scene needs (stack/SceneSolve.hpp), or none in a dry run.
  int status = core::kExitOk;
  stack::SceneSolveResult solve;
  OutputData output;
  std::optional<driver::HistoryResults> taken;  // a load history's steps as they converge
  if (cl.dryRun) {
    summary["solver"] = "dry run: not solved";
  } else {
    if (rank == 0 && stack::isContactProblem(set.scene))
      std::cout << "  solver chain: " << stack::describeSolverChain(set.scene, params) << "\n";
    core::ScopedPhase phase("Solve");
    // A load history writes its result as it goes (checkpoints; rank 0 holds no written step),
    // with or without a result file. The observer is given on every rank (the stack's calls of
    // it may be collective); only rank 0 works.
    stack::StepObserver afterStep;
    if (set.scene.loadHistory) {
      taken.emplace(set.scene, resultFiles.exodus.get(), params.sublist("Load Steps").get<double>("Checkpoint Seconds"),
                    infoRecords(argc, argv, params), rank);
      afterStep = std::ref(*taken);
    }
    solve = stack::solveScene(set.scene, std::move(set.systems), set.B, params, MPI_COMM_WORLD, total, afterStep);
    if (taken && !cl.output.empty()) summary["checkpoints"] = taken->checkpoints();
    status = solve.converged() ? core::kExitOk : core::kExitNotConverged;
    stack::addSolveSummary(solve, params, summary);
    if (rank == 0) std::cout << stack::solveReport(solve);
  }
  summary["times"]["total_s"] = total.seconds();

  // (5) Results on rank 0, which holds the global displacement and reactions: one time step,
  // or one per load step solved (the earlier steps' results, then the last state).
  std::vector<stack::StressResults> stress;
  std::optional<core::ScopedPhase> resultsPhase(std::in_place, "Results: stresses and reactions");
  if (rank == 0 && !cl.dryRun) output.steps = resultSteps(set.scene, solve, taken ? &*taken : nullptr, summary, stress);
  // Peak memory per rank (KiB) after the solve and the stresses; rank 0's own figure is read
  // again after writing the Exodus result, just before the summary.
  std::vector<long> maxRssPerRankKb = gatherPeakRssKb(rank);
  resultsPhase.reset();
  // The phases up to here (the files are written after the summary is complete).
  const auto phases = core::finishPhaseTimers(Teuchos::MpiComm<int>(MPI_COMM_WORLD));
  stack::addTimersToSummary(phases, summary);
  if (rank == 0 && !cl.dryRun) std::cout << stack::timingTable(phases);
  if (rank == 0) writeResults(argc, argv, start, set.scene, output, taken ? &*taken : nullptr, maxRssPerRankKb, summary);  // (6)
  return status;
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
  if (const int refused = driver::prepareProcess(argv); refused != 0) return refused;
  lineBufferedOutput();
  // A file size limit (ulimit -f) makes a write fail with EFBIG, an I/O error the run reports
  // (exit 4, nothing partial left), instead of killing the process in the middle of a write.
  std::signal(SIGXFSZ, SIG_IGN);
  // A pipe or FIFO whose reader went away makes the write fail with EPIPE (exit 4, said as
  // such) instead of killing rank 0 without a word.
  std::signal(SIGPIPE, SIG_IGN);
  core::chooseQuickSingletonStart();  // one process without mpirun: MPI_Init 0.39 -> 0.04 s (doc/measurements/performance.md)
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
