// Errors on some MPI ranks only, run through core::RankErrors as the tribos driver does
// (CTest integration.rankErrors.*, with expect_run.sh checking status, text and time):
//   rank_faults input-error-on-rank-1      rank 1 fails, rank 0 finishes its work
//   rank_faults input-error-while-waiting  rank 1 fails, rank 0 waits in a collective forever
//   rank_faults same-error-everywhere      every rank fails with the same message
//   rank_faults internal-and-input         rank 0 internal error, the others bad input
//   rank_faults not-converged              every rank ends with status 3
#include <mpi.h>

#include <iostream>
#include <stdexcept>
#include <string>

#include "tribos/core/Errors.hpp"
#include "tribos/core/RankErrors.hpp"

namespace {
using namespace tribos;

core::RankOutcome runScenario(const std::string& scenario, int rank) {
  try {
    if (scenario == "input-error-on-rank-1") {
      if (rank == 1) throw core::InputError("mesh.exo: node 7 exists only on rank 1");
    } else if (scenario == "input-error-while-waiting") {
      if (rank == 1) throw core::InputError("mesh.exo: rank 1 gave up before the collective");
      MPI_Barrier(MPI_COMM_WORLD);  // rank 1 never comes
    } else if (scenario == "same-error-everywhere") {
      throw core::InputError("scene.xml: the same error on every rank");
    } else if (scenario == "internal-and-input") {
      if (rank == 0) throw std::runtime_error("a consequence on rank 0");
      throw core::InputError("scene.xml: the cause on the other ranks");
    } else if (scenario == "not-converged") {
      return {core::kExitNotConverged, ""};
    } else {
      throw std::invalid_argument("unknown scenario " + scenario);
    }
    return {core::kExitOk, ""};
  } catch (const core::InputError& e) {
    return {core::kExitBadInput, std::string("error: ") + e.what()};
  } catch (const std::exception& e) {
    return {core::kExitInternal, std::string("internal error: ") + e.what()};
  }
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int status = 0;
  {
    core::RankErrors errors;
    status = errors.finish(runScenario(argc > 1 ? argv[1] : "", rank), "rank_faults");
  }
  MPI_Finalize();
  return status;
}
