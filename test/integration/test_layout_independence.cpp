// The solver's iteration counts do not depend on the rank x thread layout (issue 9): the
// Table 1 cell 2x1x1 / H/h = 3 through the driver on 1 and 2 ranks, each with 1 and 2
// threads. What made them differ before: CHOLMOD factorised supernodally alone and
// simplicially in a thread team (now by matrix size only), and the dual map's global ids,
// which the power method's start vector depends on, followed the rank count (now
// ConstraintMatrix::rowId). On one rank count the results are bitwise equal for any number
// of threads (every per-subdomain operation runs in full on one thread, sums in a fixed
// order); across rank counts only the reductions' rounding differs.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
struct Layout {
  int ranks, threads;
};

nlohmann::json solve(const Layout& layout, const std::filesystem::path& dir) {
  const auto summary = dir / ("summary_np" + std::to_string(layout.ranks) + "_t" + std::to_string(layout.threads) + ".json");
  const std::string command =
      std::string(TRIBOS_MPIEXEC) + " --allow-run-as-root --oversubscribe --bind-to none -x OMP_NUM_THREADS=" +
      std::to_string(layout.threads) + " -x OMP_WAIT_POLICY=PASSIVE -np " + std::to_string(layout.ranks) + " " +
      TRIBOS_DRIVER + " --input " + tribos::test::quote(tribos::test::sourceDir() + "/input/two_bricks.xml") +
      " --set 'Mesh/Subdomains Per Brick=2x1x1' --set 'Mesh/H Over h=3' --set Solver/Verbose=false --summary " +
      summary.string();
  const auto run = tribos::test::runCommand(command);
  EXPECT_EQ(run.status, 0) << command << "\n" << run.output;
  std::ifstream in(summary);
  if (!in) return {};
  return nlohmann::json::parse(in);
}
}  // namespace

TEST(tribosDriver, sameIterationCountsOnEveryRankAndThreadLayout) {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_layout_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto reference = solve({1, 1}, dir);
  ASSERT_FALSE(reference.is_null());
  ASSERT_TRUE(reference["converged"].get<bool>());
  for (const Layout layout : {Layout{1, 2}, Layout{2, 1}, Layout{2, 2}}) {
    SCOPED_TRACE(std::to_string(layout.ranks) + " rank(s) x " + std::to_string(layout.threads) + " thread(s)");
    const auto j = solve(layout, dir);
    ASSERT_FALSE(j.is_null());
    EXPECT_EQ(j["n_ranks"], layout.ranks);
    EXPECT_EQ(j["n_threads"], layout.threads);
    for (const char* count : {"outer_iterations", "inner_iterations", "pfp_applications", "f_applications", "cg_steps",
                              "expansion_steps", "proportioning_steps", "fixed_point_iterations"})
      EXPECT_EQ(j[count], reference[count]) << count;
    const double energy = j["energy"], referenceEnergy = reference["energy"];
    if (layout.ranks == 1)
      EXPECT_EQ(energy, referenceEnergy);  // bitwise: threads change nothing
    else
      EXPECT_NEAR(energy, referenceEnergy, 1e-12 * std::abs(referenceEnergy));
  }
  std::filesystem::remove_all(dir);
}
