// The paper's two bricks: counts by formula for every Table 1 cell, conformity, sets,
// decomposition independence of the global mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;
using namespace tribos::mesh;

namespace {
struct Cell {
  int subdomains, hOverH;
  long long n;  // the paper's n (Table 1)
};
// This test's own copy of Table 1's n column (../shared/paper/table1.csv).
const Cell kTable1[] = {{4, 2, 324},       {4, 3, 768},       {4, 4, 1500},      {4, 5, 2592},    {32, 2, 2592},
                        {32, 3, 6144},     {32, 4, 12000},    {32, 5, 20736},    {108, 2, 8748},  {108, 3, 20736},
                        {108, 4, 40500},   {108, 5, 69984},   {256, 2, 20736},   {256, 3, 49152}, {256, 4, 96000},
                        {256, 5, 165888},  {500, 2, 40500},   {500, 3, 96000},   {500, 4, 187500}, {500, 5, 324000}};

TwoBricksSpec specFor(int subdomains, int hOverH) {
  const int s = subdomains / 2;
  int ny = 1;
  while (2 * ny * ny * ny != s) ++ny;
  return {{2 * ny, ny, ny}, hOverH};
}

using Face = std::array<LO, 3>;
Face faceOf(const Mesh& m, LO e, int side) {
  Face f;
  for (int v = 0; v < 3; ++v) f[v] = m.faceNodes(e, side).node[v];
  std::sort(f.begin(), f.end());
  return f;
}
}  // namespace

TEST(TwoBricks, countsMatchFormulaForEveryTable1Cell) {
  for (const Cell& cell : kTable1) {
    SCOPED_TRACE(std::to_string(cell.subdomains) + " / " + std::to_string(cell.hOverH));
    const auto spec = specFor(cell.subdomains, cell.hOverH);
    const Mesh mesh = generateTwoBricks(spec);
    const int m = cell.hOverH, ex = spec.subdomainsPerBrick.nx * m, ey = spec.subdomainsPerBrick.ny * m,
              ez = spec.subdomainsPerBrick.nz * m;
    EXPECT_EQ(mesh.numNodes(), 2 * (ex + 1) * (ey + 1) * (ez + 1));
    EXPECT_EQ(mesh.numElements(), 2 * 5 * ex * ey * ez);
    ASSERT_EQ(mesh.numBlocks(), 2);
    for (int b = 0; b < 2; ++b) {
      EXPECT_EQ(mesh.blocks[b].first, b * 5 * ex * ey * ez);
      EXPECT_EQ(mesh.blocks[b].count, 5 * ex * ey * ez);
    }
    // (name, id, cube faces on it, grid nodes on it): x planes hold ey*ez cube faces, z planes ex*ey;
    // each cube face is cut into 2 triangles.
    struct SetCount {
      const char* name;
      int id, faces, nodes;
    };
    const SetCount sets[] = {{"dirichlet_aluminium", 1, ey * ez, (ey + 1) * (ez + 1)},
                             {"dirichlet_steel", 2, ey * ez, (ey + 1) * (ez + 1)},
                             {"contact_aluminium", 3, ex * ey, (ex + 1) * (ey + 1)},
                             {"contact_steel", 4, ex * ey, (ex + 1) * (ey + 1)},
                             {"load_end", 5, ey * ez, (ey + 1) * (ez + 1)},
                             {"load_top", 6, ex * ey, (ex + 1) * (ey + 1)}};
    for (const SetCount& set : sets) {
      SCOPED_TRACE(set.name);
      EXPECT_EQ(mesh.nodeSet(set.name).id, set.id);
      EXPECT_EQ(mesh.sideSet(set.name).id, set.id);
      EXPECT_EQ(mesh.nodeSet(set.name).nodes.size(), static_cast<size_t>(set.nodes));
      EXPECT_EQ(mesh.sideSet(set.name).elements.size(), static_cast<size_t>(2 * set.faces));
      EXPECT_EQ(mesh.sideSet(set.name).sides.size(), static_cast<size_t>(2 * set.faces));
    }
    const auto d = buildDecomposition(mesh, structuredPartition(mesh, spec));
    EXPECT_EQ(d.numSubdomains(), cell.subdomains);
    // n = 2s * 3 (H/h + 1)^3: every subdomain is an (H/h)^3 cube grid with its own nodes.
    EXPECT_EQ(d.numPrimalDofs(), 3LL * cell.subdomains * (m + 1) * (m + 1) * (m + 1));
    EXPECT_EQ(d.numPrimalDofs(), cell.n);
    for (const auto& s : d.subdomains) {
      EXPECT_EQ(s.numNodes(), (m + 1) * (m + 1) * (m + 1));
      EXPECT_EQ(s.elements.size(), static_cast<size_t>(5 * m * m * m));
    }
  }
}

