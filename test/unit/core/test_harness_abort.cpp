// Deliberately failing: rank 1 throws inside a test while rank 0 waits for it in a
// collective. Without the harness's meeting after each test (TestMain.cpp) this run would
// hang until CTest's timeout; with it, rank 1 aborts the job within seconds and names the
// test, its rank and its failure. CTest (core.TestMain.oneRankThrowingEndsEveryRank_np2)
// passes when that message appears in time.
#include <gtest/gtest.h>
#include <mpi.h>

#include <stdexcept>

TEST(DeliberateFailure, oneRankThrowsWhileTheOtherWaitsInACollective) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 1) throw std::runtime_error("thrown on rank 1 only");
  MPI_Barrier(MPI_COMM_WORLD);
}
