// Decompositions: structured and METIS partitions cover every element once, never span two
// bodies, are balanced; rank ownership is consistent.
#include <gtest/gtest.h>

#include <algorithm>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;
using namespace tribos::mesh;

TEST(Decomposition, subdomainsPartitionTheElementsAndKeepLocalConnectivity) {
  const Mesh mesh = generateTwoBricks({{4, 2, 2}, 3});
  const auto d = buildDecomposition(mesh, structuredPartition(mesh, {{4, 2, 2}, 3}));
  std::vector<int> seen(mesh.numElements(), 0);
  for (const auto& s : d.subdomains) {
    for (size_t i = 0; i < s.elements.size(); ++i) {
      seen[s.elements[i]]++;
      for (int v = 0; v < 4; ++v) EXPECT_EQ(s.nodes[s.tets[i][v]], mesh.tets[s.elements[i]][v]);
      EXPECT_EQ(mesh.blockOf(s.elements[i]), s.body);
    }
  }
  for (int c : seen) EXPECT_EQ(c, 1);
}

TEST(Decomposition, partsSpanningTwoBodiesOrEmptyAreInputErrors) {
  const Mesh mesh = generateTwoBricks({{2, 1, 1}, 1});
  std::vector<int> oneForAll(mesh.numElements(), 0);
  EXPECT_THROW(buildDecomposition(mesh, oneForAll), core::InputError);
  std::vector<int> gap(mesh.numElements(), 0);
  for (LO e = mesh.blocks[1].first; e < mesh.numElements(); ++e) gap[e] = 2;  // part 1 empty
  EXPECT_THROW(buildDecomposition(mesh, gap), core::InputError);
}

TEST(Decomposition, rankOwnershipIsContiguousAndConsistent) {
  for (int S : {4, 7, 500})
    for (int R : {1, 2, 3, 4}) {
      EXPECT_EQ(firstSubdomain(0, S, R), 0);
      EXPECT_EQ(firstSubdomain(R, S, R), S);
      for (int s = 0; s < S; ++s) {
        const int r = ownerRank(s, S, R);
        EXPECT_LE(firstSubdomain(r, S, R), s);
        EXPECT_LT(s, firstSubdomain(r + 1, S, R));
      }
    }
}

TEST(metisPartition, coversEveryElementOnceWithinOneBodyAndBalanced) {
  const Mesh mesh = generateTwoBricks({{2, 1, 1}, 4});
  for (int parts : {4, 7, 16}) {
    SCOPED_TRACE(parts);
    const auto part = metisPartition(mesh, parts);
    ASSERT_EQ(static_cast<LO>(part.size()), mesh.numElements());
    const auto d = buildDecomposition(mesh, part);  // throws if a part spans two bodies or is empty
    EXPECT_EQ(d.numSubdomains(), parts);
    // Balance per body: METIS's default imbalance for PartMeshDual is 3%; contiguity and the
    // element granularity of these small meshes cost a few more per cent.
    for (int b = 0; b < 2; ++b) {
      std::vector<int> sizes;
      for (const auto& s : d.subdomains)
        if (s.body == b) sizes.push_back(static_cast<int>(s.elements.size()));
      const double average = static_cast<double>(mesh.blocks[b].count) / sizes.size();
      EXPECT_LE(*std::max_element(sizes.begin(), sizes.end()), 1.10 * average);
    }
  }
  EXPECT_THROW(metisPartition(mesh, 1), core::InputError);
  EXPECT_THROW(metisPartition(mesh, 100000), core::InputError);
}
