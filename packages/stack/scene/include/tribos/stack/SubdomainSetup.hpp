#pragma once
// Set-up phase shared by --dry-run and the full run: every rank assembles the subdomain
// systems it owns (threads over subdomains) and the global dimensions are reduced.
#include <mpi.h>

#include <vector>

#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::stack {

struct SetupReport {
  long long nPrimal = 0;        ///< n: sum of subdomain dofs (paper Table 1)
  long long nRigid = 0;         ///< l: 6 per subdomain
  long long nnz = 0;            ///< stored entries of all K_s
  int nSubdomains = 0;
  int nRanks = 1;
  int nThreads = 1;
  double assemblySeconds = 0.0; ///< slowest rank
};

/// Assembles K_s, f_s, R_s of the subdomains owned by this rank into `systems` (index =
/// local subdomain) and returns the reduced dimensions. Collective over `comm`.
SetupReport assembleOwnedSubdomains(const Scene& scene, MPI_Comm comm,
                                    std::vector<fem::SubdomainSystem>& systems);

}  // namespace tribos::stack
