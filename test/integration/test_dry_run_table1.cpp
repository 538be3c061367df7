// tribos --dry-run reproduces the dimensions of the paper's Table 1: n (primal dofs) and
// l (rigid body modes) for all 20 cells. The figures below are this test's own copy of
// ../shared/paper/table1.csv (2s, H/h, n, l).
#include <unistd.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
struct Cell {
  int subdomains, hOverH;
  long long n, l;
};
const Cell kTable1[] = {
    {4, 2, 324, 24},        {4, 3, 768, 24},        {4, 4, 1500, 24},       {4, 5, 2592, 24},
    {32, 2, 2592, 192},     {32, 3, 6144, 192},     {32, 4, 12000, 192},    {32, 5, 20736, 192},
    {108, 2, 8748, 648},    {108, 3, 20736, 648},   {108, 4, 40500, 648},   {108, 5, 69984, 648},
    {256, 2, 20736, 1536},  {256, 3, 49152, 1536},  {256, 4, 96000, 1536},  {256, 5, 165888, 1536},
    {500, 2, 40500, 3000},  {500, 3, 96000, 3000},  {500, 4, 187500, 3000}, {500, 5, 324000, 3000}};

// 2s subdomains in two bricks of s = nx * ny * nz with nx = 2 ny = 2 nz.
std::string gridFor(int subdomains) {
  const int s = subdomains / 2;
  for (int ny = 1; ny <= 10; ++ny)
    if (2 * ny * ny * ny == s) return std::to_string(2 * ny) + "x" + std::to_string(ny) + "x" + std::to_string(ny);
  return "invalid";
}
}  // namespace

TEST(tribosDryRun, dimensionsMatchTable1) {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_table1_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const Cell& cell : kTable1) {
    SCOPED_TRACE("2s = " + std::to_string(cell.subdomains) + ", H/h = " + std::to_string(cell.hOverH));
    const auto summary = dir / ("cell_" + std::to_string(cell.subdomains) + "_" + std::to_string(cell.hOverH) + ".json");
    const auto run = tribos::test::runCommand(
        std::string(TRIBOS_DRIVER) + " --input " + tribos::test::quote(tribos::test::sourceDir() + "/input/two_bricks.xml") +
        " --dry-run --set 'Mesh/Subdomains Per Brick=" + gridFor(cell.subdomains) + "' --set 'Mesh/H Over h=" +
        std::to_string(cell.hOverH) + "' --summary " + tribos::test::quote(summary.string()));
    ASSERT_EQ(run.status, 0) << run.output;
    std::ifstream in(summary);
    const auto j = nlohmann::json::parse(in);
    EXPECT_EQ(j.at("n_primal").get<long long>(), cell.n);
    EXPECT_EQ(j.at("n_rigid").get<long long>(), cell.l);
    EXPECT_EQ(j.at("n_subdomains").get<int>(), cell.subdomains);
  }
  std::filesystem::remove_all(dir);
}
