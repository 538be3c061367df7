// Exodus II: write -> read round trip is identical (bitwise); files written by other tools
// (no names, 64-bit ids, unsorted node sets, element variables on some blocks) read as
// documented; bad files are input errors naming the file; bad writer calls are rejected.
#include <gtest/gtest.h>
#include <unistd.h>

#include <exodusII.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;
using namespace tribos::mesh;

namespace {

/// A fresh directory per test under the system temp dir, removed with everything in it.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag)
      : dir_(std::filesystem::temp_directory_path() / ("tribos_exo_" + std::to_string(::getpid()) + "_" + tag)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

/// Unit cube cut into 6 tetrahedra around the diagonal 0-6 (Kuhn triangulation); the first
/// three tets form block "lower" (id 10), the last three "upper" (id 20). Node set "bottom"
/// (id 3): nodes on z = 0; side set "top" (id 7): faces on z = 1.
Mesh cubeMesh() {
  Mesh m;
  // Corners in the usual HEX8 order: bottom face counter-clockwise, then the top face.
  m.coords = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (const auto& tet : {std::array<LO, 4>{0, 1, 2, 6}, {0, 2, 3, 6}, {0, 3, 7, 6}, {0, 7, 4, 6}, {0, 4, 5, 6}, {0, 5, 1, 6}})
    m.elements.add(ElementType::Tet4, tet.data());
  for (LO e = 0; e < m.numElements(); ++e)
    if (m.elementVolume(e) < 0) std::swap(m.elements.mutableNodes(e)[1], m.elements.mutableNodes(e)[2]);  // orient positively
  m.blocks = {{"lower", 10, 0, 3}, {"upper", 20, 3, 3}};
  NodeSet bottom{"bottom", 3, {}};
  for (LO n = 0; n < m.numNodes(); ++n)
    if (m.coords[n][2] == 0.0) bottom.nodes.push_back(n);
  m.nodeSets = {bottom};
  SideSet top{"top", 7, {}, {}};
  for (LO e = 0; e < m.numElements(); ++e)
    for (int s = 0; s < 4; ++s) {
      bool onTop = true;
      for (LO n : m.faceNodes(e, s)) onTop = onTop && m.coords[n][2] == 1.0;
      if (onTop) {
        top.elements.push_back(e);
        top.sides.push_back(s);
      }
    }
  m.sideSets = {top};
  return m;
}

bool bitwiseEqual(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// Two steps, two nodal fields and one element field with values that do not survive a
/// float or text round trip (so a lossy writer would be caught).
std::vector<TimeStep> someSteps(const Mesh& mesh) {
  std::vector<TimeStep> steps(2);
  for (int s = 0; s < 2; ++s) {
    steps[s].time = 0.1 * (s + 1) + 1.0 / 3.0;
    for (const char* name : {"displacement_x", "contact_pressure"}) {
      Field f{name, std::vector<double>(mesh.numNodes())};
      for (LO n = 0; n < mesh.numNodes(); ++n) f.values[n] = std::sin(n + 0.1 * s) * (name[0] == 'd' ? 1e-3 : 2e7);
      steps[s].nodal.push_back(f);
    }
    Field sub{"subdomain", std::vector<double>(mesh.numElements())};
    for (LO e = 0; e < mesh.numElements(); ++e) sub.values[e] = e % 7 + s + 1.0 / 7.0;
    steps[s].element.push_back(sub);
  }
  return steps;
}

void expectSameMesh(const Mesh& back, const Mesh& mesh) {
  ASSERT_EQ(back.coords.size(), mesh.coords.size());
  EXPECT_EQ(std::memcmp(back.coords.data(), mesh.coords.data(), mesh.coords.size() * sizeof(mesh.coords[0])), 0)
      << "coordinates differ bitwise";
  EXPECT_TRUE(back.elements == mesh.elements);
  ASSERT_EQ(back.blocks.size(), mesh.blocks.size());
  for (size_t b = 0; b < mesh.blocks.size(); ++b) {
    EXPECT_EQ(back.blocks[b].name, mesh.blocks[b].name);
    EXPECT_EQ(back.blocks[b].id, mesh.blocks[b].id);
    EXPECT_EQ(back.blocks[b].first, mesh.blocks[b].first);
    EXPECT_EQ(back.blocks[b].count, mesh.blocks[b].count);
  }
  ASSERT_EQ(back.nodeSets.size(), mesh.nodeSets.size());
  for (size_t s = 0; s < mesh.nodeSets.size(); ++s) {
    EXPECT_EQ(back.nodeSets[s].name, mesh.nodeSets[s].name);
    EXPECT_EQ(back.nodeSets[s].id, mesh.nodeSets[s].id);
    EXPECT_EQ(back.nodeSets[s].nodes, mesh.nodeSets[s].nodes);
  }
  ASSERT_EQ(back.sideSets.size(), mesh.sideSets.size());
  for (size_t s = 0; s < mesh.sideSets.size(); ++s) {
    EXPECT_EQ(back.sideSets[s].name, mesh.sideSets[s].name);
    EXPECT_EQ(back.sideSets[s].id, mesh.sideSets[s].id);
    EXPECT_EQ(back.sideSets[s].elements, mesh.sideSets[s].elements);
    EXPECT_EQ(back.sideSets[s].sides, mesh.sideSets[s].sides);
  }
}

void expectSameSteps(const std::vector<TimeStep>& back, const std::vector<TimeStep>& steps) {
  ASSERT_EQ(back.size(), steps.size());
  for (size_t s = 0; s < steps.size(); ++s) {
    EXPECT_TRUE(bitwiseEqual({back[s].time}, {steps[s].time})) << "time of step " << s + 1;
    ASSERT_EQ(back[s].nodal.size(), steps[s].nodal.size());
    for (size_t v = 0; v < steps[s].nodal.size(); ++v) {
      EXPECT_EQ(back[s].nodal[v].name, steps[s].nodal[v].name);
      EXPECT_TRUE(bitwiseEqual(back[s].nodal[v].values, steps[s].nodal[v].values)) << steps[s].nodal[v].name;
    }
    ASSERT_EQ(back[s].element.size(), steps[s].element.size());
    for (size_t v = 0; v < steps[s].element.size(); ++v) {
      EXPECT_EQ(back[s].element[v].name, steps[s].element[v].name);
      EXPECT_TRUE(bitwiseEqual(back[s].element[v].values, steps[s].element[v].values)) << steps[s].element[v].name;
    }
  }
}

/// readExodus(path) must throw core::InputError whose message starts with the path and
/// contains `what`.
void expectInputError(const std::string& path, const std::string& what) {
  try {
    readExodus(path);
    ADD_FAILURE() << "no error for " << path;
  } catch (const core::InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << "expected \"" << what << "\" in: " << msg;
  }
}

template <class F>
void expectInvalidArgument(F&& call, const std::string& what) {
  try {
    call();
    ADD_FAILURE() << "no std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << "expected \"" << what << "\" in: " << e.what();
  }
}

/// One block of `nodesPerElement`-node elements of `topology` with the raw API, the way
/// another tool would write it (no names), in `dim` dimensions.
void writeRawSingleBlock(const std::string& path, const char* topology, int nodesPerElement, int dim = 3) {
  int cpu = 8, io = 8;
  const int id = ex_create(path.c_str(), EX_CLOBBER, &cpu, &io);
  ASSERT_GE(id, 0) << path;
  ASSERT_EQ(ex_put_init(id, "other tool", dim, nodesPerElement, 1, 1, 0, 0), 0);
  std::vector<double> x(nodesPerElement), y(nodesPerElement), z(nodesPerElement);
  for (int n = 0; n < nodesPerElement; ++n) {
    x[n] = n % 2;
    y[n] = (n / 2) % 2;
    z[n] = n / 4;
  }
  ASSERT_EQ(ex_put_coord(id, x.data(), y.data(), dim == 3 ? z.data() : nullptr), 0);
  ASSERT_EQ(ex_put_block(id, EX_ELEM_BLOCK, 42, topology, 1, nodesPerElement, 0, 0, 0), 0);
  std::vector<int> conn(nodesPerElement);
  for (int n = 0; n < nodesPerElement; ++n) conn[n] = n + 1;
  ASSERT_EQ(ex_put_conn(id, EX_ELEM_BLOCK, 42, conn.data(), nullptr, nullptr), 0);
  ASSERT_EQ(ex_close(id), 0);
}
}  // namespace

TEST(ExodusIO, roundTripIsIdentical) {
  const ScratchDir dir("roundtrip");
  const Mesh mesh = cubeMesh();
  ASSERT_NO_THROW(mesh.validate("cubeMesh"));
  ASSERT_EQ(mesh.nodeSets[0].nodes.size(), 4u);
  ASSERT_EQ(mesh.sideSets[0].elements.size(), 2u);
  const auto steps = someSteps(mesh);
  const std::string path = dir.file("cube.exo");
  writeExodus(path, mesh, steps);
  const ExodusData back = readExodus(path);
  expectSameMesh(back.mesh, mesh);
  expectSameSteps(back.steps, steps);
}

TEST(ExodusIO, meshWithoutStepsAndLongNamesRoundTrips) {
  const ScratchDir dir("nosteps");
  Mesh mesh = cubeMesh();
  // Longer than the library's default of 32 characters and than our default of 64.
  mesh.sideSets[0].name = "a_side_set_name_that_is_quite_a_bit_longer_than_sixty_four_characters_in_total";
  const std::string path = dir.file("cube.exo");
  writeExodus(path, mesh);
  const ExodusData back = readExodus(path);
  expectSameMesh(back.mesh, mesh);
  EXPECT_TRUE(back.steps.empty());
}

TEST(ExodusIO, twoBricksRoundTripIsIdentical) {
  const ScratchDir dir("twobricks");
  const Mesh mesh = generateTwoBricks({{2, 1, 1}, 2});
  const auto steps = someSteps(mesh);
  const std::string path = dir.file("two_bricks.exo");
  writeExodus(path, mesh, steps);
  const ExodusData back = readExodus(path);
  expectSameMesh(back.mesh, mesh);
  expectSameSteps(back.steps, steps);
}

// Global variables per step and info records (how a result was made) survive the round
// trip; an info line longer than the format's 80 characters is wrapped, not cut.
TEST(ExodusIO, globalVariablesAndInfoRecordsRoundTrip) {
  const ScratchDir dir("globals");
  const Mesh mesh = cubeMesh();
  auto steps = someSteps(mesh);
  for (size_t s = 0; s < steps.size(); ++s)
    steps[s].global = {{"outer_iterations", 12.0 + s}, {"kkt_equilibrium", 1.0 / 3.0 * 1e-9}};
  const std::string longLine(170, 'x');
  const std::vector<std::string> info = {"tribos --input scene.xml", "", longLine};
  const std::string path = dir.file("globals.exo");
  writeExodus(path, mesh, steps, info);
  const ExodusData back = readExodus(path);
  expectSameSteps(back.steps, steps);
  for (size_t s = 0; s < steps.size(); ++s) {
    ASSERT_EQ(back.steps[s].global.size(), 2u);
    for (size_t v = 0; v < 2; ++v) {
      EXPECT_EQ(back.steps[s].global[v].name, steps[s].global[v].name);
      EXPECT_TRUE(bitwiseEqual({back.steps[s].global[v].value}, {steps[s].global[v].value}));
    }
  }
  EXPECT_EQ(back.info, (std::vector<std::string>{info[0], "", longLine.substr(0, 80), longLine.substr(80, 80),
                                                 longLine.substr(160)}));
  steps[1].global.pop_back();
  expectInvalidArgument([&] { writeExodus(dir.file("bad.exo"), mesh, steps); }, "global variables");
}

// The layout meshio writes: block and set ids from 0, no names, node sets only. Every entity
// is still named ("block_0", "nodeset_0"), and the file Tribos writes back reads the same.
TEST(ExodusIO, idsFromZeroAndUnnamedEntitiesRead) {
  const ScratchDir dir("zero");
  Mesh mesh = cubeMesh();
  mesh.blocks[0].id = 0;
  mesh.blocks[1].id = 1;
  for (auto& b : mesh.blocks) b.name.clear();
  mesh.nodeSets[0].id = 0;
  mesh.nodeSets[0].name.clear();
  mesh.sideSets.clear();
  const std::string path = dir.file("zero.exo");
  writeExodus(path, mesh);
  const ExodusData back = readExodus(path);
  ASSERT_EQ(back.mesh.blocks.size(), 2u);
  EXPECT_EQ(back.mesh.blocks[0].name, "block_0");
  EXPECT_EQ(back.mesh.blocks[0].id, 0);
  EXPECT_EQ(back.mesh.blocks[1].name, "block_1");
  EXPECT_TRUE(back.mesh.elements == mesh.elements);
  ASSERT_EQ(back.mesh.nodeSets.size(), 1u);
  EXPECT_EQ(back.mesh.nodeSets[0].name, "nodeset_0");
  EXPECT_EQ(back.mesh.nodeSets[0].nodes, mesh.nodeSets[0].nodes);
  const std::string again = dir.file("again.exo");
  writeExodus(again, back.mesh);
  expectSameMesh(readExodus(again).mesh, back.mesh);
}

TEST(ExodusIO, writerClobbersAnExistingFile) {
  const ScratchDir dir("clobber");
  const std::string path = dir.file("cube.exo");
  writeExodus(path, generateTwoBricks({{2, 1, 1}, 2}), {});
  const Mesh mesh = cubeMesh();
  writeExodus(path, mesh, someSteps(mesh));
  expectSameMesh(readExodus(path).mesh, mesh);
}

// A file as another tool writes it: 64-bit ids (netCDF-4), no names, lower-case topology,
// a node set in face order with repeats, an element variable stored on one block only.
TEST(ExodusIO, readsForeignFileWithDefaults) {
  const ScratchDir dir("foreign");
  const std::string path = dir.file("foreign.exo");
  const Mesh cube = cubeMesh();
  {
    int cpu = 8, io = 8;
    const int id = ex_create(path.c_str(), EX_CLOBBER | EX_NETCDF4 | EX_ALL_INT64_DB, &cpu, &io);
    ASSERT_GE(id, 0);
    ex_set_int64_status(id, EX_ALL_INT64_API);
    ASSERT_EQ(ex_put_init(id, "foreign", 3, 8, 6, 2, 1, 1), 0);
    std::vector<double> x, y, z;
    for (const auto& c : cube.coords) {
      x.push_back(c[0]);
      y.push_back(c[1]);
      z.push_back(c[2]);
    }
    ASSERT_EQ(ex_put_coord(id, x.data(), y.data(), z.data()), 0);
    for (const auto& b : cube.blocks) {
      ASSERT_EQ(ex_put_block(id, EX_ELEM_BLOCK, b.id, b.id == 10 ? "tetra" : "TET4", b.count, 4, 0, 0, 0), 0);
      std::vector<int64_t> conn;
      for (LO e = b.first; e < b.first + b.count; ++e)
        for (LO n : cube.elementNodes(e)) conn.push_back(n + 1);
      ASSERT_EQ(ex_put_conn(id, EX_ELEM_BLOCK, b.id, conn.data(), nullptr, nullptr), 0);
    }
    const std::vector<int64_t> nodes = {4, 1, 3, 1, 2, 4};  // 1-based, unsorted, repeated
    ASSERT_EQ(ex_put_set_param(id, EX_NODE_SET, 3, static_cast<int64_t>(nodes.size()), 0), 0);
    ASSERT_EQ(ex_put_set(id, EX_NODE_SET, 3, nodes.data(), nullptr), 0);
    const auto& top = cube.sideSets[0];
    std::vector<int64_t> elements, sides;
    for (size_t i = 0; i < top.elements.size(); ++i) {
      elements.push_back(top.elements[i] + 1);
      sides.push_back(top.sides[i] + 1);
    }
    ASSERT_EQ(ex_put_set_param(id, EX_SIDE_SET, 7, static_cast<int64_t>(elements.size()), 0), 0);
    ASSERT_EQ(ex_put_set(id, EX_SIDE_SET, 7, elements.data(), sides.data()), 0);
    ASSERT_EQ(ex_put_variable_param(id, EX_ELEM_BLOCK, 1), 0);
    char name[] = "stress";
    char* names[] = {name};
    ASSERT_EQ(ex_put_variable_names(id, EX_ELEM_BLOCK, 1, names), 0);
    int truth[2] = {0, 1};  // only on block 20
    ASSERT_EQ(ex_put_truth_table(id, EX_ELEM_BLOCK, 2, 1, truth), 0);
    const double time = 2.5, stress[3] = {1.5, 2.5, 3.5};
    ASSERT_EQ(ex_put_time(id, 1, &time), 0);
    ASSERT_EQ(ex_put_var(id, 1, EX_ELEM_BLOCK, 1, 20, 3, stress), 0);
    ASSERT_EQ(ex_close(id), 0);
  }
  const ExodusData data = readExodus(path);
  ASSERT_EQ(data.mesh.blocks.size(), 2u);
  EXPECT_EQ(data.mesh.blocks[0].name, "block_10");
  EXPECT_EQ(data.mesh.blocks[1].name, "block_20");
  EXPECT_TRUE(data.mesh.elements == cube.elements);
  ASSERT_EQ(data.mesh.nodeSets.size(), 1u);
  EXPECT_EQ(data.mesh.nodeSets[0].name, "nodeset_3");
  EXPECT_EQ(data.mesh.nodeSets[0].nodes, (std::vector<LO>{0, 1, 2, 3}));
  ASSERT_EQ(data.mesh.sideSets.size(), 1u);
  EXPECT_EQ(data.mesh.sideSets[0].name, "sideset_7");
  EXPECT_EQ(data.mesh.sideSets[0].elements, cube.sideSets[0].elements);
  EXPECT_EQ(data.mesh.sideSets[0].sides, cube.sideSets[0].sides);
  ASSERT_EQ(data.steps.size(), 1u);
  EXPECT_EQ(data.steps[0].time, 2.5);
  EXPECT_TRUE(data.steps[0].nodal.empty());
  ASSERT_EQ(data.steps[0].element.size(), 1u);
  EXPECT_EQ(data.steps[0].element[0].name, "stress");
  EXPECT_EQ(data.steps[0].element[0].values, (std::vector<double>{0, 0, 0, 1.5, 2.5, 3.5}));
}

TEST(ExodusIO, badFilesAreInputErrorsNamingTheFile) {
  const ScratchDir dir("errors");
  expectInputError(dir.file("missing.exo"), "does not exist");

  const std::string text = dir.file("text.exo");
  std::ofstream(text) << "this is not an Exodus file\n";
  expectInputError(text, "not an Exodus");

  // Element types Tribos does not take: the message names the block, and says what to
  // convert a 20-node hexahedron to.
  const std::string hex = dir.file("hex20.exo");
  writeRawSingleBlock(hex, "HEX20", 20);
  expectInputError(hex, "HEX20");
  expectInputError(hex, "block_42");
  expectInputError(hex, "Mesh.ElementOrder = 1");

  const std::string pyramid = dir.file("pyramid.exo");
  writeRawSingleBlock(pyramid, "PYRAMID5", 5);
  expectInputError(pyramid, "PYRAMID5");

  const std::string flat = dir.file("flat.exo");
  writeRawSingleBlock(flat, "TRI3", 3, 2);
  expectInputError(flat, "2D");

  Mesh inverted = cubeMesh();
  std::swap(inverted.elements.mutableNodes(4)[1], inverted.elements.mutableNodes(4)[2]);
  const std::string invertedPath = dir.file("inverted.exo");
  writeExodus(invertedPath, inverted);
  expectInputError(invertedPath, "element 5 of block \"upper\" is inverted");

  // Ids out of range: the writer copies them as they are, the reader must reject them.
  Mesh badNode = cubeMesh();
  badNode.nodeSets[0].nodes.push_back(99);
  const std::string badNodePath = dir.file("bad_node_set.exo");
  writeExodus(badNodePath, badNode);
  expectInputError(badNodePath, "node set \"bottom\" references node 100");

  Mesh badSide = cubeMesh();
  badSide.sideSets[0].sides[0] = 4;
  const std::string badSidePath = dir.file("bad_side.exo");
  writeExodus(badSidePath, badSide);
  expectInputError(badSidePath, "side 5 out of range");

  Mesh badConn = cubeMesh();
  badConn.elements.mutableNodes(0)[3] = 8;
  const std::string badConnPath = dir.file("bad_conn.exo");
  writeExodus(badConnPath, badConn);
  expectInputError(badConnPath, "references node 9 out of range");
}

TEST(ExodusIO, corruptCountsBadGeometryAndEmptyEntitiesAreInputErrors) {
  const ScratchDir dir("untrusted");
  auto written = [&](const std::string& name, const Mesh& mesh) {
    const std::string path = dir.file(name);
    writeExodus(path, mesh);
    return path;
  };
  // A node count in the netCDF header that the file cannot hold (classic format: the
  // dimension's 4-byte big-endian length follows its name, padded to 4 bytes).
  const std::string good = written("good.exo", cubeMesh());
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t at = bytes.find("num_nodes");
  ASSERT_NE(at, std::string::npos);
  bytes.replace(at + 12, 4, std::string("\x7f\xff\xff\xff", 4));
  std::ofstream(dir.file("corrupt.exo"), std::ios::binary) << bytes;
  expectInputError(dir.file("corrupt.exo"), "a corrupt one");

  Mesh nan = cubeMesh();
  nan.coords[5][0] = std::nan("");
  expectInputError(written("nan.exo", nan), "node 6 has a coordinate that is not finite");

  Mesh flat = cubeMesh();
  flat.coords[6] = {0.5, 0.5, 0.0};  // the diagonal's end on the bottom face: tets 1, 2 become flat
  expectInputError(written("flat.exo", flat), "element 1 of block \"lower\" is degenerate");

  Mesh emptyBlock = cubeMesh();
  emptyBlock.blocks.insert(emptyBlock.blocks.begin() + 1, {"hollow", 15, 3, 0});
  expectInputError(written("empty_block.exo", emptyBlock), "element block \"hollow\" (id 15) has no elements");

  // Sets may be empty in a file; using one is the error (Mesh::nodeSet, Mesh::sideSet).
  Mesh emptySets = cubeMesh();
  emptySets.nodeSets.push_back({"none", 4, {}});
  emptySets.sideSets.push_back({"nowhere", 8, {}, {}});
  const std::string emptySetsPath = written("empty_sets.exo", emptySets);
  const Mesh back = readExodus(emptySetsPath).mesh;
  for (const auto& lookup : {std::function<void()>([&] { back.nodeSet("none"); }),
                             std::function<void()>([&] { back.sideSet("nowhere"); })}) {
    try {
      lookup();
      ADD_FAILURE() << "an empty set in use";
    } catch (const core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("of the mesh (" + emptySetsPath + ") is empty"), std::string::npos) << e.what();
    }
  }

  // The cube's two blocks as one, next to a shifted copy of itself: one body in two pieces.
  Mesh two = cubeMesh();
  const LO offset = two.numNodes();
  for (LO n = 0; n < offset; ++n) two.coords.push_back({two.coords[n][0] + 3.0, two.coords[n][1], two.coords[n][2]});
  for (LO e = 0; e < 6; ++e) two.elements.add(ElementType::Tet4, {two.elementNodes(e)[0] + offset, two.elementNodes(e)[1] + offset,
                                                 two.elementNodes(e)[2] + offset, two.elementNodes(e)[3] + offset});
  two.blocks = {{"pair", 1, 0, 12}};
  two.sideSets.clear();
  expectInputError(written("two_pieces.exo", two), "element block \"pair\" is 2 separate pieces");
}

TEST(ExodusIO, writerRejectsBadCalls) {
  const ScratchDir dir("writer");
  const Mesh mesh = cubeMesh();

  EXPECT_THROW(writeExodus(dir.file("no_such_dir/cube.exo"), mesh), core::InputError);
  try {
    writeExodus(dir.file("no_such_dir/cube.exo"), mesh);
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.file("no_such_dir/cube.exo")), std::string::npos) << e.what();
  }

  auto steps = someSteps(mesh);
  steps[1].nodal[1].name = "contact_status";
  expectInvalidArgument([&] { writeExodus(dir.file("a.exo"), mesh, steps); }, "contact_status");

  steps = someSteps(mesh);
  steps[1].element.clear();
  expectInvalidArgument([&] { writeExodus(dir.file("b.exo"), mesh, steps); }, "subdomain");

  steps = someSteps(mesh);
  steps[0].nodal[0].values.pop_back();
  expectInvalidArgument([&] { writeExodus(dir.file("c.exo"), mesh, steps); }, "displacement_x");

  steps = someSteps(mesh);
  steps[1].element[0].values.push_back(0.0);
  expectInvalidArgument([&] { writeExodus(dir.file("d.exo"), mesh, steps); }, "subdomain");

  // Validation happens before the file is created, so a bad call leaves no file behind.
  EXPECT_FALSE(std::filesystem::exists(dir.file("a.exo")));
}

