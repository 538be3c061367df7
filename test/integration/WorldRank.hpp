#pragma once
// The rank of this process in MPI_COMM_WORLD (tests check results on rank 0), shared by the
// scene helpers so that a test can use several of them.
#include <mpi.h>

namespace tribos::test {

inline int worldRank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

}  // namespace tribos::test
