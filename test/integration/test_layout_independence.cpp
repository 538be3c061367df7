// The solver's iteration counts do not depend on the rank x thread layout (issue 9): the
// Table 1 cell 2x1x1 / H/h = 3 through the driver on 1 and 2 ranks, each with 1 and 2
// threads. What made them differ before: CHOLMOD factorised supernodally alone and
// simplicially in a thread team (now by matrix size only), and the dual map's global ids,
// which the power method's start vector depends on, followed the rank count (now
// ConstraintMatrix::rowId). The results are bitwise equal on every layout (issue 11): every
// per-subdomain operation runs in full on one thread with sums in a fixed order (B_s^T in
// the rows' global-id order), a dual row adds its subdomains' terms in subdomain order on
// its owner, and every sum across rows or ranks is a reproducible one
// (core/ReproducibleSum.hpp), so 1, 2 and 3 ranks give the same counts and energy bits.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <initializer_list>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
struct Layout {
  int ranks, threads;
};

nlohmann::json solve(const Layout& layout, const std::filesystem::path& dir, const std::string& input,
                     const std::string& settings) {
  const auto summary = dir / ("summary_np" + std::to_string(layout.ranks) + "_t" + std::to_string(layout.threads) + ".json");
  const std::string command =
      std::string(TRIBOS_MPIEXEC) + " --allow-run-as-root --oversubscribe --bind-to none -x OMP_NUM_THREADS=" +
      std::to_string(layout.threads) + " -x OMP_WAIT_POLICY=PASSIVE -np " + std::to_string(layout.ranks) + " " +
      TRIBOS_DRIVER + " --input " + tribos::test::quote(tribos::test::sourceDir() + "/input/" + input) + " " + settings +
      " --set Solver/Verbose=false --summary " + summary.string();
  const auto run = tribos::test::runCommand(command);
  EXPECT_EQ(run.status, 0) << command << "\n" << run.output;
  std::ifstream in(summary);
  if (!in) return {};
  return nlohmann::json::parse(in);
}


// The counts and the energy's bits of `input` on every layout equal those on 1 rank x 1 thread.
void expectSameResultOnEveryLayout(const std::string& input, const std::string& settings,
                                   std::initializer_list<Layout> layouts) {
  char tmpl[] = "/tmp/tribos_layout_XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::filesystem::path dir(tmpl);
  const auto reference = solve({1, 1}, dir, input, settings);
  ASSERT_FALSE(reference.is_null());
  ASSERT_TRUE(reference["converged"].get<bool>());
  for (const Layout layout : layouts) {
    SCOPED_TRACE(std::to_string(layout.ranks) + " rank(s) x " + std::to_string(layout.threads) + " thread(s)");
    const auto j = solve(layout, dir, input, settings);
    ASSERT_FALSE(j.is_null());
    EXPECT_EQ(j["n_ranks"], layout.ranks);
    EXPECT_EQ(j["n_threads"], layout.threads);
    for (const char* count : {"outer_iterations", "inner_iterations", "pfp_applications", "f_applications", "cg_steps",
                              "expansion_steps", "proportioning_steps", "fixed_point_iterations"})
      EXPECT_EQ(j[count], reference[count]) << count;
    const double energy = j["energy"], referenceEnergy = reference["energy"];
    EXPECT_EQ(energy, referenceEnergy);  // bitwise (nlohmann::json writes doubles that read back exactly)
  }
  std::filesystem::remove_all(dir);
}
}  // namespace

TEST(tribosDriver, sameIterationCountsOnEveryRankAndThreadLayout) {
  expectSameResultOnEveryLayout("two_bricks.xml", "--set 'Mesh/Subdomains Per Brick=2x1x1' --set 'Mesh/H Over h=3'",
                                {Layout{1, 2}, Layout{2, 1}, Layout{2, 2}, Layout{3, 1}});
}

// A curved contact with Coulomb friction: mortar rows of three and more subdomains, friction
// ellipses, a few hundred MPGP steps; on main before the reproducible sums it drifted by 3 %
// in F applications between 1 and 2 ranks at h = 0.1 mm.
TEST(tribosDriver, curvedCoulombContactSameResultOnOneTwoThreeRanks) {
  expectSameResultOnEveryLayout("hertz_cylinder.xml",
                                "--set Mesh/File=meshes/hertz_cylinder_h0.2.exo --set 'Contact/Friction Model=Coulomb'",
                                {Layout{2, 1}, Layout{3, 1}});
}

