#include "tribos/stack/SceneSize.hpp"

#include <Teuchos_ParameterList.hpp>

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cctype>
#include <filesystem>
#include <fstream>

#include "tribos/core/Errors.hpp"
#include "tribos/stack/Scene.hpp"
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
// A subdomain factor of n unknowns holds at least kFactorFill n^(4/3) nonzeros of 8 bytes
// (nested dissection in 3D). Measured on the bricks' cube subdomains (2x1x1, factor_nonzeros
// of the summary): 5.2, 6.1, 7.3, 8.3 n^(4/3) at H/h = 6, 10, 14, 18.
constexpr double kFactorFill = 5.0;
constexpr double kBytesPerFactorNonzero = 8.0;

double physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize) : HUGE_VAL;
}

/// A number in a cgroup file ("max", absent or unreadable: HUGE_VAL).
double cgroupValue(const std::string& path) {
  std::ifstream in(path);
  std::string text;
  if (in >> text && !text.empty() && std::isdigit(static_cast<unsigned char>(text[0])))
    return std::strtod(text.c_str(), nullptr);
  return HUGE_VAL;
}

/// The least memory limit of this process's cgroup and the cgroups above it (v2 memory.max,
/// v1 memory.limit_in_bytes): a job step of a batch system sits in a cgroup of its own.
/// HUGE_VAL when there is none or it cannot be read.
double cgroupLimitBytes() {
  std::ifstream self("/proc/self/cgroup");
  double least = HUGE_VAL;
  for (std::string line; std::getline(self, line);) {
    // "0::/path" (v2) or "N:memory:/path" (v1; possibly among other controllers).
    const auto first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::filesystem::path root, file;
    if (controllers.empty()) {
      root = "/sys/fs/cgroup";
      file = "memory.max";
    } else if (("," + controllers + ",").find(",memory,") != std::string::npos) {
      root = "/sys/fs/cgroup/memory";
      file = "memory.limit_in_bytes";
    } else {
      continue;
    }
    for (std::filesystem::path dir = root / line.substr(second + 2);; dir = dir.parent_path()) {
      least = std::min(least, cgroupValue((dir / file).string()));
      if (dir == root || !dir.has_relative_path() || dir.string().size() <= root.string().size()) break;
    }
  }
  return least;
}

/// What this process may still map under its address-space limit (ulimit -v): the limit less
/// what it maps already (libraries, MPI and Kokkos); HUGE_VAL without a limit.
double addressSpaceLeftBytes() {
  struct rlimit limit {};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return HUGE_VAL;
  std::ifstream statm("/proc/self/statm");
  double mappedPages = 0.0;
  statm >> mappedPages;
  return static_cast<double>(limit.rlim_cur) - mappedPages * static_cast<double>(sysconf(_SC_PAGE_SIZE));
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

double SceneSize::bytesPerMachine(int ranksHere, int ranks, bool solving) const {
  const double mesh = tetrahedra * kBytesPerTetrahedron + nodes * kBytesPerNode;
  const double matrices =
      primalUnknowns * kBytesPerPrimalUnknown + (solving ? factorNonzeros * kBytesPerFactorNonzero : 0.0);
  return ranksHere * mesh + matrices * ranksHere / std::max(ranks, 1);
}

SceneSize estimateSceneSize(const Teuchos::ParameterList& tribos) {
  const auto& meshList = tribos.sublist("Mesh");
  SceneSize size;
  if (meshGenerator(meshList) != MeshGenerator::TwoBricks) return size;
  const auto grid =
      mesh::BrickGrid::parse(meshList.get<std::string>("Subdomains Per Brick"), "Mesh/Subdomains Per Brick");
  const double h = meshList.get<int>("H Over h");
  // Two bricks of nx*ny*nz subdomains of (H/h)^3 cubes, 5 tetrahedra per cube.
  const double nodesPerBrick = (grid.nx * h + 1.0) * (grid.ny * h + 1.0) * (grid.nz * h + 1.0);
  const double subdomains = 2.0 * grid.nx * grid.ny * grid.nz;
  size.tetrahedra = 5.0 * subdomains * h * h * h;
  size.nodes = 2.0 * nodesPerBrick;
  size.primalUnknowns = 3.0 * size.nodes;
  size.factorNonzeros = subdomains * kFactorFill * std::pow(3.0 * (h + 1.0) * (h + 1.0) * (h + 1.0), 4.0 / 3.0);
  return size;
}

void requireSceneFitsInMemory(const Teuchos::ParameterList& tribos, const std::string& source, MPI_Comm comm,
                              bool solving) {
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
  double leastMemory[2] = {std::min(physicalMemoryBytes(), cgroupLimitBytes()), addressSpaceLeftBytes()};
  MPI_Allreduce(MPI_IN_PLACE, leastMemory, 2, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(&ranksHere, &mostRanksHere, 1, MPI_INT, MPI_MAX, comm);
  const std::string what = scene + " (" + count(size.primalUnknowns) + " primal unknowns" +
                           (solving ? ", " + count(size.factorNonzeros) + " factor nonzeros" : std::string()) +
                           " at least), which need at least ";
  const std::string advice = ". Reduce Mesh/H Over h or Mesh/Subdomains Per Brick";
  const double needed = size.bytesPerMachine(mostRanksHere, ranks, solving);
  core::requireInput(needed <= leastMemory[0],
                     what + gib(needed) + " of memory on a machine running " + std::to_string(mostRanksHere) +
                         " rank(s) (each rank holds the whole mesh); it has " + gib(leastMemory[0]) +
                         " (physical memory or the cgroup's limit)" + advice);
  const double neededByOneRank = size.bytesPerMachine(1, ranks, solving);
  core::requireInput(neededByOneRank <= leastMemory[1],
                     what + gib(neededByOneRank) + " per rank; a rank may map only " + gib(leastMemory[1]) +
                         " more under its address-space limit (ulimit -v)" + advice +
                         ", or raise the limit");
}

void requireHistoryFitsInMemory(int loadSteps, MPI_Comm comm) {
  if (loadSteps <= 1) return;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  double memory = std::min({physicalMemoryBytes(), cgroupLimitBytes(), addressSpaceLeftBytes()});
  MPI_Bcast(&memory, 1, MPI_DOUBLE, 0, comm);  // rank 0's: it keeps the steps' records
  const double needed = loadSteps * kHeldBytesPerStep;
  core::requireInput(needed <= 0.5 * memory,
                     "Load Steps/Number Of Steps = " + std::to_string(loadSteps) + ": rank 0 keeps a summary entry of "
                     "every step until the end of the run, at least " + gib(needed) + ", more than half of the " +
                         gib(memory) + " it has (physical memory, the cgroup's limit or ulimit -v); give fewer "
                         "steps, or split the history with Load Steps/Restart From");
}

}  // namespace tribos::stack
