// Exodus II: write -> read round trip is identical; bad files are input errors naming the file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <exodusII.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;
using namespace tribos::mesh;

namespace {
std::string scratch(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("tribos_exo_" + std::to_string(::getpid()) + "_" + name)).string();
}

void expectInputErrorNaming(const std::string& path) {
  try {
    readExodus(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(ExodusIO, roundTripIsIdentical) {
  const Mesh mesh = generateTwoBricks({{2, 1, 1}, 2});
  std::vector<TimeStep> steps(2);
  for (int s = 0; s < 2; ++s) {
    steps[s].time = 0.5 * (s + 1);
    for (const char* name : {"displ_x", "contact_status"}) {
      Field f{name, std::vector<double>(mesh.numNodes())};
      for (LO n = 0; n < mesh.numNodes(); ++n) f.values[n] = std::sin(n + 0.1 * s) * (name[0] == 'd' ? 1e-3 : 2.0);
      steps[s].nodal.push_back(f);
    }
    Field sub{"subdomain", std::vector<double>(mesh.numElements())};
    for (LO e = 0; e < mesh.numElements(); ++e) sub.values[e] = e % 7 + s;
    steps[s].element.push_back(sub);
  }
  const std::string path = scratch("roundtrip.exo");
  writeExodus(path, mesh, steps);
  const ExodusData back = readExodus(path);
  EXPECT_EQ(back.mesh.coords, mesh.coords);
  EXPECT_EQ(back.mesh.tets, mesh.tets);
  ASSERT_EQ(back.mesh.blocks.size(), mesh.blocks.size());
  for (size_t b = 0; b < mesh.blocks.size(); ++b) {
    EXPECT_EQ(back.mesh.blocks[b].name, mesh.blocks[b].name);
    EXPECT_EQ(back.mesh.blocks[b].id, mesh.blocks[b].id);
    EXPECT_EQ(back.mesh.blocks[b].count, mesh.blocks[b].count);
  }
  ASSERT_EQ(back.mesh.nodeSets.size(), mesh.nodeSets.size());
  for (size_t s = 0; s < mesh.nodeSets.size(); ++s) {
    EXPECT_EQ(back.mesh.nodeSets[s].name, mesh.nodeSets[s].name);
    EXPECT_EQ(back.mesh.nodeSets[s].nodes, mesh.nodeSets[s].nodes);
  }
  ASSERT_EQ(back.mesh.sideSets.size(), mesh.sideSets.size());
  for (size_t s = 0; s < mesh.sideSets.size(); ++s) {
    EXPECT_EQ(back.mesh.sideSets[s].name, mesh.sideSets[s].name);
    EXPECT_EQ(back.mesh.sideSets[s].elements, mesh.sideSets[s].elements);
    EXPECT_EQ(back.mesh.sideSets[s].sides, mesh.sideSets[s].sides);
  }
  ASSERT_EQ(back.steps.size(), 2u);
  for (int s = 0; s < 2; ++s) {
    EXPECT_EQ(back.steps[s].time, steps[s].time);
    ASSERT_EQ(back.steps[s].nodal.size(), 2u);
    for (int v = 0; v < 2; ++v) {
      EXPECT_EQ(back.steps[s].nodal[v].name, steps[s].nodal[v].name);
      EXPECT_EQ(back.steps[s].nodal[v].values, steps[s].nodal[v].values);
    }
    EXPECT_EQ(back.steps[s].element[0].values, steps[s].element[0].values);
  }
  std::filesystem::remove(path);
}

TEST(ExodusIO, badFilesAreInputErrorsNamingTheFile) {
  expectInputErrorNaming("/nonexistent/mesh.exo");
  const std::string text = scratch("text.exo");
  std::ofstream(text) << "this is not an Exodus file\n";
  expectInputErrorNaming(text);

  // A hexahedral block.
  const std::string hex = scratch("hex.exo");
  {
    int cpu = 8, io = 8;
    const int id = ex_create(hex.c_str(), EX_CLOBBER, &cpu, &io);
    ASSERT_GE(id, 0);
    ex_put_init(id, "hex", 3, 8, 1, 1, 0, 0);
    const double x[8] = {0, 1, 1, 0, 0, 1, 1, 0}, y[8] = {0, 0, 1, 1, 0, 0, 1, 1}, z[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    ex_put_coord(id, x, y, z);
    ex_put_block(id, EX_ELEM_BLOCK, 1, "HEX8", 1, 8, 0, 0, 0);
    const int conn[8] = {1, 2, 3, 4, 5, 6, 7, 8};
    ex_put_conn(id, EX_ELEM_BLOCK, 1, conn, nullptr, nullptr);
    ex_close(id);
  }
  expectInputErrorNaming(hex);

  // An inverted tetrahedron.
  Mesh bad;
  bad.coords = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  bad.tets = {{0, 2, 1, 3}};
  bad.blocks = {{"body", 1, 0, 1}};
  const std::string inverted = scratch("inverted.exo");
  writeExodus(inverted, bad);
  expectInputErrorNaming(inverted);
  for (const auto& p : {text, hex, inverted}) std::filesystem::remove(p);
}
