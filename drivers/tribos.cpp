// tribos: the main driver. Reads a Teuchos XML scene, builds the mesh and its T-FETI
// decomposition, assembles every subdomain, and writes the Exodus results and a JSON
// summary. Sample runs:
//   tribos --input input/two_bricks.xml --dry-run
//   tribos --input input/two_bricks.xml --set "Mesh/H Over h=4" --summary s.json --output r.exo
//   mpirun --allow-run-as-root -np 4 tribos --input input/two_bricks.xml --dry-run
//
// The contact solver (T-FETI dual operator, SMALSE-M, MPGP, Coulomb fixed point) is not in
// this version yet: a run without --dry-run performs the set-up and says so.
#include <mpi.h>

#include <Kokkos_Core.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "CommandLine.hpp"
#include "tribos/stack/SubdomainSetup.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"

namespace {
using namespace tribos;

// Rank 0 reads the file; every rank parses the same text, so every rank sees the same
// parameters and the same errors.
Teuchos::ParameterList readSceneXml(const std::string& path, int rank) {
  std::string text;
  long long length = -1;
  if (rank == 0) {
    std::ifstream in(path);
    if (in) {
      std::ostringstream buffer;
      buffer << in.rdbuf();
      text = buffer.str();
      length = static_cast<long long>(text.size());
    }
  }
  MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  if (length < 0) throw core::InputError(path + ": cannot open the scene file");
  text.resize(static_cast<size_t>(length));
  MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD);
  Teuchos::RCP<Teuchos::ParameterList> list;
  try {
    list = Teuchos::getParametersFromXmlString(text);
  } catch (const std::exception& e) {
    throw core::InputError(path + ": not a valid Teuchos XML parameter list: " + e.what());
  }
  if (list->name() != "Tribos")
    throw core::InputError(path + ": the top-level ParameterList must be named \"Tribos\", not \"" +
                           list->name() + "\"");
  return *list;
}

nlohmann::json summaryJson(const stack::Scene& scene, const stack::SetupReport& report,
                           const driver::CommandLine& cl, double setupSeconds, double totalSeconds) {
  nlohmann::json j;
  j["input"] = cl.input;
  j["dry_run"] = cl.dryRun;
  j["solver"] = "not available in this version: set-up only";
  j["n_primal"] = report.nPrimal;
  j["n_rigid"] = report.nRigid;
  j["n_subdomains"] = report.nSubdomains;
  j["n_ranks"] = report.nRanks;
  j["n_threads"] = report.nThreads;
  j["n_nodes"] = scene.mesh.numNodes();
  j["n_elements"] = scene.mesh.numElements();
  j["stiffness_nonzeros"] = report.nnz;
  j["times"] = {{"mesh_s", scene.meshSeconds},
                {"decomposition_s", scene.decompositionSeconds},
                {"assembly_s", report.assemblySeconds},
                {"setup_s", setupSeconds},
                {"total_s", totalSeconds}};
  return j;
}

void writeOutput(const std::string& path, const stack::Scene& scene) {
  mesh::TimeStep step;
  step.time = 0.0;
  mesh::Field subdomain{"subdomain", std::vector<double>(scene.mesh.numElements())};
  for (LO e = 0; e < scene.mesh.numElements(); ++e) subdomain.values[e] = scene.decomposition.elementPart[e];
  step.element.push_back(std::move(subdomain));
  mesh::writeExodus(path, scene.mesh, {step});
}

int run(int argc, char** argv, int rank) {
  core::Stopwatch total;
  // (1) Command line.
  const driver::CommandLine cl = driver::parseCommandLine(argc, argv);
  const auto valid = stack::sceneValidParameters();
  if (cl.help) {
    if (rank == 0) std::cout << driver::usage();
    return core::kExitOk;
  }
  if (cl.listParameters) {
    if (rank == 0) std::cout << core::describeParameters(*valid);
    return core::kExitOk;
  }

  // (2) Scene parameters: XML, command-line overrides, validation against every component.
  Teuchos::ParameterList params = readSceneXml(cl.input, rank);
  for (const auto& assignment : cl.overrides) core::applyOverride(params, *valid, assignment);
  core::validateAndSetDefaults(params, *valid, cl.input);
  if (const int threads = params.sublist("Parallel").get<int>("Threads"); threads > 0)
    core::setNumThreads(threads);

  // (3) Mesh, decomposition, per-subdomain assembly.
  core::Stopwatch setup;
  const stack::Scene scene = stack::buildScene(params, cl.input);
  std::vector<fem::SubdomainSystem> systems;
  const stack::SetupReport report = stack::assembleOwnedSubdomains(scene, MPI_COMM_WORLD, systems);
  const double setupSeconds = setup.seconds();

  // (4) Report and results.
  if (rank == 0) {
    std::cout << "tribos: " << cl.input << "\n"
              << "  mesh: " << scene.mesh.numNodes() << " nodes, " << scene.mesh.numElements()
              << " tetrahedra, " << scene.mesh.numBlocks() << " bodies\n"
              << "  subdomains: " << report.nSubdomains << " on " << report.nRanks << " rank(s) x "
              << report.nThreads << " thread(s)\n"
              << "  n_primal = " << report.nPrimal << ", n_rigid = " << report.nRigid << "\n"
              << "  set-up: " << setupSeconds << " s (assembly " << report.assemblySeconds << " s)\n";
    if (!cl.dryRun)
      std::cout << "  note: the contact solver is not available in this version; only the set-up "
                   "(mesh, decomposition, subdomain stiffness, loads, rigid body modes) was run.\n";
    if (!cl.output.empty()) {
      writeOutput(cl.output, scene);
      std::cout << "  wrote " << cl.output << "\n";
    }
    if (!cl.summary.empty()) {
      std::ofstream out(cl.summary);
      if (!out) throw core::InputError(cl.summary + ": cannot write the summary file");
      out << summaryJson(scene, report, cl, setupSeconds, total.seconds()).dump(2) << "\n";
      std::cout << "  wrote " << cl.summary << "\n";
    }
  }
  return core::kExitOk;
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  int status = core::kExitOk;
  {
    Kokkos::ScopeGuard kokkos(argc, argv);
    core::warmUpKokkosForThreads();
    try {
      status = run(argc, argv, rank);
    } catch (const core::InputError& e) {
      // Input errors are the same on every rank (every rank parses the same input).
      if (rank == 0) std::cerr << "tribos: error: " << e.what() << "\n";
      status = core::kExitBadInput;
    } catch (const std::exception& e) {
      std::cerr << "tribos: internal error on rank " << rank << ": " << e.what() << "\n";
      status = core::kExitInternal;
    }
    // A rank that failed alone would leave the others waiting in a collective.
    if (status != core::kExitOk && size > 1) MPI_Abort(MPI_COMM_WORLD, status);
  }
  MPI_Finalize();
  return status;
}
