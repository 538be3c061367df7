// The command line behaves like the tools users know: --help shows Tribos's usage first
// (Kokkos's options only on request), --version names the revision and the dependencies,
// a bad option exits 2 with the usage; progress reaches a redirected log as it happens, a
// progress line appears inside inner solves, idle OpenMP threads sleep by default, and the
// JSON summary has one history entry per outer iteration.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
using tribos::test::quote;
using tribos::test::runCommand;

const std::string kDriver = TRIBOS_DRIVER;
std::string scene() { return tribos::test::sourceDir() + "/input/two_bricks.xml"; }

std::filesystem::path scratch() {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_cli_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

std::string readFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Starts `command` through the shell with stdout and stderr to `log` (a file, not a
// terminal); returns its process id.
pid_t startInBackground(const std::string& command, const std::filesystem::path& log) {
  const std::string line = "exec " + command + " > " + quote(log.string()) + " 2>&1";
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", line.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}
/// Ends a background run: SIGTERM, and SIGKILL if it is still there 10 s later (a run stuck where
/// it does not take SIGTERM once held this test until CTest's 300 s timeout, its log unseen).
void stopWithin10Seconds(pid_t pid) {
  kill(pid, SIGTERM);
  for (int k = 0; k < 200; ++k) {
    if (waitpid(pid, nullptr, WNOHANG) == pid) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  kill(pid, SIGKILL);
  waitpid(pid, nullptr, 0);
}
}  // namespace

TEST(tribosCommandLine, helpShowsTribosUsageFirstAndKokkosOnlyOnRequest) {
  auto run = runCommand(kDriver + " --help");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(run.output.rfind("tribos: 3D contact", 0), 0u) << "the usage must come first:\n" << run.output;
  EXPECT_EQ(run.output.find("Kokkos command line"), std::string::npos) << run.output;
  for (const char* option : {"--input", "--version", "--kokkos-help", "--dry-run"})
    EXPECT_NE(run.output.find(option), std::string::npos) << option;
  run = runCommand(kDriver + " --kokkos-help");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("--kokkos-threads"), std::string::npos) << run.output;
}

TEST(tribosCommandLine, versionNamesTheRevisionAndTheDependencies) {
  const auto run = runCommand(kDriver + " --version");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_EQ(firstLine(run.output).rfind("tribos ", 0), 0u) << run.output;
  EXPECT_GT(firstLine(run.output).size(), std::string("tribos ").size()) << "a revision or \"unknown\"";
  for (const char* dependency : {"Trilinos 13.", "Kokkos ", "METIS ", "Exodus II", "CHOLMOD ", "MPI ", "compiler "})
    EXPECT_NE(run.output.find(dependency), std::string::npos) << dependency << " in\n" << run.output;
}

TEST(tribosCommandLine, aBadOptionExitsWith2AndShowsTheUsage) {
  for (const std::string args : {"--input " + quote(scene()) + " --no-such-flag", std::string("--dry-run"),
                                 "--input " + quote(scene()) + " --output"}) {
    const auto run = runCommand(kDriver + " " + args);
    EXPECT_EQ(run.status, 2) << args << "\n" << run.output;
    EXPECT_EQ(firstLine(run.output).rfind("tribos: error: command line:", 0), 0u) << run.output;
    EXPECT_NE(run.output.find("Usage: "), std::string::npos) << run.output;
  }
  EXPECT_NE(runCommand(kDriver + " --no-such-flag").output.find("--no-such-flag"), std::string::npos);
}

TEST(tribosCommandLine, progressReachesARedirectedLogAsItHappens) {
  // A solve of many seconds with stdout to a file: the header must be in the file while the
  // solve still runs (block buffering would hold it until the exit). 8x4x4 / H/h 3 had become a
  // 0.5 s run: a poll delayed by a loaded machine then found the header and the exit at once,
  // and the test failed without a fault. 10x5x5 / H/h 4 runs for seconds after the header.
  const auto dir = scratch();
  const auto log = dir / "log.txt";
  const pid_t pid = startInBackground(kDriver + " --input " + quote(scene()) +
                                          " --set 'Mesh/Subdomains Per Brick=10x5x5' --set 'Mesh/H Over h=4'",
                                      log);
  ASSERT_GT(pid, 0);
  bool headerSeen = false, exited = false;
  const auto start = std::chrono::steady_clock::now();
  while (!headerSeen && !exited && std::chrono::steady_clock::now() - start < std::chrono::seconds(120)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    headerSeen = readFile(log).find("n_primal = ") != std::string::npos;
    int status = 0;
    exited = waitpid(pid, &status, WNOHANG) == pid;
  }
  if (!exited) stopWithin10Seconds(pid);
  EXPECT_TRUE(headerSeen) << "no header within 120 s; the log:\n" << readFile(log);
  EXPECT_FALSE(exited) << "the solve ended before the header was seen: the test proves nothing\n" << readFile(log);
  std::filesystem::remove_all(dir);
}

TEST(tribosCommandLine, historyHasOneEntryPerOuterIterationAndProgressLinesCanBeForced) {
  const auto dir = scratch();
  const auto summaryPath = dir / "summary.json";
  // Progress Interval = 0: a line every 10 MPGP iterations inside the inner solves.
  const auto run = runCommand(kDriver + " --input " + quote(scene()) + " --set 'Solver/Progress Interval=0'" +
                              " --summary " + quote(summaryPath.string()));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("in progress: MPGP     10"), std::string::npos) << run.output;
  const auto summary = nlohmann::json::parse(readFile(summaryPath));
  const auto& history = summary.at("history");
  ASSERT_EQ(static_cast<int>(history.size()), summary.at("outer_iterations").get<int>());
  long long previous = 0;
  int inner = 0;
  for (size_t k = 0; k < history.size(); ++k) {
    const auto& h = history[k];
    EXPECT_EQ(h.at("outer").get<int>(), static_cast<int>(k + 1));
    EXPECT_GT(h.at("pfp_applications").get<long long>(), previous) << "F applications must grow";
    previous = h.at("pfp_applications").get<long long>();
    inner += h.at("inner").get<int>();
    for (const char* key : {"projected_gradient", "equality_residual", "M", "slip_bound_change", "elapsed_s"})
      EXPECT_TRUE(h.contains(key)) << key;
  }
  EXPECT_EQ(previous, summary.at("pfp_applications").get<long long>());
  EXPECT_EQ(inner, summary.at("inner_iterations").get<int>());
  // Converged: the last entry's residuals are within the tolerance.
  const double eps = summary.at("tolerance").get<double>();
  EXPECT_LE(history.back().at("projected_gradient").get<double>(), eps);
  EXPECT_LE(history.back().at("slip_bound_change").get<double>(), eps);
  // Without Verbose there are no lines, but the history is still written.
  const auto quiet = runCommand(kDriver + " --input " + quote(scene()) + " --set Solver/Verbose=false --summary " +
                                quote(summaryPath.string()));
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_EQ(quiet.output.find("outer "), std::string::npos) << quiet.output;
  EXPECT_EQ(nlohmann::json::parse(readFile(summaryPath)).at("history").size(), history.size());
  std::filesystem::remove_all(dir);
}

TEST(tribosCommandLine, idleOpenMpThreadsSleepUnlessTheUserChoseOtherwise) {
  // libgomp shows its spin count with OMP_DISPLAY_ENV=verbose: 0 under PASSIVE. The first
  // process prints the default before it executes itself again with PASSIVE.
  const std::string show = "env -u OMP_WAIT_POLICY OMP_NUM_THREADS=2 OMP_DISPLAY_ENV=verbose ";
  const auto run = runCommand(show + kDriver + " --version");
  ASSERT_EQ(run.status, 0) << run.output;
  if (run.output.find("GOMP_SPINCOUNT") == std::string::npos) GTEST_SKIP() << "not libgomp: cannot observe";
  EXPECT_NE(run.output.find("GOMP_SPINCOUNT = '0'"), std::string::npos) << run.output;
  const auto chosen = runCommand("env OMP_WAIT_POLICY=active OMP_NUM_THREADS=2 OMP_DISPLAY_ENV=verbose " + kDriver +
                                 " --version");
  EXPECT_NE(chosen.output.find("OMP_WAIT_POLICY = 'ACTIVE'"), std::string::npos) << chosen.output;
  EXPECT_EQ(chosen.output.find("GOMP_SPINCOUNT = '0'"), std::string::npos) << chosen.output;
}

// Where two coarse solves read at least twice the bytes of F's subdomain solves (many small
// subdomains: 14x7x7 per brick at H/h 2, ratio 2.3), the progress output says that the coarse
// problem dominates and that fewer, larger subdomains would be faster, and names the coarse
// factor's precision ("Auto" rounds it there); on the paper's smallest cell it says neither.
TEST(tribosCommandLine, aDecompositionTooFineForTheCoarseProblemIsPointedOut) {
  const std::string oneOuter = " --set 'Mesh/H Over h=2' --set 'Solver/Max Outer Iterations=1'";
  const auto fine = runCommand(kDriver + " --input " + quote(scene()) + " --set 'Mesh/Subdomains Per Brick=14x7x7'" +
                               oneOuter);
  EXPECT_EQ(fine.status, 3) << fine.output;  // one outer iteration: not converged
  EXPECT_NE(fine.output.find("note: the coarse problem dominates"), std::string::npos) << fine.output;
  EXPECT_NE(fine.output.find("fewer, larger subdomains would be faster"), std::string::npos);
  EXPECT_NE(fine.output.find("coarse factor: single precision"), std::string::npos);
  const auto coarse = runCommand(kDriver + " --input " + quote(scene()) + oneOuter);
  EXPECT_EQ(coarse.output.find("coarse problem dominates"), std::string::npos) << coarse.output;
  EXPECT_EQ(coarse.output.find("coarse factor:"), std::string::npos);
}
