#pragma once
/// \file SingletonStart.hpp
/// A process started without mpirun (an MPI singleton: `tribos --input x.xml`, a unit test)
/// spent 0.39 s of its 0.5 s start-up in MPI_Init: Open MPI 4.1 starts an `orted` daemon for a
/// singleton and selects the UCX point-to-point layer, which probes the network devices
/// (measured on Debian 12's Open MPI 4.1.4, a bare MPI_Init: 0.389 s; isolated singleton 0.255 s;
/// isolated with the ob1 layer 0.039 s). One process talks to no other, so neither is needed.

namespace tribos::core {

/// Before MPI_Init: when no launcher started this process (none of OMPI_COMM_WORLD_SIZE,
/// PMIX_RANK, PMI_RANK, PMI_SIZE is set), sets OMPI_MCA_ess_singleton_isolated=1 (no daemon)
/// with a session directory of the process's own (OMPI_MCA_orte_jobfam_session_dir: isolated
/// singletons would otherwise share one) and OMPI_MCA_pml=ob1 (no UCX), each unless the
/// environment already chooses it (a user's own isolated setting keeps Open MPI's directory). Processes that
/// mpirun or srun start keep the site's choice (UCX is what carries InfiniBand). Returns
/// whether it set anything.
bool chooseQuickSingletonStart();

}  // namespace tribos::core
