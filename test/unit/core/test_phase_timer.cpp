// The run's phase timers (core/PhaseTimer.hpp) on Teuchos::StackedTimer: nested paths in the
// order of first start, calls counted, nothing without a start, seconds reduced over the
// ranks when every rank ran the same phases and rank 0's (flagged) otherwise.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>

#include <chrono>
#include <thread>

#include "tribos/core/PhaseTimer.hpp"

using tribos::core::PhaseTime;
using tribos::core::ScopedPhase;

namespace {
const Teuchos::MpiComm<int>& world() {
  static const Teuchos::MpiComm<int> comm(MPI_COMM_WORLD);
  return comm;
}
void sleepMs(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }
}  // namespace

TEST(PhaseTimer, nestsByScopeCountsCallsAndReducesOverTheRanks) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  tribos::core::startPhaseTimers("run");
  {
    ScopedPhase setUp("Set-up");
    {
      ScopedPhase mesh("Set-up: mesh");
      sleepMs(5 + 20 * rank);  // the slowest rank sets max_s
    }
  }
  for (int k = 0; k < 3; ++k) {
    ScopedPhase solve("Solve");
    sleepMs(2);
  }
  bool same = false;
  const auto phases = tribos::core::finishPhaseTimers(world(), &same);
  EXPECT_TRUE(same);
  ASSERT_EQ(phases.size(), 4u);
  EXPECT_EQ(phases[0].path, "run");
  EXPECT_EQ(phases[1].path, "run@Set-up");
  EXPECT_EQ(phases[2].path, "run@Set-up@Set-up: mesh");
  EXPECT_EQ(phases[3].path, "run@Solve");
  EXPECT_EQ(phases[3].calls, 3);
  EXPECT_EQ(phases[2].calls, 1);
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  EXPECT_GE(phases[2].maxSeconds, 0.004 + 0.02 * (size - 1));  // the slowest rank's
  EXPECT_LE(phases[2].minSeconds, phases[2].maxSeconds);
  EXPECT_GE(phases[1].maxSeconds, phases[2].minSeconds);  // a phase holds its children
  EXPECT_GE(phases[0].maxSeconds, phases[1].minSeconds + phases[3].minSeconds);
}

TEST(PhaseTimer, doesNothingWithoutAStart) {
  { ScopedPhase phase("Alone"); }
  EXPECT_TRUE(tribos::core::finishPhaseTimers(world()).empty());
}

TEST(PhaseTimer, phasesThatDifferBetweenRanksAreRankZerosAndFlagged) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  tribos::core::startPhaseTimers("run");
  if (rank == 0) {
    ScopedPhase only("Rank 0 only");
  }
  bool same = true;
  const auto phases = tribos::core::finishPhaseTimers(world(), &same);
  EXPECT_EQ(same, size == 1);
  EXPECT_EQ(phases.size(), rank == 0 ? 2u : 1u);
}
