// Bad input gets a clear message naming the file or parameter and exit status 2; --help,
// --list-parameters and --output work; a METIS-decomposed Exodus mesh can be read back in.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "RunCommand.hpp"
#include "TestPaths.hpp"
#include "tribos/mesh/ExodusIO.hpp"

namespace {
using tribos::test::quote;
using tribos::test::runCommand;

const std::string kDriver = TRIBOS_DRIVER;
std::string scene() { return tribos::test::sourceDir() + "/input/two_bricks.xml"; }

std::filesystem::path scratch() {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_driver_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

void writeFile(const std::filesystem::path& path, const std::string& text) { std::ofstream(path) << text; }

void expectBadInput(const std::string& args, const std::string& mention) {
  const auto run = runCommand(kDriver + " " + args);
  EXPECT_EQ(run.status, 2) << args << "\n" << run.output;
  EXPECT_NE(run.output.find(mention), std::string::npos) << "message should mention \"" << mention << "\":\n" << run.output;
}
}  // namespace

TEST(tribosDriver, helpAndParameterListing) {
  auto run = runCommand(kDriver + " --help");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("--dry-run"), std::string::npos);
  run = runCommand(kDriver + " --list-parameters");
  EXPECT_EQ(run.status, 0);
  for (const char* name : {"Mesh/Subdomains Per Brick", "Mesh/H Over h", "Contact/Friction Model", "Contact/F1",
                           "Solver/Tolerance", "Solver/Max Outer Iterations", "Materials/*/Lame Mu"})
    EXPECT_NE(run.output.find(name), std::string::npos) << name;
}

TEST(tribosDriver, badInputNamesTheCulpritAndExitsWith2) {
  const auto dir = scratch();
  expectBadInput("--input /nonexistent/scene.xml --dry-run", "/nonexistent/scene.xml");
  expectBadInput("--input " + quote(scene()) + " --dry-run --set 'Mesh/H over h=3'", "H Over h");
  expectBadInput("--input " + quote(scene()) + " --dry-run --set 'Mesh/H Over h=three'", "three");
  expectBadInput("--input " + quote(scene()) + " --dry-run --set 'Mesh/H Over h=0'", "H Over h");
  expectBadInput("--input " + quote(scene()) + " --dry-run --set 'Mesh/Subdomains Per Brick=3x1x1'",
                 "Subdomains Per Brick");
  expectBadInput("--input " + quote(scene()) + " --dry-run --set 'Contact/Friction Model=Coulomb-ish'",
                 "Friction Model");
  expectBadInput("--input " + quote(scene()) + " --dry-run --set 'Boundary/Dirichlet Node Sets={nowhere}'",
                 "nowhere");
  expectBadInput("--input " + quote(scene()) + " --no-such-flag", "--no-such-flag");

  writeFile(dir / "broken.xml", "<ParameterList name=\"Tribos\"><Parameter name=\"x\"");
  expectBadInput("--input " + quote((dir / "broken.xml").string()) + " --dry-run", "broken.xml");
  writeFile(dir / "unknown.xml",
            "<ParameterList name=\"Tribos\"><ParameterList name=\"Mesh\">"
            "<Parameter name=\"Generatr\" type=\"string\" value=\"Two Bricks\"/></ParameterList></ParameterList>");
  expectBadInput("--input " + quote((dir / "unknown.xml").string()) + " --dry-run", "Generatr");
  writeFile(dir / "exodus.xml",
            "<ParameterList name=\"Tribos\"><ParameterList name=\"Mesh\">"
            "<Parameter name=\"Generator\" type=\"string\" value=\"Exodus\"/>"
            "<Parameter name=\"File\" type=\"string\" value=\"/nonexistent/mesh.exo\"/></ParameterList></ParameterList>");
  expectBadInput("--input " + quote((dir / "exodus.xml").string()) + " --dry-run", "/nonexistent/mesh.exo");
  std::filesystem::remove_all(dir);
}

