// The external preprocessor path: a gmsh mesh (input/meshes/block_on_plate.msh, made by
// gmsh from block_on_plate.geo) converted by tribos-msh2exo and solved by tribos: the contact
// force balances the applied load exactly (20 MPa x 600 mm^2 down, 0.5 MPa x 600 mm^2 shear).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

using tribos::test::quote;
using tribos::test::runCommand;

TEST(externalMesh, gmshMeshConvertsAndSolvesWithBalancedContactForces) {
  const auto root = tribos::test::sourceDir();
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_gmsh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto exo = (dir / "block_on_plate.exo").string();
  auto run = runCommand(std::string(TRIBOS_MSH2EXO) + " --split-bodies " + quote(root + "/input/meshes/block_on_plate.msh") +
                        " " + quote(exo));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("interface_plate"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("interface_block"), std::string::npos) << run.output;

  const auto summary = (dir / "summary.json").string();
  run = runCommand(std::string(TRIBOS_DRIVER) + " --input " + quote(root + "/input/block_on_plate.xml") +
                   " --set 'Mesh/File=" + exo + "' --set Solver/Tolerance=1e-8 --set Solver/Verbose=false --summary " +
                   quote(summary));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(summary);
  const auto j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["converged"].get<bool>());
  const auto force = j["total_contact_force"];  // on the block (master), from the plate
  EXPECT_NEAR(force[0].get<double>(), -0.5 * 600.0, 1e-6 * 12000.0);
  EXPECT_NEAR(force[1].get<double>(), 0.0, 1e-6 * 12000.0);
  EXPECT_NEAR(force[2].get<double>(), 20.0 * 600.0, 1e-6 * 12000.0);
  EXPECT_LE(j["kkt"]["equilibrium"].get<double>(), 1e-6);
  EXPECT_LE(j["kkt"]["non_penetration"].get<double>(), 1e-6);

  // Without splitting, the bodies share their interface nodes: the scene's contact side
  // sets do not exist, and the driver says which one (exit status 2).
  const auto shared = (dir / "shared.exo").string();
  ASSERT_EQ(runCommand(std::string(TRIBOS_MSH2EXO) + " " + quote(root + "/input/meshes/block_on_plate.msh") + " " +
                       quote(shared))
                .status,
            0);
  run = runCommand(std::string(TRIBOS_DRIVER) + " --input " + quote(root + "/input/block_on_plate.xml") +
                   " --set 'Mesh/File=" + shared + "' --dry-run");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("interface_plate"), std::string::npos) << run.output;
  // A missing gmsh file is an input error naming it.
  run = runCommand(std::string(TRIBOS_MSH2EXO) + " /nonexistent/mesh.msh " + quote(shared));
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.output.find("/nonexistent/mesh.msh"), std::string::npos) << run.output;
  std::filesystem::remove_all(dir);
}
