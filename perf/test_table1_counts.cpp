// Perf regression guard (label perf): the solver's counts on Table 1 cells stay within the
// two-sided band of perf/baselines/table1_counts.json. Counts, not times: they are what does
// not depend on the machine (STYLE.md 7). Times are recorded by perf/tools/table1.sh.
// A count above the band is a regression; a count below it fails too, so that an improvement
// is written into the baseline on purpose (and a later drift back up is caught from there).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
// One count of one cell against its band [low, high] around the baseline.
void expectWithinBand(const std::string& what, double count, double baseline, double low, double high) {
  EXPECT_LE(count, high) << what << " " << count << " is more than the baseline " << baseline << " allows (at most "
                         << high << "): a regression, or a change whose cost must be written into "
                         << "perf/baselines/table1_counts.json in a commit that says why";
  EXPECT_GE(count, low) << what << " " << count << " is fewer than the baseline " << baseline << " allows (at least "
                        << low << "): update perf/baselines/table1_counts.json in a commit that says why";
}
}  // namespace

TEST(table1Counts, stayWithinTheBaselineBand) {
  const auto root = tribos::test::sourceDir();
  std::ifstream in(root + "/perf/baselines/table1_counts.json");
  ASSERT_TRUE(in) << "missing perf/baselines/table1_counts.json";
  const auto baseline = nlohmann::json::parse(in);
  const int outerBand = baseline["band"]["outer"];
  const double pfpBand = baseline["band"]["pfp_relative"];
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_perf_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const auto& cell : baseline["cells"]) {
    // A Table 1 cell (grid, h) of the paper's scene, or any scene under input/ with overrides
    // (the curved contacts: a default must win there too, not only on the bricks).
    std::string name, args;
    if (cell.contains("input")) {
      name = cell["input"].get<std::string>();
      args = " --input " + tribos::test::quote(root + "/input/" + name);
      for (const auto& o : cell["set"]) {
        args += " --set " + tribos::test::quote(o.get<std::string>());
        name += " " + o.get<std::string>();
      }
    } else {
      const std::string grid = cell["grid"];
      const int h = cell["h"];
      name = grid + "_" + std::to_string(h);
      args = " --input " + tribos::test::quote(root + "/input/two_bricks.xml") + " --set 'Mesh/Subdomains Per Brick=" +
             grid + "' --set 'Mesh/H Over h=" + std::to_string(h) + "'";
    }
    SCOPED_TRACE(name);
    const auto summary = (dir / "summary.json").string();
    const auto run = tribos::test::runCommand(std::string(TRIBOS_DRIVER) + args +
                                              " --set Solver/Verbose=false --summary " + summary);
    ASSERT_EQ(run.status, 0) << run.output;
    std::ifstream s(summary);
    const auto j = nlohmann::json::parse(s);
    EXPECT_TRUE(j["converged"].get<bool>());
    const int outer = j["outer_iterations"], pfp = j["pfp_applications"];
    const int outerBase = cell["outer"], pfpBase = cell["pfp"];
    std::printf("cell %s: outer %d (baseline %d), pfp %d (baseline %d)\n", name.c_str(), outer, outerBase, pfp,
                pfpBase);
    std::fflush(stdout);
    // A cell whose counts differ between machines (the same source and flags; round-off of the
    // machine's libraries in a scene that amplifies it) lists what the others measured: the band
    // then runs from the smallest to the largest of them.
    int outerLow = outerBase, outerHigh = outerBase, pfpLow = pfpBase, pfpHigh = pfpBase;
    for (const auto& other : cell.value("other_machines", nlohmann::json::array())) {
      outerLow = std::min(outerLow, other["outer"].get<int>()), outerHigh = std::max(outerHigh, other["outer"].get<int>());
      pfpLow = std::min(pfpLow, other["pfp"].get<int>()), pfpHigh = std::max(pfpHigh, other["pfp"].get<int>());
    }
    expectWithinBand("outer_iterations", outer, outerBase, outerLow - outerBand, outerHigh + outerBand);
    expectWithinBand("pfp_applications", pfp, pfpBase, pfpLow * (1.0 - pfpBand), pfpHigh * (1.0 + pfpBand));
    RecordProperty("outer " + name, outer);
    RecordProperty("pfp " + name, pfp);
  }
  std::filesystem::remove_all(dir);
}
