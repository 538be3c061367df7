// Face neighbours and compact clusters of subdomains (perf/prototypes/SubdomainClusters.hpp): the
// neighbours of a structured decomposition are its grid neighbours in the same brick; clusters
// cover every subdomain once, stay in one body, are face-connected and not too small, and
// depend on nothing but the decomposition.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <vector>

#include "SubdomainClusters.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;
using namespace tribos::mesh;

namespace {
struct Bricks {
  Mesh mesh;
  Decomposition D;
};

Bricks bricks(BrickGrid grid, int h) {
  Bricks b{generateTwoBricks({grid, h}), {}};
  b.D = buildDecomposition(b.mesh, structuredPartition(b.mesh, {grid, h}));
  return b;
}

// The grid cell (i, j, k) of a subdomain of the bricks, from its centroid (cubes of edge 10 / ny).
std::array<int, 3> cellOf(const Bricks& b, int s, double edge) {
  std::array<double, 3> c{0, 0, 0};
  for (LO node : b.D.subdomains[s].nodes)
    for (int k = 0; k < 3; ++k) c[k] += b.mesh.coords[node][k] / b.D.subdomains[s].numNodes();
  return {static_cast<int>(c[0] / edge), static_cast<int>(c[1] / edge), static_cast<int>(c[2] / edge)};
}

// Every cluster's subdomains are face-connected through face neighbours inside it.
bool faceConnected(const std::vector<int>& members, const std::vector<std::vector<int>>& neighbours) {
  std::set<int> inside(members.begin(), members.end()), seen{members[0]};
  std::vector<int> stack{members[0]};
  while (!stack.empty()) {
    const int a = stack.back();
    stack.pop_back();
    for (int b : neighbours[a])
      if (inside.count(b) && seen.insert(b).second) stack.push_back(b);
  }
  return seen.size() == inside.size();
}
}  // namespace

TEST(SubdomainClusters, faceNeighboursAreTheGridNeighboursInTheSameBrick) {
  const Bricks b = bricks({4, 2, 2}, 2);
  const auto neighbours = faceNeighbours(b.mesh, b.D);
  ASSERT_EQ(static_cast<int>(neighbours.size()), 32);
  for (int s = 0; s < 32; ++s) {
    const auto cs = cellOf(b, s, 5.0);
    std::vector<int> expected;
    for (int t = 0; t < 32; ++t) {
      if (t == s || b.D.subdomains[t].body != b.D.subdomains[s].body) continue;
      const auto ct = cellOf(b, t, 5.0);
      const int distance = std::abs(cs[0] - ct[0]) + std::abs(cs[1] - ct[1]) + std::abs(cs[2] - ct[2]);
      // A face holds (H/h + 1)^2 = 9 nodes; an edge neighbour shares 3 nodes on a line and a
      // corner neighbour 1: neither is a face.
      EXPECT_EQ(sharedFaceNodes(b.mesh, b.D, s, t).size(), distance == 1 ? 9u : 0u) << s << " and " << t;
      if (distance == 1) expected.push_back(t);
    }
    EXPECT_EQ(neighbours[s], expected) << "subdomain " << s;
  }
}

TEST(SubdomainClusters, clustersCoverEverySubdomainOnceInOneBodyFaceConnected) {
  for (const auto& [grid, size] : std::vector<std::pair<BrickGrid, int>>{{{4, 2, 2}, 8}, {{6, 3, 3}, 8}, {{10, 5, 5}, 8},
                                                                          {{6, 3, 3}, 27}, {{4, 2, 2}, 1}}) {
    const Bricks b = bricks(grid, 2);
    const auto cluster = compactClusters(b.mesh, b.D, size);
    const auto neighbours = faceNeighbours(b.mesh, b.D);
    ASSERT_EQ(static_cast<int>(cluster.size()), b.D.numSubdomains());
    std::map<int, std::vector<int>> members;
    for (int s = 0; s < b.D.numSubdomains(); ++s) members[cluster[s]].push_back(s);
    // Ids 0, 1, ... in the order of their lowest subdomain.
    int expectedId = 0;
    for (const auto& [id, list] : members) EXPECT_EQ(id, expectedId++);
    for (int s = 0, seen = -1; s < b.D.numSubdomains(); ++s)
      if (cluster[s] > seen) EXPECT_EQ(cluster[s], ++seen);
    const int perBody = grid.count();
    const int expectedClusters = 2 * std::max(1, static_cast<int>(std::lround(static_cast<double>(perBody) / size)));
    EXPECT_LE(static_cast<int>(members.size()), expectedClusters) << grid.count() << " per brick, size " << size;
    for (const auto& [id, list] : members) {
      for (int s : list) EXPECT_EQ(b.D.subdomains[s].body, b.D.subdomains[list[0]].body);
      EXPECT_TRUE(faceConnected(list, neighbours)) << "cluster " << id;
      EXPECT_GE(2 * static_cast<int>(list.size()), std::min(size, perBody)) << "cluster " << id;
    }
  }
}

TEST(SubdomainClusters, clustersOfOneAreTheSubdomainsAndOneClusterPerBodyWhenLarge) {
  const Bricks b = bricks({4, 2, 2}, 2);
  const auto single = compactClusters(b.mesh, b.D, 1);
  for (int s = 0; s < 32; ++s) EXPECT_EQ(single[s], s);
  const auto whole = compactClusters(b.mesh, b.D, 1000);
  for (int s = 0; s < 32; ++s) EXPECT_EQ(whole[s], s < 16 ? 0 : 1);
  EXPECT_THROW(compactClusters(b.mesh, b.D, 0), std::invalid_argument);
}

TEST(SubdomainClusters, clustersOfTheBricksAreCompact) {
  // No bars: every cluster of about 8 spans at most 3 subdomains along each axis (a bar of 4
  // costs 6 times the kappa of a cube of 8, doc/measurements/coarse_problem.md), on a grid that divides
  // evenly (8x4x4) and on one that does not (10x5x5).
  for (const BrickGrid grid : {BrickGrid{8, 4, 4}, BrickGrid{10, 5, 5}}) {
    const Bricks b = bricks(grid, 2);
    const double edge = 10.0 / grid.ny;
    const auto cluster = compactClusters(b.mesh, b.D, 8);
    std::map<int, std::array<int, 6>> box;  // lo, hi per axis
    for (int s = 0; s < b.D.numSubdomains(); ++s) {
      const auto c = cellOf(b, s, edge);
      auto [it, fresh] = box.try_emplace(cluster[s], std::array<int, 6>{c[0], c[1], c[2], c[0], c[1], c[2]});
      for (int k = 0; k < 3; ++k) it->second[k] = std::min(it->second[k], c[k]), it->second[3 + k] = std::max(it->second[3 + k], c[k]);
    }
    EXPECT_EQ(static_cast<int>(box.size()), 2 * static_cast<int>(std::lround(grid.count() / 8.0)));
    for (const auto& [id, bx] : box)
      for (int k = 0; k < 3; ++k) EXPECT_LE(bx[3 + k] - bx[k] + 1, 3) << grid.count() << " per brick, cluster " << id;
  }
}