TEST(TwoBricks, meshIsConformingAndPositivelyOriented) {
  for (const TwoBricksSpec& spec : {TwoBricksSpec{{2, 1, 1}, 1}, TwoBricksSpec{{2, 1, 1}, 2},
                                    TwoBricksSpec{{2, 1, 1}, 3}, TwoBricksSpec{{4, 2, 2}, 3}}) {
    const int ex = spec.subdomainsPerBrick.nx * spec.hOverH, ey = spec.subdomainsPerBrick.ny * spec.hOverH,
              ez = spec.subdomainsPerBrick.nz * spec.hOverH;
    SCOPED_TRACE(std::to_string(ex) + "x" + std::to_string(ey) + "x" + std::to_string(ez));
    const Mesh mesh = generateTwoBricks(spec);
    // The bricks have separate nodes (brick 1's first): no tet of one uses a node of the other.
    const LO nodesPerBrick = (ex + 1) * (ey + 1) * (ez + 1);
    for (LO e = 0; e < mesh.numElements(); ++e)
      for (LO n : mesh.elementNodes(e)) EXPECT_EQ(n / nodesPerBrick, mesh.blockOf(e));
    std::map<Face, int> count;
    for (LO e = 0; e < mesh.numElements(); ++e) {
      EXPECT_GT(mesh.elementVolume(e), 0.0);
      for (int side = 0; side < 4; ++side) count[faceOf(mesh, e, side)]++;
    }
    // Interior faces are shared by exactly two tets; boundary faces lie on a brick's boundary planes.
    for (const auto& [face, c] : count) {
      ASSERT_LE(c, 2);
      if (c == 2) continue;
      bool onPlane = false;
      for (int axis = 0; axis < 3; ++axis) {
        const double v = mesh.coords[face[0]][axis];
        bool same = true;
        for (LO n : face) same = same && mesh.coords[n][axis] == v;
        const double extent = axis == 0 ? 20.0 : (axis == 1 ? 10.0 : -1.0);
        if (same && (v == 0.0 || v == extent || (axis == 2 && (v == 10.0 || v == 20.0)))) onPlane = true;
      }
      EXPECT_TRUE(onPlane);
    }
    // Boundary triangles: 2 per cube face on the 6 faces of each of the 2 bricks, no more.
    size_t boundary = 0;
    for (const auto& [face, c] : count) boundary += c == 1;
    EXPECT_EQ(boundary, static_cast<size_t>(2 * 2 * 2 * (ex * ey + ey * ez + ex * ez)));
    for (int b = 0; b < 2; ++b) {
      double volume = 0.0;
      for (LO e = mesh.blocks[b].first; e < mesh.blocks[b].first + mesh.blocks[b].count; ++e)
        volume += mesh.elementVolume(e);
      EXPECT_NEAR(volume, 2000.0, 1e-9);
    }
  }
}