// MPGP's tangent CG (CG steps that slide friction multipliers along their ellipses, projected
// back, gradient recomputed) from the first step, so that it runs many times on this small
// mesh (546 F applications): its sums are reproducible ones too, so the bits do not move.
TEST(tribosDriver, tangentCgSameResultOnOneTwoThreeRanks) {
  expectSameResultOnEveryLayout("hertz_cylinder.xml",
                                "--set Mesh/File=meshes/hertz_cylinder_h0.2.exo --set 'Contact/Friction Model=Coulomb'"
                                " --set 'Solver/MPGP/tangent CG after=0'",
                                {Layout{2, 1}, Layout{3, 1}, Layout{1, 2}});
}

// The coarse solves spread over the ranks (DistributedCoarseSolve, issue 11), on whatever
// factor size (FETI/Distributed Coarse From = 0), here G G^T of 256 subdomains (271 488 values, split
// over 2 and 3 ranks): the counts and the energy's bits of one rank, and the multi-rank runs
// did spread them.
TEST(tribosDriver, coarseSolvesSpreadOverTheRanksSameResult) {
  const std::string settings =
      "--set 'Mesh/Subdomains Per Brick=8x4x4' --set 'Mesh/H Over h=2' --set 'FETI/Distributed Coarse From=0'";
  expectSameResultOnEveryLayout("two_bricks.xml", settings, {Layout{2, 1}, Layout{3, 1}});
  char tmpl[] = "/tmp/tribos_spread_XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const auto j = solve({2, 1}, tmpl, "two_bricks.xml", settings);
  ASSERT_FALSE(j.is_null());
  EXPECT_GE(j["operator_profile"]["coarse_rank_subtrees"].get<int>(), 2);
  EXPECT_LT(j["operator_profile"]["coarse_values_per_solve"].get<long long>(),
            j["operator_profile"]["coarse_factor_nonzeros"].get<long long>());
  std::filesystem::remove_all(tmpl);
}

// The coarse factor in single precision (FETI/Coarse Factor Precision = Single): its parts
// travel to the ranks as floats, lambda_Im and the rigid body coefficients are refined to
// double on every rank alike; the same counts and energy bits on 1, 2 and 3 ranks, with the
// coarse solves spread (FETI/Distributed Coarse From = 0) and on rank 0 alone.
TEST(tribosDriver, singlePrecisionCoarseFactorSameResultOnOneTwoThreeRanks) {
  const std::string settings =
      "--set 'Mesh/Subdomains Per Brick=4x2x2' --set 'Mesh/H Over h=2' --set 'FETI/Coarse Factor Precision=Single'";
  expectSameResultOnEveryLayout("two_bricks.xml", settings, {Layout{2, 1}, Layout{1, 2}});
  // 256 subdomains: a factor the planner splits (4x2x2's is not), so that float parts travel.
  const std::string spread =
      "--set 'Mesh/Subdomains Per Brick=8x4x4' --set 'Mesh/H Over h=2' --set 'FETI/Coarse Factor Precision=Single'"
      " --set 'FETI/Distributed Coarse From=0'";
  expectSameResultOnEveryLayout("two_bricks.xml", spread, {Layout{2, 1}, Layout{3, 1}});
  char tmpl[] = "/tmp/tribos_single_spread_XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const auto j = solve({2, 1}, tmpl, "two_bricks.xml", spread);
  ASSERT_FALSE(j.is_null());
  EXPECT_TRUE(j["operator_profile"]["coarse_single"].get<bool>());
  EXPECT_GE(j["operator_profile"]["coarse_rank_subtrees"].get<int>(), 2);
  std::filesystem::remove_all(tmpl);
}

// "Auto" decides from quantities every rank layout shares (the coarse factor and the
// subdomains' bytes, not the ranks' copies of G's slots): a cell at the threshold
// (10x5x5 / H/h 2: two coarse solves read 1.0x what F does) takes the same precision, and
// gives the same bits, on 1, 2 and 3 ranks.
TEST(tribosDriver, autoCoarsePrecisionIsTheSameOnEveryLayout) {
  expectSameResultOnEveryLayout("two_bricks.xml", "--set 'Mesh/Subdomains Per Brick=10x5x5' --set 'Mesh/H Over h=2'",
                                {Layout{2, 1}, Layout{3, 1}});
}

