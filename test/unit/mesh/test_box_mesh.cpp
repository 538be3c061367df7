// The test helper boxMesh / mergeMeshes (test/common/BoxMesh.hpp), which the contact-search,
// constraint-matrix and patch tests build on: a wrong helper would make those tests pass or
// fail for the wrong reason, so its geometry is checked here against what it promises.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "BoxMesh.hpp"

using namespace tribos;

namespace {
using Face = std::array<LO, 3>;
Face sortedFace(const mesh::Mesh& m, LO e, int side) {
  Face f;
  for (int v = 0; v < 3; ++v) f[v] = m.faceNodes(e, side).node[v];
  std::sort(f.begin(), f.end());
  return f;
}
}  // namespace

TEST(BoxMesh, conformingPositiveAndFaceSets) {
  const std::array<double, 3> origin{0.5, -1.0, 2.0}, size{2.0, 1.5, 0.75};
  const std::array<int, 3> n{3, 4, 2};
  const auto m = test::boxMesh(origin, size, n, "body");
  m.validate("test");  // ids in range, sets sorted, every tet positive
  EXPECT_EQ(m.numNodes(), 4 * 5 * 3);
  EXPECT_EQ(m.numElements(), 6 * 3 * 4 * 2);
  ASSERT_EQ(m.numBlocks(), 1);
  EXPECT_EQ(m.blocks[0].name, "body");

  // The tets fill the box: positive volumes that add up to its volume.
  double volume = 0.0;
  for (LO e = 0; e < m.numElements(); ++e) {
    EXPECT_GT(m.elementVolume(e), 0.0);
    volume += m.elementVolume(e);
  }
  EXPECT_NEAR(volume, size[0] * size[1] * size[2], 1e-14);

  // Conforming: every face is shared by two tets or lies on the boundary; the boundary faces
  // are exactly those of the six side sets, each in one set (a non-conforming split would
  // leave interior faces used once).
  std::map<Face, int> uses;
  for (LO e = 0; e < m.numElements(); ++e)
    for (int side = 0; side < 4; ++side) uses[sortedFace(m, e, side)]++;
  std::set<Face> boundary;
  for (const auto& [f, count] : uses) {
    EXPECT_LE(count, 2);
    if (count == 1) boundary.insert(f);
  }
  EXPECT_EQ(boundary.size(), 2u * 2u * (3 * 4 + 4 * 2 + 3 * 2));
  std::set<Face> inSets;
  ASSERT_EQ(m.sideSets.size(), 6u);
  ASSERT_EQ(m.nodeSets.size(), 6u);
  const char* names[6] = {"body_x0", "body_x1", "body_y0", "body_y1", "body_z0", "body_z1"};
  for (int s = 0; s < 6; ++s) {
    const int axis = s / 2;
    const bool upper = s % 2 == 1;
    const double plane = origin[axis] + (upper ? size[axis] : 0.0);
    const auto& ss = m.sideSet(names[s]);
    const auto& ns = m.nodeSet(names[s]);
    EXPECT_EQ(ss.id, s + 1);
    EXPECT_EQ(ns.id, s + 1);
    // The side set covers the face's area with outward normals.
    double area = 0.0;
    for (size_t f = 0; f < ss.elements.size(); ++f) {
      const auto face = sortedFace(m, ss.elements[f], ss.sides[f]);
      EXPECT_TRUE(boundary.count(face)) << names[s];
      EXPECT_TRUE(inSets.insert(face).second) << names[s] << ": face in two sets";
      for (LO v : face) EXPECT_EQ(m.coords[v][axis], plane) << names[s];
      const auto normal = m.faceNormal(ss.elements[f], ss.sides[f]);
      const double length = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
      EXPECT_NEAR(normal[axis], (upper ? 1.0 : -1.0) * length, 1e-14) << names[s];
      area += 0.5 * length;
    }
    EXPECT_NEAR(area, size[(axis + 1) % 3] * size[(axis + 2) % 3], 1e-14) << names[s];
    // The node set is every node on the plane.
    std::vector<LO> expected;
    for (LO v = 0; v < m.numNodes(); ++v)
      if (m.coords[v][axis] == plane) expected.push_back(v);
    EXPECT_EQ(ns.nodes, expected) << names[s];
  }
  EXPECT_EQ(inSets, boundary);

  // Merging: b's nodes, elements and ids follow a's; b's sets still name b's geometry.
  const auto b = test::boxMesh({0.0, 0.0, 5.0}, {1.0, 1.0, 1.0}, {2, 1, 1}, "other");
  const auto merged = test::mergeMeshes(m, b);
  merged.validate("test");
  EXPECT_EQ(merged.numNodes(), m.numNodes() + b.numNodes());
  EXPECT_EQ(merged.numElements(), m.numElements() + b.numElements());
  ASSERT_EQ(merged.numBlocks(), 2);
  EXPECT_EQ(merged.blocks[1].first, m.numElements());
  EXPECT_NE(merged.blocks[0].id, merged.blocks[1].id);
  std::set<int> nodeSetIds, sideSetIds;
  for (const auto& s : merged.nodeSets) nodeSetIds.insert(s.id);
  for (const auto& s : merged.sideSets) sideSetIds.insert(s.id);
  EXPECT_EQ(nodeSetIds.size(), 12u);
  EXPECT_EQ(sideSetIds.size(), 12u);
  for (LO e = 0; e < b.numElements(); ++e)
    for (int v = 0; v < 4; ++v)
      EXPECT_EQ(merged.coords[merged.elementNodes(m.numElements() + e)[v]], b.coords[b.elementNodes(e)[v]]);
  for (LO v : merged.nodeSet("other_z1").nodes) EXPECT_EQ(merged.coords[v][2], 6.0);
  EXPECT_EQ(merged.nodeSet("other_z1").nodes.size(), 6u);
  EXPECT_EQ(merged.sideSet("other_z1").elements.size(), 4u);
  for (LO e : merged.sideSet("other_z1").elements) EXPECT_EQ(merged.blockOf(e), 1);
}
