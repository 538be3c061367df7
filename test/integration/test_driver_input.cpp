// Every class of bad input is an input error: exit status 2, a message that names the file
// (or the --set override) and the parameter, no library source lines, and no output file left
// behind. Limits that end a solve name themselves (exit 3, results written and flagged).
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
using tribos::test::quote;
using tribos::test::runCommand;
namespace fs = std::filesystem;

const std::string kDriver = TRIBOS_DRIVER;
std::string paperScene() { return quote(tribos::test::sourceDir() + "/input/two_bricks.xml"); }

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

class DriverInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("tribos_input_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A scene file in the scratch directory.
  std::string scene(const std::string& name, const std::string& body) {
    const auto path = dir_ / name;
    std::ofstream(path) << body;
    return quote(path.string());
  }

  // Runs with --output and --summary into an empty folder: exit 2, every `mention` in the
  // message, nothing written, no Teuchos source-file text.
  void expectRefused(const std::string& args, const std::vector<std::string>& mentions) {
    const auto out = dir_ / "out";
    fs::create_directories(out);
    const auto run = runCommand(kDriver + " " + args + " --output " + quote((out / "r.exo").string()) +
                                " --summary " + quote((out / "s.json").string()));
    EXPECT_EQ(run.status, 2) << args << "\n" << run.output;
    for (const auto& m : mentions) EXPECT_TRUE(contains(run.output, m)) << "should name \"" << m << "\":\n" << run.output;
    EXPECT_FALSE(contains(run.output, "Throw number")) << run.output;
    EXPECT_FALSE(contains(run.output, ".cpp:")) << run.output;
    EXPECT_FALSE(contains(run.output, "tribos: internal error")) << run.output;
    EXPECT_TRUE(fs::is_empty(out)) << args << ": a file was left in " << out;
    fs::remove_all(out);
  }

  fs::path dir_;
};

std::string tribosList(const std::string& body) { return "<ParameterList name=\"Tribos\">" + body + "</ParameterList>"; }
std::string meshList(const std::string& body) {
  return tribosList("<ParameterList name=\"Mesh\">" + body + "</ParameterList>");
}
std::string parameter(const std::string& name, const std::string& type, const std::string& value) {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>";
}
}  // namespace

TEST_F(DriverInput, aParameterOrSublistGivenTwiceIsAnInputError) {
  expectRefused("--input " + scene("twice.xml", meshList(parameter("H Over h", "int", "2") +
                                                         parameter("H Over h", "int", "3"))),
                {"twice.xml", "\"Mesh/H Over h\" is given twice"});
  expectRefused("--input " + scene("twice_list.xml", tribosList("<ParameterList name=\"Mesh\"/>"
                                                                "<ParameterList name=\"Mesh\"/>")),
                {"twice_list.xml", "\"Mesh\" is given twice"});
}

TEST_F(DriverInput, valuesOfTheWrongTypeAreInputErrors) {
  // In the file: each used to be read by atoi/atof (2, 0, inf, nan) and run on.
  const std::vector<std::vector<std::string>> inFile = {
      {"H Over h", "int", "2.5", "is not an integer"},
      {"Initial Gap", "double", "garbage", "is not a number"},
      {"Initial Gap", "double", "inf", "is not a finite number"},
      {"Initial Gap", "double", "nan", "is not a finite number"}};
  for (const auto& c : inFile)
    expectRefused("--input " + scene("typed.xml", meshList(parameter(c[0], c[1], c[2]))),
                  {"typed.xml", "Mesh/" + c[0], c[3]});
  // On the command line: the override is named.
  for (const std::string& set : {"Mesh/H Over h=2.5", "Materials/aluminium/Young Modulus=inf",
                                 "Solver/Tolerance=nan", "Contact/F1=garbage"})
    expectRefused("--input " + paperScene() + " --set '" + set + "'", {"--set \"" + set + "\""});
}

TEST_F(DriverInput, valuesOutsideTheirRangeAreInputErrors) {
  // Each ran before (a hang, a silent success or "not converged").
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"Solver/Tolerance=0", "(0, 1)"},           {"Solver/SMALSE-M/beta=15", "(0, 1)"},
      {"Solver/MPGP/step scale=3", "(0, 2)"},     {"Solver/SMALSE-M/rho=0", "(0, inf)"},
      {"Contact/F1=-1", "[0, 1e+100]"},           {"Materials/aluminium/Poisson Ratio=0.5", "(-1, 0.5)"},
      {"Materials/aluminium/Young Modulus=0", "(0, 1e+100]"}, {"Solver/Max Seconds=-1", "[0, inf)"}};
  for (const auto& [set, range] : cases) {
    const std::string path = set.substr(0, set.find('='));
    expectRefused("--input " + paperScene() + " --set '" + set + "'", {"--set \"" + set + "\"", path, range});
  }
  // In the file, the file is named.
  expectRefused("--input " + scene("range.xml", tribosList("<ParameterList name=\"Solver\">" +
                                                           parameter("Tolerance", "double", "0") + "</ParameterList>")),
                {"range.xml", "Solver/Tolerance", "(0, 1)"});
}