// The single-precision coarse factor changes the projector, not the problem (SMALSE-M's
// penalty enforces G mu = 0 itself; doc/measurements/coarse_problem.md): at eps = 1e-9 the solution is the
// double factor's to the solver's accuracy (measured on 6x3x3 / H/h 2: energies 3e-12 apart,
// displacements 9e-10 of the largest). The summary says which factor ran and how well it
// solved the gate's right-hand side, and that the exact solves were refined.
TEST(tribosDriver, singlePrecisionCoarseFactorGivesTheDoubleFactorsSolution) {
  char tmpl[] = "/tmp/tribos_single_XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::filesystem::path dir(tmpl);
  const std::string cell = "--set 'Mesh/Subdomains Per Brick=4x2x2' --set 'Mesh/H Over h=2' --set Solver/Tolerance=1e-9";
  std::filesystem::create_directories(dir / "double");
  const auto dbl = solve({1, 1}, dir / "double", "two_bricks.xml", cell + " --set 'FETI/Coarse Factor Precision=Double'");
  std::filesystem::create_directories(dir / "single");
  const auto sgl = solve({1, 1}, dir / "single", "two_bricks.xml", cell + " --set 'FETI/Coarse Factor Precision=Single'");
  ASSERT_FALSE(dbl.is_null());
  ASSERT_FALSE(sgl.is_null());
  EXPECT_TRUE(dbl["converged"].get<bool>());
  EXPECT_TRUE(sgl["converged"].get<bool>());
  EXPECT_FALSE(dbl["operator_profile"]["coarse_single"].get<bool>());
  EXPECT_TRUE(sgl["operator_profile"]["coarse_single"].get<bool>());
  const double gate = sgl["operator_profile"]["coarse_single_error"];
  EXPECT_GT(gate, 0.0);
  EXPECT_LE(gate, 1e-3);
  EXPECT_GT(sgl["operator_profile"]["coarse_refinement_steps"].get<long long>(), 0);
  // The end's alpha (G_I G_I^T) is timed in the summary with the other coarse costs.
  EXPECT_GT(dbl["operator_profile"]["rigid_coefficients_s"].get<double>(), 0.0);
  const double e1 = dbl["energy"], e2 = sgl["energy"];
  EXPECT_LT(std::abs(e1 - e2), 1e-10 * std::abs(e1));
  const double f1 = dbl["total_normal_force"], f2 = sgl["total_normal_force"];
  EXPECT_LT(std::abs(f1 - f2), 1e-8 * std::abs(f1));
  std::filesystem::remove_all(dir);
}

// Where the single factor solves the gate's right-hand side worse than the gate allows (here
// the gate lowered below its error), G G^T is factorised again in double: the run is the
// double factor's, bit for bit, and the summary reports the error that sent it back.
TEST(tribosDriver, aSingleCoarseFactorFailingTheGateFallsBackToDouble) {
  char tmpl[] = "/tmp/tribos_gate_XXXXXX";
  ASSERT_NE(::mkdtemp(tmpl), nullptr);
  const std::filesystem::path dir(tmpl);
  const std::string cell = "--set 'Mesh/Subdomains Per Brick=2x1x1' --set 'Mesh/H Over h=2'";
  std::filesystem::create_directories(dir / "double");
  std::filesystem::create_directories(dir / "gated");
  const auto dbl = solve({1, 1}, dir / "double", "two_bricks.xml", cell + " --set 'FETI/Coarse Factor Precision=Double'");
  const auto gated = solve({1, 1}, dir / "gated", "two_bricks.xml",
                          cell + " --set 'FETI/Coarse Factor Precision=Single' --set 'FETI/Single Coarse Gate=1e-15'");
  ASSERT_FALSE(dbl.is_null());
  ASSERT_FALSE(gated.is_null());
  EXPECT_FALSE(gated["operator_profile"]["coarse_single"].get<bool>());
  EXPECT_GT(gated["operator_profile"]["coarse_single_error"].get<double>(), 1e-15);
  EXPECT_EQ(gated["operator_profile"]["coarse_refinement_steps"].get<long long>(), 0);
  EXPECT_EQ(gated["f_applications"], dbl["f_applications"]);
  EXPECT_EQ(gated["outer_iterations"], dbl["outer_iterations"]);
  const double e1 = dbl["energy"], e2 = gated["energy"];
  EXPECT_EQ(e1, e2);
  std::filesystem::remove_all(dir);
}