TEST(tribosDriver, outputCarriesTheSubdomainsAndReadsBackThroughMetis) {
  const auto dir = scratch();
  const auto exo = dir / "bricks.exo";
  auto run = runCommand(kDriver + " --input " + quote(scene()) + " --dry-run --set 'Mesh/Subdomains Per Brick=4x2x2'" +
                        " --output " + quote(exo.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  const auto data = tribos::mesh::readExodus(exo.string());
  ASSERT_EQ(data.steps.size(), 1u);
  ASSERT_EQ(data.steps[0].element.size(), 1u);
  EXPECT_EQ(data.steps[0].element[0].name, "subdomain");
  // 32 subdomains of (H/h)^3 = 8 cubes of 5 tets each.
  std::vector<int> perSubdomain(32, 0);
  for (double s : data.steps[0].element[0].values) {
    ASSERT_GE(s, 0);
    ASSERT_LT(s, 32);
    perSubdomain[static_cast<int>(s)]++;
  }
  for (int c : perSubdomain) EXPECT_EQ(c, 40);

  // The written mesh is a valid Exodus input for a METIS-decomposed run of the same scene.
  writeFile(dir / "from_exodus.xml",
            "<ParameterList name=\"Tribos\"><ParameterList name=\"Mesh\">"
            "<Parameter name=\"Generator\" type=\"string\" value=\"Exodus\"/>"
            "<Parameter name=\"File\" type=\"string\" value=\"" + exo.string() + "\"/>"
            "<Parameter name=\"Subdomains\" type=\"int\" value=\"6\"/></ParameterList>"
            "<ParameterList name=\"Materials\">"
            "<ParameterList name=\"aluminium\"><Parameter name=\"Young Modulus\" type=\"double\" value=\"70000\"/>"
            "<Parameter name=\"Poisson Ratio\" type=\"double\" value=\"0.35\"/></ParameterList>"
            "<ParameterList name=\"steel\"><Parameter name=\"Lame Lambda\" type=\"double\" value=\"63600\"/>"
            "<Parameter name=\"Lame Mu\" type=\"double\" value=\"83010\"/></ParameterList></ParameterList>"
            "<ParameterList name=\"Loads\"><ParameterList name=\"top\">"
            "<Parameter name=\"Side Set\" type=\"string\" value=\"load_top\"/>"
            "<Parameter name=\"Traction\" type=\"Array(double)\" value=\"{0, 0, -30}\"/></ParameterList></ParameterList>"
            "<ParameterList name=\"Boundary\"><Parameter name=\"Dirichlet Node Sets\" type=\"Array(string)\" "
            "value=\"{dirichlet_aluminium, dirichlet_steel}\"/></ParameterList>"
            "<ParameterList name=\"Contact\"><Parameter name=\"Slave Side Set\" type=\"string\" value=\"contact_aluminium\"/>"
            "<Parameter name=\"Master Side Set\" type=\"string\" value=\"contact_steel\"/></ParameterList>"
            "</ParameterList>");
  const auto summary = dir / "summary.json";
  run = runCommand(kDriver + " --input " + quote((dir / "from_exodus.xml").string()) + " --dry-run --summary " +
                   quote(summary.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(summary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"n_subdomains\": 6"), std::string::npos) << text;
  EXPECT_NE(text.find("\"n_rigid\": 36"), std::string::npos) << text;

  // A material missing for a block is an error naming the block.
  writeFile(dir / "no_material.xml",
            "<ParameterList name=\"Tribos\"><ParameterList name=\"Mesh\">"
            "<Parameter name=\"Generator\" type=\"string\" value=\"Exodus\"/>"
            "<Parameter name=\"File\" type=\"string\" value=\"" + exo.string() + "\"/></ParameterList>"
            "<ParameterList name=\"Materials\"><ParameterList name=\"steel\">"
            "<Parameter name=\"Lame Lambda\" type=\"double\" value=\"63600\"/>"
            "<Parameter name=\"Lame Mu\" type=\"double\" value=\"83010\"/></ParameterList></ParameterList>"
            "</ParameterList>");
  expectBadInput("--input " + quote((dir / "no_material.xml").string()) + " --dry-run", "aluminium");
  std::filesystem::remove_all(dir);
}

TEST(tribosDriver, everySceneInInputRunsAndConvergesWithResults) {
  // The Cattaneo-Mindlin scenes (load histories, 14 and 60 s) run as delivered in their own
  // CTests, integration.cattaneoMindlin.sphere and .cylinder, which check their results; so does
  // the bolted joint (a 31-step history, 36 s: integration.boltedJoint.*).
  const std::vector<std::string> runElsewhere = {"cattaneo_sphere.xml", "cattaneo_cylinder.xml", "bolted_joint.xml"};
  const auto dir = scratch();
  for (const auto& entry : std::filesystem::directory_iterator(tribos::test::sourceDir() + "/input")) {
    if (entry.path().extension() != ".xml") continue;
    const std::string name = entry.path().filename().string();
    if (std::find(runElsewhere.begin(), runElsewhere.end(), name) != runElsewhere.end()) continue;
    SCOPED_TRACE(entry.path().string());
    const auto exo = dir / "result.exo";
    const auto run = runCommand(kDriver + " --input " + quote(entry.path().string()) + " --set Solver/Verbose=false" +
                                " --output " + quote(exo.string()));
    EXPECT_EQ(run.status, 0) << run.output;
    const auto data = tribos::mesh::readExodus(exo.string());
    ASSERT_EQ(data.steps.size(), 1u);  // no scene here has a load history
    std::vector<std::string> names;
    for (const auto& f : data.steps[0].nodal) names.push_back(f.name);
    for (const char* required : {"displ_x", "displ_y", "displ_z"})
      EXPECT_NE(std::find(names.begin(), names.end(), required), names.end()) << required;
  }
  std::filesystem::remove_all(dir);
}

TEST(tribosDriver, aSolveThatDidNotConvergeSaysSoWithExitStatus3) {
  const auto dir = scratch();
  const auto summary = dir / "summary.json";
  const auto run = runCommand(kDriver + " --input " + quote(scene()) + " --set 'Solver/Max Outer Iterations=2'" +
                              " --set Solver/Verbose=false --summary " + quote(summary.string()) + " --output " +
                              quote((dir / "r.exo").string()));
  EXPECT_EQ(run.status, 3) << run.output;
  EXPECT_NE(run.output.find("NOT CONVERGED"), std::string::npos) << run.output;
  std::ifstream in(summary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\"converged\": false"), std::string::npos) << text;
  EXPECT_TRUE(std::filesystem::exists(dir / "r.exo"));  // results are still written
  std::filesystem::remove_all(dir);
}