// A result written one step at a time (a load history's, issue 43): a copy taken between two
// steps is a whole file of the steps so far, the finished file reads back as writeExodus's,
// and a step whose names differ from the first step's is refused without harming the file.
TEST(ExodusIO, stepByStepWriterMatchesTheWholeWrite) {
  const ScratchDir dir("stepwise");
  const Mesh mesh = cubeMesh();
  auto steps = someSteps(mesh);
  for (size_t s = 0; s < steps.size(); ++s) steps[s].global = {{"load_step", 1.0 + s}};
  const std::vector<std::string> info = {"tribos --input scene.xml"};
  const std::string path = dir.file("stepwise.exo");
  ExodusWriter writer(path, mesh, info);
  writer.append(steps[0]);
  std::filesystem::copy_file(path, dir.file("copy.exo"));
  const ExodusData copy = readExodus(dir.file("copy.exo"));
  expectSameMesh(copy.mesh, mesh);
  expectSameSteps(copy.steps, {steps[0]});

  auto renamed = steps[1];
  renamed.nodal[0].name = "elsewhere";
  expectInvalidArgument([&] { writer.append(renamed); }, "elsewhere");
  for (size_t s = 1; s < steps.size(); ++s) writer.append(steps[s]);
  writer.close();
  EXPECT_EQ(writer.steps(), static_cast<int>(steps.size()));
  const ExodusData back = readExodus(path);
  expectSameMesh(back.mesh, mesh);
  expectSameSteps(back.steps, steps);
  EXPECT_EQ(back.info, info);
  EXPECT_THROW(writer.append(steps[0]), std::logic_error);
}
