#include "tribos/stack/SubdomainSetup.hpp"

#include "tribos/core/Parallel.hpp"
#include "tribos/core/Timer.hpp"

namespace tribos::stack {

SetupReport assembleOwnedSubdomains(const Scene& scene, MPI_Comm comm,
                                    std::vector<fem::SubdomainSystem>& systems) {
  SetupReport report;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &report.nRanks);
  report.nSubdomains = scene.decomposition.numSubdomains();
  report.nThreads = core::numThreads();

  const int first = mesh::firstSubdomain(rank, report.nSubdomains, report.nRanks);
  const int last = mesh::firstSubdomain(rank + 1, report.nSubdomains, report.nRanks);
  // One slot per owned subdomain, allocated before the threads start (TOOLCHAIN.md rule 1).
  systems.assign(last - first, fem::SubdomainSystem{});
  core::Stopwatch watch;
  core::forEachSubdomain(last - first, [&](int i) {
    const auto& subdomain = scene.decomposition.subdomains[first + i];
    systems[i] = fem::assembleSubdomain(scene.mesh, subdomain, scene.materials, scene.loads);
    if (scene.loadHistory)  // each load on its own for the history (the elements go after the set-up)
      for (const auto& named : scene.namedLoads)
        systems[i].loadParts.push_back(fem::assembleSubdomainLoads(scene.mesh, subdomain, scene.materials, named.second));
  });
  const double seconds = watch.seconds();

  long long local[3] = {0, 0, 0};
  for (const auto& s : systems) {
    local[0] += s.K.n;
    local[1] += 6;
    local[2] += static_cast<long long>(s.K.values.size());
  }
  long long global[3];
  MPI_Allreduce(local, global, 3, MPI_LONG_LONG, MPI_SUM, comm);
  report.nPrimal = global[0];
  report.nRigid = global[1];
  report.nnz = global[2];
  MPI_Allreduce(&seconds, &report.assemblySeconds, 1, MPI_DOUBLE, MPI_MAX, comm);
  return report;
}

}  // namespace tribos::stack
