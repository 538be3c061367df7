// Decompositions: structured and METIS partitions cover every element once, never span two
// bodies, are balanced; rank ownership is consistent.
#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <string>
#include <vector>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;
using namespace tribos::mesh;

TEST(Decomposition, subdomainsPartitionTheElementsAndKeepLocalConnectivity) {
  const Mesh mesh = generateTwoBricks({{4, 2, 2}, 3});
  const auto d = buildDecomposition(mesh, structuredPartition(mesh, {{4, 2, 2}, 3}));
  ASSERT_EQ(d.numSubdomains(), 32);
  EXPECT_EQ(d.elementPart, structuredPartition(mesh, {{4, 2, 2}, 3}));
  std::vector<int> seen(mesh.numElements(), 0);
  for (int p = 0; p < d.numSubdomains(); ++p) {
    const Subdomain& s = d.subdomains[p];
    EXPECT_EQ(s.body, p < 16 ? 0 : 1);  // brick 1's subdomains first
    EXPECT_EQ(s.numNodes(), 4 * 4 * 4);  // (H/h + 1)^3
    EXPECT_EQ(s.numDofs(), 3 * 64);
    EXPECT_TRUE(std::is_sorted(s.elements.begin(), s.elements.end()));
    EXPECT_TRUE(std::adjacent_find(s.elements.begin(), s.elements.end()) == s.elements.end());
    EXPECT_TRUE(std::is_sorted(s.nodes.begin(), s.nodes.end()));
    EXPECT_TRUE(std::adjacent_find(s.nodes.begin(), s.nodes.end()) == s.nodes.end());
    // Every local node is used by some local tet.
    std::vector<int> used(s.nodes.size(), 0);
    for (LO v : s.localElements.flatNodes()) used.at(v) = 1;
    EXPECT_EQ(std::accumulate(used.begin(), used.end(), 0), s.numNodes());
    ASSERT_EQ(static_cast<size_t>(s.localElements.size()), s.elements.size());
    for (LO e : s.elements) EXPECT_EQ(d.elementPart[e], p);
    for (size_t i = 0; i < s.elements.size(); ++i) {
      seen[s.elements[i]]++;
      for (int v = 0; v < 4; ++v) EXPECT_EQ(s.nodes[s.localElements.nodes(i)[v]], mesh.elementNodes(s.elements[i])[v]);
      EXPECT_EQ(mesh.blockOf(s.elements[i]), s.body);
    }
  }
  for (int c : seen) EXPECT_EQ(c, 1);
}

namespace {
std::string inputErrorOf(const Mesh& mesh, const std::vector<int>& part) {
  try {
    buildDecomposition(mesh, part);
  } catch (const core::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}
}  // namespace

TEST(Decomposition, badPartMapsAreInputErrors) {
  const Mesh mesh = generateTwoBricks({{2, 1, 1}, 1});
  // A part spanning both bodies: the message names the part and both blocks.
  std::vector<int> span(mesh.numElements(), 0);
  span.back() = 1;
  span[mesh.blocks[1].first] = 1;
  span[0] = 1;  // part 1 = first element of aluminium + elements of steel
  const std::string what = inputErrorOf(mesh, span);
  EXPECT_NE(what.find("subdomain 1"), std::string::npos) << what;
  EXPECT_NE(what.find("aluminium"), std::string::npos) << what;
  EXPECT_NE(what.find("steel"), std::string::npos) << what;
  // An empty part (1 is never used).
  std::vector<int> gap(mesh.numElements(), 0);
  for (LO e = mesh.blocks[1].first; e < mesh.numElements(); ++e) gap[e] = 2;
  EXPECT_NE(inputErrorOf(mesh, gap).find("subdomain 1"), std::string::npos);
  // A negative part id, and a map of the wrong size.
  std::vector<int> negative = gap;
  for (LO e = mesh.blocks[1].first; e < mesh.numElements(); ++e) negative[e] = 1;
  negative[3] = -1;
  inputErrorOf(mesh, negative);
  inputErrorOf(mesh, std::vector<int>(mesh.numElements() - 1, 0));
  inputErrorOf(mesh, {});
}

TEST(Decomposition, rankOwnershipIsContiguousAndConsistent) {
  for (int S : {4, 7, 500})
    for (int R : {1, 2, 3, 4, 6, 9}) {  // 6 and 9 > S = 4: some ranks own nothing
      SCOPED_TRACE(std::to_string(S) + " subdomains on " + std::to_string(R) + " ranks");
      EXPECT_EQ(firstSubdomain(0, S, R), 0);
      EXPECT_EQ(firstSubdomain(R, S, R), S);
      for (int r = 0; r < R; ++r) {
        const int count = firstSubdomain(r + 1, S, R) - firstSubdomain(r, S, R);
        EXPECT_GE(count, S / R);  // balanced: S/R or S/R + 1 each
        EXPECT_LE(count, S / R + 1);
      }
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
  // Fewer parts than bodies, more parts than a body has elements: named errors.
  for (int bad : {1, 0, -3, 100000}) {
    try {
      metisPartition(mesh, bad);
      ADD_FAILURE() << bad;
    } catch (const core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("Mesh/Subdomains"), std::string::npos) << e.what();
    }
  }
  // One part per body: no METIS call, each body is its own part.
  const auto two = metisPartition(mesh, 2);
  for (LO e = 0; e < mesh.numElements(); ++e) EXPECT_EQ(two[e], mesh.blockOf(e));
}

TEST(metisPartition, smallBodiesGetOnePartEach) {
  // Re-block the 2x1x1, H/h = 2 mesh (2 x 80 tets): the first brick less its last two tets,
  // those two tets as one-element bodies, the second brick. Proportional shares of 6 parts
  // are 2.925, 0.0375, 0.0375, 3: the small bodies get one part each, taken from the bodies
  // whose shares exceed their quotas most, and the shares still sum to 6.
  Mesh mesh = generateTwoBricks({{2, 1, 1}, 2});
  ASSERT_EQ(mesh.numElements(), 160);
  mesh.blocks = {{"big", 1, 0, 78}, {"tiny_a", 2, 78, 1}, {"tiny_b", 3, 79, 1}, {"steel", 4, 80, 80}};
  const auto part = metisPartition(mesh, 6);
  const auto d = buildDecomposition(mesh, part);
  ASSERT_EQ(d.numSubdomains(), 6);
  EXPECT_EQ(part[78], 2);
  EXPECT_EQ(part[79], 3);
  for (int p : {0, 1}) EXPECT_EQ(d.subdomains[p].body, 0);
  for (int p : {4, 5}) EXPECT_EQ(d.subdomains[p].body, 3);
  EXPECT_THROW(metisPartition(mesh, 3), core::InputError);  // 4 bodies
}

TEST(metisPartition, aBodyInSeveralPiecesIsAnInputErrorNamingTheBlockAndItsIslands) {
  // Both bricks (which share no node) as one body: no contiguous partition exists, and a
  // subdomain holding both would have 12 rigid motions.
  Mesh mesh = generateTwoBricks({{2, 1, 1}, 2});
  mesh.blocks = {{"both", 1, 0, mesh.numElements()}};
  for (int parts : {1, 4}) {
    try {
      metisPartition(mesh, parts);
      ADD_FAILURE() << "no error for a body in two pieces";
    } catch (const core::InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("element block \"both\" is 2 separate pieces"), std::string::npos) << what;
      EXPECT_NE(what.find("80 elements from element 1, 80 elements from element 81"), std::string::npos) << what;
    }
  }
}
