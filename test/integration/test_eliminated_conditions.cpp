// FETI/Displacement Conditions = Eliminated and Automatic (issue 46): components prescribed to 0 leave K_s
// instead of getting rows of B, the subdomains' rigid modes shrink to those the eliminated
// components leave free, and the coarse problem pins the others. The discrete problem is the
// same, so the solution must be the one with multipliers to the solver's tolerance: energy,
// contact forces, reactions (now K u - f at the eliminated dofs) and the force balance, on a
// clamped cantilever (linear T-FETI), the paper's clamped bricks (every subdomain of the
// clamped faces loses all six modes) and a Hertz cylinder with Coulomb friction on a thin
// plane-strain slice (u_y = 0 on both end faces: the scene it is for).
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
nlohmann::json solve(const std::string& input, const std::string& settings, const std::string& conditions) {
  char tmpl[] = "/tmp/tribos_eliminated_XXXXXX";
  if (!::mkdtemp(tmpl)) return {};
  const std::filesystem::path summary = std::filesystem::path(tmpl) / "s.json";
  const std::string command = std::string(TRIBOS_DRIVER) + " --input " +
                              tribos::test::quote(tribos::test::sourceDir() + "/input/" + input) + " " + settings +
                              " --set 'FETI/Displacement Conditions=" + conditions +
                              "' --set Solver/Verbose=false --summary " + summary.string();
  const auto run = tribos::test::runCommand(command);
  EXPECT_EQ(run.status, 0) << command << "\n" << run.output;
  nlohmann::json j;
  if (std::ifstream in(summary); in) j = nlohmann::json::parse(in);
  std::filesystem::remove_all(tmpl);
  return j;
}

double relative(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-300); }

// The same solution both ways: strain energy, normal force, every support's reaction (relative to
// the largest), the force balance.
void expectSameSolution(const std::string& input, const std::string& settings, double tolerance,
                        const std::string& mode = "Eliminated") {
  const auto rows = solve(input, settings, "Multipliers");
  const auto eliminated = solve(input, settings, mode);
  ASSERT_FALSE(rows.is_null());
  ASSERT_FALSE(eliminated.is_null());
  ASSERT_TRUE(eliminated["converged"].get<bool>()) << eliminated["message"];
  EXPECT_LT(eliminated["n_dual"].get<long long>(), rows["n_dual"].get<long long>());
  EXPECT_LE(relative(eliminated["strain_energy"], rows["strain_energy"]), tolerance);
  if (rows.contains("total_normal_force"))
    EXPECT_LE(relative(eliminated["total_normal_force"], rows["total_normal_force"]), tolerance);
  double largest = 0.0;
  for (const auto& [name, force] : rows["reactions"].items())
    for (int d = 0; d < 3; ++d) largest = std::max(largest, std::abs(force[d].get<double>()));
  ASSERT_GT(largest, 0.0);
  for (const auto& [name, force] : rows["reactions"].items()) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(eliminated["reactions"].contains(name));
    for (int d = 0; d < 3; ++d)
      EXPECT_LE(std::abs(eliminated["reactions"][name][d].get<double>() - force[d].get<double>()), tolerance * largest);
  }
  EXPECT_LE(eliminated["force_balance"].get<double>(), 1e-8);
}
}  // namespace

TEST(eliminatedConditions, clampedCantileverAsWithMultipliers) {
  expectSameSolution("cantilever_hex8.xml", "", 1e-5);
}

TEST(eliminatedConditions, paperBricksEverySubdomainOfTheClampsPinned) {
  expectSameSolution("two_bricks.xml", "--set 'Mesh/Subdomains Per Brick=2x1x1' --set 'Mesh/H Over h=3'", 1e-5);
}

TEST(eliminatedConditions, planeStrainSliceCoulombAsWithMultipliers) {
  expectSameSolution("hertz_cylinder.xml",
                     "--set Mesh/File=meshes/hertz_cylinder_h0.2.exo --set 'Contact/Friction Model=Coulomb'", 1e-5);
}

// Automatic, the default: the plane-strain and symmetry components leave K_s, the clamp under
// the block keeps its rows (between the two other modes in rows), the same solution.
TEST(eliminatedConditions, automaticEliminatesAllButTheClamps) {
  const std::string settings = "--set Mesh/File=meshes/hertz_cylinder_h0.2.exo --set 'Contact/Friction Model=Coulomb'";
  expectSameSolution("hertz_cylinder.xml", settings, 1e-5, "Automatic");
  const auto automatic = solve("hertz_cylinder.xml", settings, "Automatic");
  const auto eliminated = solve("hertz_cylinder.xml", settings, "Eliminated");
  EXPECT_GT(automatic["n_dual"].get<long long>(), eliminated["n_dual"].get<long long>());
}

// On the paper's bricks, clamped on whole faces and held nowhere else, Automatic is the rows:
// the same dual dimension and the same iterations (Table 1 unchanged by the default).
TEST(eliminatedConditions, automaticKeepsTheRowsOfTheClampedBricks) {
  const std::string settings = "--set 'Mesh/Subdomains Per Brick=4x2x2' --set 'Mesh/H Over h=3'";
  const auto rows = solve("two_bricks.xml", settings, "Multipliers");
  const auto automatic = solve("two_bricks.xml", settings, "Automatic");
  EXPECT_EQ(automatic["n_dual"], rows["n_dual"]);
  EXPECT_EQ(automatic["pfp_applications"], rows["pfp_applications"]);
  EXPECT_EQ(automatic["strain_energy"], rows["strain_energy"]);
}

// A load history whose grip takes hold after a preload (Load Steps/grip/Active {0, 1, 1}): the
// grip starts where step 1 left its nodes (a base that is not 0: rows), the clamp below is
// eliminated; the constraints are rebuilt when the grip takes hold.
TEST(eliminatedConditions, gripAddedAfterAPreloadAsWithMultipliers) {
  expectSameSolution("../test/integration/grip_after_preload.xml", "", 1e-5);
}