TEST_F(DriverInput, absurdMagnitudesAreInputErrors) {
  // Issue 8's list: E = 1e300 ran "successfully", a traction of 1e300 hung; F = 1e300 and E or
  // a traction near 1e300 overflow the squares in the norms (doc/stability.md). Every physical
  // magnitude is bounded by 1e100, NaN and Inf are refused in arrays too.
  const std::string paperWithLoads = paperScene() + " --set 'Loads/top/Side Set=load_top'";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"Materials/steel/Young Modulus=1e300", "(0, 1e+100]"},
      {"Materials/steel/Lame Mu=1e300", "(0, 1e+100]"},
      {"Materials/steel/Lame Lambda=-1e300", "[-1e+100, 1e+100]"},
      {"Loads/top/Traction={0,0,-1e300}", "magnitude <= 1e+100"},
      {"Loads/top/Traction={0,0,nan}", "is not a finite number"},
      {"Loads/top/Traction={0,0,inf}", "is not a finite number"},
      {"Loads/weight/Volume Force={0,0,1e300}", "magnitude <= 1e+100"},
      {"Boundary/pull/Displacement={1e300,0,0}", "magnitude <= 1e+100"},
      {"Contact/F1=1e300", "[0, 1e+100]"},
      {"Contact/Slip Bound=1e300", "[0, 1e+100]"},
      {"Mesh/Initial Gap=1e300", "[0, 1e+100]"}};
  for (const auto& [set, range] : cases) {
    const std::string path = set.substr(0, set.find('='));
    expectRefused("--input " + paperWithLoads + " --set '" + set + "'", {"--set \"" + set + "\"", path, range});
  }
  // In the file, the file is named.
  const std::string traction = "<ParameterList name=\"Loads\"><ParameterList name=\"top\">" +
                               parameter("Side Set", "string", "load_top") +
                               parameter("Traction", "Array(double)", "{0, 0, -1e300}") + "</ParameterList></ParameterList>";
  expectRefused("--input " + scene("huge.xml", tribosList(traction)), {"huge.xml", "Loads/top/Traction", "1e+100"});
  // A stiffness contrast beyond double precision (1e16 ran without end): both blocks named.
  const std::string contrast =
      " --set 'Materials/aluminium/Young Modulus=7e4' --set 'Materials/aluminium/Poisson Ratio=0.35'"
      " --set 'Materials/steel/Poisson Ratio=0.35' --set 'Materials/steel/Young Modulus=";
  expectRefused("--input " + paperScene() + contrast + "7e20'", {"two_bricks.xml", "\"steel\"", "\"aluminium\"", "1e+16 > 1e15"});
  // Just inside the bound it is no input error: a dry run passes.
  const auto run = runCommand(kDriver + " --input " + paperScene() + contrast + "7e18' --dry-run");
  EXPECT_EQ(run.status, 0) << run.output;
}

TEST_F(DriverInput, brokenOrDeeplyNestedXmlIsAnInputError) {
  expectRefused("--input " + scene("broken.xml", "<ParameterList name=\"Tribos\"><Parameter name=\"x\""),
                {"broken.xml", "not a valid XML parameter list"});
  expectRefused("--input " + scene("unclosed.xml", "<ParameterList name=\"Tribos\"><ParameterList name=\"Mesh\">"),
                {"unclosed.xml"});
  // 100000 nested lists crashed the recursive reader (signal 11).
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += "<ParameterList name=\"a\">";
  for (int i = 0; i < 100000; ++i) deep += "</ParameterList>";
  expectRefused("--input " + scene("deep.xml", tribosList(deep)), {"deep.xml", "nests more than 64"});
}

TEST_F(DriverInput, badKokkosOptionsAreInputErrors) {
  // Kokkos threw std::invalid_argument from inside Kokkos::initialize (signal 6).
  for (const std::string option : {"--kokkos-num-threads=abc", "--kokkos-threads=abc", "--kokkos-threads=2.5",
                                   "--kokkos-threads", "--kokkos-num-devices=2,x"})
    expectRefused("--input " + paperScene() + " " + option, {option.substr(0, option.find('='))});
  // Kokkos never sees options without its prefix (it aborted on --threads=abc).
  expectRefused("--input " + paperScene() + " --threads=abc", {"--threads=abc"});
}

