// What the driver checks around the solve: before it, that every rigid motion of every body
// meets a row of B (a free one is an input error, exit 2, naming the body and the motion,
// in dry runs too); after it, the console line with every KKT residual of the discrete
// problem, the same numbers as the summary's.
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <regex>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
using tribos::test::quote;
using tribos::test::runCommand;

const std::string kDriver = TRIBOS_DRIVER;
std::string input(const std::string& name) { return tribos::test::sourceDir() + "/input/" + name; }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST(tribosDriver, aFreeRigidMotionIsAnInputErrorBeforeTheSolve) {
  // block_on_plate.xml: a block on a clamped plate, held by contact and friction only.
  // Frictionless, nothing holds the block's sliding in x and y or its spin about z (the
  // interface is the plane z = const): exit 2, naming the body and those three motions and
  // nothing else, before any solver output.
  const std::string scene = quote(input("block_on_plate.xml"));
  for (const std::string mode : {"", " --dry-run"}) {
    SCOPED_TRACE("mode:" + mode);
    const auto run = runCommand(kDriver + " --input " + scene + " --set 'Contact/Friction Model=None'" + mode);
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_TRUE(contains(run.output, "3 rigid motions are free")) << run.output;
    for (const char* motion : {"body \"block\": translation x", "body \"block\": translation y",
                               "body \"block\": rotation about z"})
      EXPECT_TRUE(contains(run.output, motion)) << motion << "\n" << run.output;
    EXPECT_FALSE(contains(run.output, "body \"plate\"")) << run.output;  // the clamped plate is held
    EXPECT_FALSE(contains(run.output, "translation z")) << run.output;   // the normal rows hold these
    EXPECT_FALSE(contains(run.output, "rotation about x")) << run.output;
    EXPECT_FALSE(contains(run.output, "rotation about y")) << run.output;
    EXPECT_FALSE(contains(run.output, "SMALSE-M")) << run.output;
    EXPECT_FALSE(contains(run.output, "outer")) << run.output;
  }
  // With the scene's Coulomb friction (F = 0.3) the tangential rows hold the block: it solves.
  const auto run = runCommand(kDriver + " --input " + scene + " --set Solver/Verbose=false");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_FALSE(contains(run.output, "rigid motion")) << run.output;
  EXPECT_FALSE(contains(run.output, "found no master face")) << run.output;
}