TEST(TwoBricks, sideSetsLieOnTheirPlanesWithOutwardNormals) {
  const Mesh mesh = generateTwoBricks({{4, 2, 2}, 2});
  struct Expect {
    const char* name;
    int axis;
    double value, normalSign;
  };
  for (const Expect& x : {Expect{"dirichlet_aluminium", 0, 0.0, -1}, Expect{"dirichlet_steel", 0, 0.0, -1},
                          Expect{"contact_aluminium", 2, 10.0, 1}, Expect{"contact_steel", 2, 10.0, -1},
                          Expect{"load_end", 0, 20.0, 1}, Expect{"load_top", 2, 20.0, 1}}) {
    SCOPED_TRACE(x.name);
    const auto& set = mesh.sideSet(x.name);
    ASSERT_FALSE(set.elements.empty());
    for (size_t f = 0; f < set.elements.size(); ++f) {
      const auto face = mesh.faceNodes(set.elements[f], set.sides[f]);
      const auto &a = mesh.coords[face.node[0]], &b = mesh.coords[face.node[1]], &c = mesh.coords[face.node[2]];
      for (const auto* p : {&a, &b, &c}) EXPECT_DOUBLE_EQ((*p)[x.axis], x.value);
      const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
      EXPECT_GT(n[x.axis] * x.normalSign, 0.0);
    }
    // Sides of the brick the set names, and the node set of the same name holds exactly
    // the vertices of its side set.
    const int brick = std::string(x.name).find("aluminium") != std::string::npos ? 0 : 1;
    std::vector<LO> nodes;
    for (size_t f = 0; f < set.elements.size(); ++f) {
      EXPECT_EQ(mesh.blockOf(set.elements[f]), brick);
      for (LO n : mesh.faceNodes(set.elements[f], set.sides[f])) nodes.push_back(n);
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    EXPECT_EQ(nodes, mesh.nodeSet(x.name).nodes);
  }
}

TEST(TwoBricks, globalMeshDoesNotDependOnTheDecomposition) {
  // Same h, different subdomain grids: h = 5, h = 20/6 (odd H/h on one side) and h = 20/12.
  const std::pair<TwoBricksSpec, TwoBricksSpec> pairs[] = {{{{2, 1, 1}, 4}, {{4, 2, 2}, 2}},
                                                           {{{2, 1, 1}, 6}, {{6, 3, 3}, 2}},
                                                           {{{4, 2, 2}, 3}, {{6, 3, 3}, 2}}};
  for (const auto& [specA, specB] : pairs) {
    const Mesh a = generateTwoBricks(specA);
    const Mesh b = generateTwoBricks(specB);
    EXPECT_EQ(a.coords, b.coords);
    EXPECT_TRUE(a.elements == b.elements);
    ASSERT_EQ(a.sideSets.size(), b.sideSets.size());
    for (size_t i = 0; i < a.sideSets.size(); ++i) {
      EXPECT_EQ(a.sideSets[i].elements, b.sideSets[i].elements);
      EXPECT_EQ(a.sideSets[i].sides, b.sideSets[i].sides);
      EXPECT_EQ(a.nodeSets[i].nodes, b.nodeSets[i].nodes);
    }
  }
}

TEST(TwoBricks, badGridsAreInputErrorsNamingTheParameter) {
  const BrickGrid g = BrickGrid::parse("10x5x5", "Mesh/Subdomains Per Brick");
  EXPECT_EQ(g.nx, 10);
  EXPECT_EQ(g.ny, 5);
  EXPECT_EQ(g.nz, 5);
  EXPECT_EQ(g.count(), 250);
  for (const char* bad : {"2x1", "2x1x1x1", "axbxc", "0x1x1", "2x1x-1", "", " 2x1x1", "+2x1x1", "2x1x1 ", "2xx1",
                          "2x1x", "2X1X1", "2.0x1x1", "99999999999x1x1"}) {
    try {
      BrickGrid::parse(bad, "Mesh/Subdomains Per Brick");
      ADD_FAILURE() << "accepted \"" << bad << "\"";
    } catch (const core::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("Mesh/Subdomains Per Brick"), std::string::npos) << what;
      EXPECT_NE(what.find("\"" + std::string(bad) + "\""), std::string::npos) << what;
    }
  }
  // Non-cubic subdomains (20/nx != 10/ny or ny != nz) are named by the parameter.
  for (const BrickGrid& grid : {BrickGrid{3, 1, 1}, BrickGrid{2, 1, 2}, BrickGrid{4, 2, 1}, BrickGrid{0, 0, 0}}) {
    try {
      generateTwoBricks({grid, 2});
      ADD_FAILURE() << grid.nx << "x" << grid.ny << "x" << grid.nz;
    } catch (const core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Mesh/Subdomains Per Brick"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(generateTwoBricks({{2, 1, 1}, 0}), core::InputError);
  EXPECT_THROW(generateTwoBricks({{2000, 1000, 1000}, 5}), core::InputError);  // too many tets for int ids
}
