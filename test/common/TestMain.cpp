// GoogleTest main for every Tribos test: MPI and Kokkos live for the whole run, only rank 0
// prints, and a failure on any rank makes every rank exit non-zero.
//
// A test that fails on one rank only (an exception, or an ASSERT that returns early) may
// skip a collective that the other ranks then wait in forever. After every test the ranks
// meet (core::RankErrors::meet): a rank where the test failed waits a few seconds for the
// others and otherwise aborts the job with a message naming the test and the rank, so a
// broken MPI test fails in seconds instead of hanging until CTest's timeout.
#include <gtest/gtest.h>
#include <mpi.h>

#include <exception>
#include <iostream>

#include <Tpetra_Core.hpp>

#include "tribos/core/Parallel.hpp"
#include "tribos/core/RankErrors.hpp"
#include "tribos/core/SingletonStart.hpp"

namespace {
class MeetAfterEachTest : public ::testing::EmptyTestEventListener {
 public:
  explicit MeetAfterEachTest(tribos::core::RankErrors& errors) : errors_(errors) {}
  void OnTestEnd(const ::testing::TestInfo& test) override {
    std::string what = std::string("test ") + test.test_suite_name() + "." + test.name();
    // Ranks other than 0 print nothing: if this rank aborts the job, its first failure is
    // what the user sees.
    const auto& result = *test.result();
    for (int i = 0; i < result.total_part_count(); ++i)
      if (result.GetTestPartResult(i).failed()) {
        const auto& part = result.GetTestPartResult(i);
        const std::string where =
            part.file_name() ? std::string(part.file_name()) + ":" + std::to_string(part.line_number()) + ": " : "";
        what += " (" + where + part.summary() + ")";
        break;
      }
    errors_.meet(result.Failed(), what);
  }

 private:
  tribos::core::RankErrors& errors_;
};

// An exception outside any test (GoogleTest catches those inside) ends the whole job at
// once, with the rank, instead of leaving the other ranks waiting for this one.
void abortJobOnUncaughtException() {
  std::set_terminate([] {
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    std::cerr << "uncaught exception on rank " << rank;
    try {
      if (auto current = std::current_exception()) std::rethrow_exception(current);
    } catch (const std::exception& e) {
      std::cerr << ": " << e.what();
    } catch (...) {
    }
    std::cerr << ": aborting all ranks" << std::endl;
    MPI_Abort(MPI_COMM_WORLD, 1);
    std::abort();
  });
}
}  // namespace

int main(int argc, char** argv) {
  tribos::core::chooseQuickSingletonStart();  // a test run without mpirun starts in 0.04 s, not 0.4 s
  MPI_Init(&argc, &argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  abortJobOnUncaughtException();
  int result = 0;
  {
    tribos::core::RankErrors errors;
    Tpetra::ScopeGuard tpetra(&argc, &argv);  // Kokkos too; MPI is already up
    tribos::core::warmUpKokkosForThreads();
    ::testing::InitGoogleTest(&argc, argv);
    auto& listeners = ::testing::UnitTest::GetInstance()->listeners();
    if (rank != 0) delete listeners.Release(listeners.default_result_printer());
    listeners.Append(new MeetAfterEachTest(errors));  // GoogleTest owns and deletes it
    result = RUN_ALL_TESTS();
  }
  int worst = 0;
  MPI_Allreduce(&result, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