TEST(tribosDriver, threeBodiesOnTwoInterfacesCarryTheLoadThroughEach) {
  // three_bodies.xml (issue 30): a rounded punch on a block on a clamped foundation, two
  // Contact/<name> interfaces with their own friction coefficients. Each interface carries the
  // punch's load: 50 MPa on its 10 x 10 top is 5000 N down, 2 MPa is 200 N along x.
  const auto summary = std::filesystem::temp_directory_path() / ("tribos_three_" + std::to_string(::getpid()) + ".json");
  const auto run = runCommand(kDriver + " --input " + quote(input("three_bodies.xml")) +
                              " --set Solver/Verbose=false --summary " + quote(summary.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  nlohmann::json j;
  std::ifstream(summary) >> j;
  std::filesystem::remove(summary);
  ASSERT_EQ(j.at("interfaces").size(), 2u);
  // The force on each master: the punch above its slave is pushed up and back, the foundation
  // below its slave down and along.
  const double sign[2] = {1.0, -1.0};
  for (int k = 0; k < 2; ++k) {
    const auto& i = j.at("interfaces")[k];
    SCOPED_TRACE(i.at("name").get<std::string>());
    EXPECT_NEAR(i.at("normal_force").get<double>(), 5000.0, 10.0);  // the fillet's slope tilts a little of it
    EXPECT_NEAR(i.at("contact_force")[2].get<double>(), sign[k] * 5000.0, 5000.0 * 1e-4);
    EXPECT_NEAR(i.at("contact_force")[0].get<double>(), -sign[k] * 200.0, 5000.0 * 1e-4);
    EXPECT_NEAR(i.at("contact_force")[1].get<double>(), 0.0, 5000.0 * 1e-4);
  }
  EXPECT_EQ(j.at("interfaces")[0].at("name"), "punch_on_block");
  // At F = 0.15 every node under the block slides: the block's rigid motions are held by its
  // sliding rows alone (the slip has no component across the friction force). It was exit 3,
  // "no equilibrium found" (G_I G_I^T singular without them).
  const auto sliding = runCommand(kDriver + " --input " + quote(input("three_bodies.xml")) +
                                  " --set Solver/Verbose=false --set Contact/block_on_foundation/F1=0.15"
                                  " --set Contact/block_on_foundation/F2=0.15 --summary " + quote(summary.string()));
  ASSERT_EQ(sliding.status, 0) << sliding.output;
  std::ifstream(summary) >> j;
  std::filesystem::remove(summary);
  EXPECT_EQ(j.at("interfaces")[1].at("stick").get<int>(), 0);
  EXPECT_GT(j.at("interfaces")[1].at("slip").get<int>(), 250);
  EXPECT_NEAR(j.at("interfaces")[1].at("friction_force").get<double>(), 0.15 * 5000.0, 1.0);
  EXPECT_TRUE(contains(run.output, "interface block_on_foundation block_bottom -> foundation_top: ")) << run.output;
}

TEST(tribosDriver, aBodyFreeBecauseItsContactFoundNothingNamesTheSearchDistance) {
  // The paper's bricks 0.5 apart with the upper brick unclamped: its contact, searched within
  // 0.1, finds no master face, so nothing holds it; the message says why and which nodes.
  const auto run = runCommand(kDriver + " --input " + quote(input("two_bricks.xml")) +
                              " --dry-run --set 'Mesh/Initial Gap=0.5' --set 'Contact/Search Distance=0.1'"
                              " --set 'Boundary/Dirichlet Node Sets={dirichlet_steel}'");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_TRUE(contains(run.output, "body \"aluminium\": translation x")) << run.output;
  EXPECT_TRUE(contains(run.output, "slave nodes found no master face within Contact/Search Distance = 0.1 (nodes "))
      << run.output;
  EXPECT_TRUE(contains(run.output, "numbered from 1 as in the mesh file")) << run.output;
}

TEST(tribosDriver, theConsolePrintsEveryKktResidual) {
  // A normal run of the paper's scene: the console's KKT line names every residual, each
  // printed value is the summary's (cout's 6 significant digits) and within the printed
  // tolerance (the run converged).
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_driver_checks_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto summaryPath = dir / "summary.json";
  const auto run = runCommand(kDriver + " --input " + quote(input("two_bricks.xml")) + " --set Solver/Verbose=false" +
                              " --summary " + quote(summaryPath.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(summaryPath));
  std::filesystem::remove_all(dir);
  const auto& kkt = summary.at("kkt");

  std::smatch line;
  ASSERT_TRUE(std::regex_search(run.output, line, std::regex("KKT \\(each <= ([^ ]+) for \"converged\"\\): ([^\n]*)")))
      << run.output;
  const double tolerance = std::stod(line[1]);
  EXPECT_NEAR(tolerance, kkt.at("tolerance").get<double>(), 1e-5 * tolerance);
  const std::string residuals = line[2];
  const std::pair<const char*, const char*> printedAs[] = {
      {"equilibrium", "equilibrium"},         {"gluing/Dirichlet", "gluing_dirichlet"},
      {"penetration", "non_penetration"},     {"complementarity", "complementarity"},
      {"normal sign", "normal_sign"},         {"friction", "friction_admissibility"},
      {"slip rule", "slip_rule"},             {"stick rule", "stick_rule"}};
  for (const auto& [label, key] : printedAs) {
    SCOPED_TRACE(label);
    std::smatch value;
    ASSERT_TRUE(std::regex_search(residuals, value, std::regex(std::string("(^|, )") + label + " ([^ ,]+)")))
        << residuals;
    const double printed = std::stod(value[2]), stored = kkt.at(key).get<double>();
    EXPECT_NEAR(printed, stored, 1e-5 * std::abs(stored)) << residuals;
    EXPECT_GE(printed, 0.0);
    EXPECT_LE(printed, tolerance);
  }
}


TEST(tribosDriver, unwritableOutputsAreInputErrorsBeforeAnyWorkAndOutputsAreAtomic) {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_outputs_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto exo = (dir / "r.exo").string(), summary = (dir / "s.json").string();
  const std::string scene = quote(input("two_bricks.xml")) + " --set Solver/Verbose=false";
  // An unwritable summary path: exit 2 naming it and the option, before the solve, and the
  // (writable) Exodus result is not written either.
  auto run = runCommand(kDriver + " --input " + scene + " --output " + quote(exo) + " --summary " +
                        quote((dir / "missing" / "s.json").string()));
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("missing/s.json"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("--summary"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("SMALSE-M"), std::string::npos) << "it solved first:\n" << run.output;
  EXPECT_FALSE(std::filesystem::exists(exo));
  run = runCommand(kDriver + " --input " + scene + " --output " + quote((dir / "missing" / "r.exo").string()));
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("--output"), std::string::npos) << run.output;
  // A normal run: both files, and nothing left under the partial name.
  run = runCommand(kDriver + " --input " + scene + " --output " + quote(exo) + " --summary " + quote(summary));
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_TRUE(std::filesystem::exists(exo));
  EXPECT_TRUE(std::filesystem::exists(summary));
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().string().find("partial"), std::string::npos) << entry.path();
  std::filesystem::remove_all(dir);
}
