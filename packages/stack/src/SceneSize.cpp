#include "tribos/stack/SceneSize.hpp"

#include <Teuchos_ParameterList.hpp>

#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/TwoBricks.hpp"

namespace tribos::stack {

namespace {
// Lower bounds, well under what a run was measured to take (two_bricks.xml, H/h = 12: 1.3 kB
// per primal unknown in a dry run, 2.8 kB with the solve), so that only scenes that surely
// cannot fit are refused: a tetrahedron's 4 node indices, block and subdomain; a node's
// coordinates; a primal unknown's stiffness row (81 nonzeros of 12 bytes) at half.
constexpr double kBytesPerTetrahedron = 24.0;
constexpr double kBytesPerNode = 24.0;
constexpr double kBytesPerPrimalUnknown = 500.0;

double physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize) : HUGE_VAL;
}

std::string gib(double bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g GiB", bytes / (1024.0 * 1024.0 * 1024.0));
  return text;
}

std::string count(double n) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", n);
  return text;
}
}  // namespace

double SceneSize::bytesPerMachine(int ranksHere, int ranks) const {
  const double mesh = tetrahedra * kBytesPerTetrahedron + nodes * kBytesPerNode;
  return ranksHere * mesh + primalUnknowns * kBytesPerPrimalUnknown * ranksHere / std::max(ranks, 1);
}

SceneSize estimateSceneSize(const Teuchos::ParameterList& tribos) {
  const auto& meshList = tribos.sublist("Mesh");
  SceneSize size;
  if (meshList.get<std::string>("Generator") != "Two Bricks") return size;
  const auto grid =
      mesh::BrickGrid::parse(meshList.get<std::string>("Subdomains Per Brick"), "Mesh/Subdomains Per Brick");
  const double h = meshList.get<int>("H Over h");
  // Two bricks of nx*ny*nz subdomains of (H/h)^3 cubes, 5 tetrahedra per cube.
  const double nodesPerBrick = (grid.nx * h + 1.0) * (grid.ny * h + 1.0) * (grid.nz * h + 1.0);
  size.tetrahedra = 2.0 * 5.0 * grid.nx * grid.ny * grid.nz * h * h * h;
  size.nodes = 2.0 * nodesPerBrick;
  size.primalUnknowns = 3.0 * size.nodes;
  return size;
}

void requireSceneFitsInMemory(const Teuchos::ParameterList& tribos, const std::string& source, MPI_Comm comm) {
  const SceneSize size = estimateSceneSize(tribos);
  const auto& meshList = tribos.sublist("Mesh");
  const std::string scene = source + ": Mesh: Subdomains Per Brick = " +
                            meshList.get<std::string>("Subdomains Per Brick") + " with H Over h = " +
                            std::to_string(meshList.get<int>("H Over h")) + " make " + count(size.tetrahedra) +
                            " tetrahedra and " + count(size.nodes) + " nodes";
  core::requireInput(size.tetrahedra <= INT_MAX && size.nodes <= INT_MAX,
                     scene + ", more than 32-bit local indices count (" + count(INT_MAX) +
                         "); reduce H Over h or the subdomains");
  // The machine with the least memory, and the most ranks on one machine (ranks that share
  // memory form one MPI_COMM_TYPE_SHARED group): the same numbers on every rank.
  MPI_Comm machine;
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &machine);
  int ranksHere = 1, ranks = 1, mostRanksHere = 1;
  MPI_Comm_size(machine, &ranksHere);
  MPI_Comm_free(&machine);
  MPI_Comm_size(comm, &ranks);
  double leastMemory = physicalMemoryBytes();
  MPI_Allreduce(MPI_IN_PLACE, &leastMemory, 1, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&ranksHere, &mostRanksHere, 1, MPI_INT, MPI_MAX, comm);
  const double needed = size.bytesPerMachine(mostRanksHere, ranks);
  core::requireInput(needed <= leastMemory,
                     scene + " (" + count(size.primalUnknowns) + " primal unknowns at least), which need at least " +
                         gib(needed) + " of memory on a machine running " + std::to_string(mostRanksHere) +
                         " rank(s) (each rank holds the whole mesh); it has " + gib(leastMemory) +
                         ". Reduce Mesh/H Over h or Mesh/Subdomains Per Brick");
}

}  // namespace tribos::stack