TEST_F(DriverInput, aSceneTooLargeForMemoryIsAnInputErrorBeforeTheMesh) {
  // H/h = 200 was std::bad_alloc (exit 1) while the mesh was generated.
  expectRefused("--input " + paperScene() + " --dry-run --set 'Mesh/H Over h=200'",
                {"two_bricks.xml", "H Over h = 200", "GiB of memory", "Reduce Mesh/H Over h"});
  expectRefused("--input " + paperScene() + " --dry-run --set 'Mesh/Subdomains Per Brick=1000x500x500'",
                {"Subdomains Per Brick = 1000x500x500", "32-bit"});
  // An address-space limit (ulimit -v 8 GB): H/h = 60 ran 55 s into std::bad_alloc; its four
  // subdomain factors alone need more. The dry run, which factorises nothing, still runs.
  const auto limited = runCommand("ulimit -v 8000000 && " + kDriver + " --input " + paperScene() +
                                  " --set 'Mesh/H Over h=60'");
  EXPECT_EQ(limited.status, 2) << limited.output;
  EXPECT_TRUE(contains(limited.output, "factor nonzeros at least")) << limited.output;
  // (A machine with less memory than the estimate refuses it for that first.)
  EXPECT_TRUE(contains(limited.output, "under its address-space limit (ulimit -v)") ||
              contains(limited.output, "(physical memory or the cgroup's limit)"))
      << limited.output;
  EXPECT_FALSE(contains(limited.output, "bad_alloc")) << limited.output;
}

TEST_F(DriverInput, limitsThatEndASolveNameThemselves) {
  // `resultsWritten` false: the limit came before the solve ended anything (the set-up).
  auto run = [&](const std::string& scene, const std::string& sets, bool resultsWritten = true) {
    const auto summary = dir_ / "s.json", exo = dir_ / "r.exo";
    fs::remove(summary);
    fs::remove(exo);
    const auto r = runCommand(kDriver + " --input " + scene + " --set Solver/Verbose=false " + sets + " --summary " +
                              quote(summary.string()) + " --output " + quote(exo.string()));
    EXPECT_EQ(r.status, 3) << sets << "\n" << r.output;
    EXPECT_EQ(fs::exists(exo), resultsWritten) << "results are written when a solve ended\n" << r.output;
    const auto json = nlohmann::json::parse(std::ifstream(summary));
    EXPECT_FALSE(json.at("converged").get<bool>());
    return json.at("message").get<std::string>();
  };
  // A budget far below the set-up's time: it ends at the first check, on any machine, before
  // the solve; the summary says so.
  std::string message = run(paperScene(), "--set 'Solver/Max Seconds=0.001'", false);
  EXPECT_TRUE(contains(message, "stopped: Solver/Max Seconds = 0.001 reached after ")) << message;
  EXPECT_TRUE(contains(message, "during reading the mesh (nothing solved, no results written)")) << message;
  message = run(paperScene(), "--set 'Solver/Max Outer Iterations=2'");
  EXPECT_TRUE(contains(message, "stopped: Solver/Max Outer Iterations = 2 reached")) << message;
  message = run(paperScene(), "--set 'Solver/Max Outer Iterations=3' --set 'Solver/MPGP/max iterations=2'");
  EXPECT_TRUE(contains(message, "ended at Solver/MPGP/max iterations = 2")) << message;
  message = run(paperScene(), "--set 'Contact/Fixed Point=Exact' --set 'Contact/Max Fixed Point Iterations=1'");
  EXPECT_TRUE(contains(message, "stopped: Contact/Max Fixed Point Iterations = 1 reached")) << message;
  // The linear solve (bonded bricks): the CG cap and the budget.
  const std::string bonded = quote(tribos::test::sourceDir() + "/input/two_bricks_bonded.xml");
  message = run(bonded, "--set 'FETI/Max Iterations=2'");
  EXPECT_TRUE(contains(message, "stopped: FETI/Max Iterations = 2 reached")) << message;
  message = run(bonded, "--set 'Solver/Max Seconds=0.001'", false);
  EXPECT_TRUE(contains(message, "stopped: Solver/Max Seconds = 0.001 reached")) << message;
}

TEST_F(DriverInput, theParameterListingShowsRangesAndTheBudget) {
  const auto run = runCommand(kDriver + " --list-parameters");
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* line : {"Solver/SMALSE-M/rho  (double, default 10, range (0, inf))",
                           "Solver/SMALSE-M/beta  (double, default 0.9, range (0, 1))",
                           "Solver/MPGP/step scale  (double, default 1.9, range (0, 2))",
                           "Solver/Max Seconds  (double, default 0, range [0, inf))",
                           "Materials/*/Poisson Ratio  (double, default none (required), range (-1, 0.5))"})
    EXPECT_TRUE(contains(run.output, line)) << line << "\n" << run.output;
}
