// Solver/Max Seconds as one deadline from the start of the run: no deadline never stops;
// a passed one stops every rank together, with the message that names the parameter.
#include <gtest/gtest.h>
#include <mpi.h>

#include <thread>

#include "tribos/core/Deadline.hpp"
#include "tribos/core/Errors.hpp"

using tribos::core::Deadline;
using tribos::core::LimitReached;

TEST(Deadline, noneNeverPasses) {
  const Deadline none;
  EXPECT_FALSE(none.limited());
  EXPECT_FALSE(none.passed());
  EXPECT_NO_THROW(none.check("the assembly", MPI_COMM_WORLD));
  EXPECT_NO_THROW(none.agree(true, "the factorisation", MPI_COMM_WORLD));
}

TEST(Deadline, countsFromTheStartItIsGiven) {
  const tribos::core::Stopwatch start;
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  const Deadline deadline(0.02, start);
  EXPECT_TRUE(deadline.passed());
  try {
    deadline.check("the assembly", MPI_COMM_WORLD);
    FAIL() << "nothing thrown";
  } catch (const LimitReached& e) {
    EXPECT_NE(std::string(e.what()).find("stopped: Solver/Max Seconds = 0.02 reached after"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("during the assembly"), std::string::npos);
  }
  EXPECT_FALSE(Deadline(100.0, start).passed());
  EXPECT_NO_THROW(Deadline(100.0, start).check("the assembly", MPI_COMM_WORLD));
}

// Every rank throws when any rank stopped its loop early (run on 2 ranks: only rank 1 stops).
TEST(Deadline, oneRankStoppingStopsEveryRank) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const Deadline deadline(100.0, tribos::core::Stopwatch());
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const bool stoppedHere = rank == size - 1;
  EXPECT_THROW(deadline.agree(stoppedHere, "the factorisation", MPI_COMM_WORLD), LimitReached);
  EXPECT_NO_THROW(deadline.agree(false, "the factorisation", MPI_COMM_WORLD));
}
