// GoogleTest main for every Tribos test: MPI and Kokkos live for the whole run, only rank 0
// prints, and a failure on any rank makes every rank exit non-zero.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Tpetra_Core.hpp>

#include "tribos/core/Parallel.hpp"

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  int result = 0;
  {
    Tpetra::ScopeGuard tpetra(&argc, &argv);  // Kokkos too; MPI is already up
    tribos::core::warmUpKokkosForThreads();
    ::testing::InitGoogleTest(&argc, argv);
    if (rank != 0) {
      auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
    }
    result = RUN_ALL_TESTS();
  }
  int worst = 0;
  MPI_Allreduce(&result, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
