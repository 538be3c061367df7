// Node-to-surface contact search (geometry/ContactSearch.hpp): the closest point on a triangle
// against a brute-force sample, and the pairing of two stacked boxes (test/common/BoxMesh):
// matching meshes pair node to node, non-matching ones project every slave node onto the
// master plane with convex weights, nodes beyond the search distance are unpaired, overlap
// is a negative gap, and the number of closest-point evaluations per slave node stays
// bounded as the master surface grows (no quadratic search).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "BoxMesh.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/geometry/ContactSearch.hpp"
#include "tribos/geometry/MasterSurface.hpp"
#include "tribos/geometry/SurfaceNormals.hpp"

using namespace tribos;

namespace {
using Vec3 = std::array<double, 3>;

Vec3 add(const Vec3& a, const Vec3& b, double s = 1.0) { return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]}; }
Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 unit(const Vec3& a) {
  const double l = std::sqrt(dot(a, a));
  return {a[0] / l, a[1] / l, a[2] / l};
}
double distance(const Vec3& a, const Vec3& b) { return std::sqrt(dot(sub(a, b), sub(a, b))); }
Vec3 point(const std::array<double, 3>& w, const Vec3& a, const Vec3& b, const Vec3& c) {
  return {w[0] * a[0] + w[1] * b[0] + w[2] * c[0], w[0] * a[1] + w[1] * b[1] + w[2] * c[1],
          w[0] * a[2] + w[1] * b[2] + w[2] * c[2]};
}

/// Smallest distance from x to a barycentric grid of n(n+1)/2 points of the triangle
/// (edges and vertices included): an upper bound on the true distance, within h/2 of it.
double bruteForceDistance(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, int n) {
  double best = INFINITY;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      best = std::min(best, distance(x, point({1.0 - u - v, u, v}, a, b, c)));
    }
  return best;
}

// A tilted, scalene triangle (no axis or symmetry makes a wrong region look right).
const Vec3 kA{0.1, 0.2, 0.3}, kB{2.0, 0.4, -0.1}, kC{0.5, 1.7, 0.6};

template <size_t N>
void expectConvex(const std::array<double, N>& w) {
  double sum = 0.0;
  for (double wi : w) {
    EXPECT_GE(wi, 0.0);
    sum += wi;
  }
  EXPECT_NEAR(sum, 1.0, 1e-15);
}

/// Two boxes stacked along z: "lower" (the slave body, its top lower_z1) below "upper" (the
/// master, its bottom upper_z0), footprints starting at (0, 0).
mesh::Mesh stacked(std::array<double, 2> lowerSize, std::array<int, 2> lowerCells, std::array<double, 2> upperSize,
                   std::array<int, 2> upperCells, double upperBottom = 1.0) {
  const auto lower = test::boxMesh({0.0, 0.0, 0.0}, {lowerSize[0], lowerSize[1], 1.0}, {lowerCells[0], lowerCells[1], 1}, "lower");
  const auto upper = test::boxMesh({0.0, 0.0, upperBottom}, {upperSize[0], upperSize[1], 1.0},
                                   {upperCells[0], upperCells[1], 1}, "upper");
  auto m = test::mergeMeshes(lower, upper);
  m.validate("test");
  return m;
}

geometry::ContactSearchResult search(const mesh::Mesh& m, double searchDistance) {
  return geometry::searchContactPairs(m, "lower_z1", "upper_z0", searchDistance);
}

/// The projection of a pair: the weighted master vertices.
Vec3 projection(const mesh::Mesh& m, const geometry::ContactPair& p) {
  EXPECT_EQ(p.masterNodes[3], -1);  // triangles here
  return point({p.weights[0], p.weights[1], p.weights[2]}, m.coords[p.masterNodes[0]], m.coords[p.masterNodes[1]],
               m.coords[p.masterNodes[2]]);
}

/// The master face of a pair really is face `masterFace` of the master side set, its
/// vertices in side-set order, and the pair's slave node is a node of the slave side set.
void expectConsistentPair(const mesh::Mesh& m, const geometry::ContactPair& p) {
  const auto& master = m.sideSet("upper_z0");
  ASSERT_GE(p.masterFace, 0);
  ASSERT_LT(static_cast<size_t>(p.masterFace), master.elements.size());
  for (int v = 0; v < 3; ++v)
    EXPECT_EQ(p.masterNodes[v], m.faceNodes(master.elements[p.masterFace], master.sides[p.masterFace]).node[v]);
  const auto slaves = geometry::sideSetNodes(m, m.sideSet("lower_z1"));
  EXPECT_TRUE(std::binary_search(slaves.begin(), slaves.end(), p.slaveNode));
  EXPECT_EQ(p.nearestMasterNode(), p.masterNodes[std::max_element(p.weights.begin(), p.weights.end()) - p.weights.begin()]);
}
}  // namespace

TEST(ContactSearch, closestPointInEveryVoronoiRegion) {
  const Vec3 normal = unit(cross(sub(kB, kA), sub(kC, kA)));
  // Outward in-plane directions: away from the opposite vertex, perpendicular to the edge.
  auto outward = [&](const Vec3& p, const Vec3& q) { return unit(cross(sub(q, p), normal)); };
  const Vec3 outAB = outward(kA, kB), outBC = outward(kB, kC), outCA = outward(kC, kA);
  // The sign of cross(edge, normal) depends on the orientation: make it point away from the third vertex.
  auto away = [&](Vec3 d, const Vec3& onEdge, const Vec3& opposite) {
    if (dot(d, sub(opposite, onEdge)) > 0.0) d = {-d[0], -d[1], -d[2]};
    return d;
  };
  const Vec3 nAB = away(outAB, kA, kC), nBC = away(outBC, kB, kA), nCA = away(outCA, kC, kB);
  const Vec3 vertices[3] = {kA, kB, kC};
  for (double height : {0.0, 0.7, -0.4}) {  // in the plane, above it, below it
    SCOPED_TRACE("height " + std::to_string(height));
    const Vec3 lift{height * normal[0], height * normal[1], height * normal[2]};
    // Vertex regions: beyond the vertex, outside both adjacent edges' slabs.
    const Vec3 beyond[3] = {add(nAB, nCA), add(nAB, nBC), add(nBC, nCA)};
    for (int v = 0; v < 3; ++v) {
      const Vec3 x = add(add(vertices[v], beyond[v], 0.3), lift);
      const auto w = geometry::closestPointOnTriangle(x, kA, kB, kC);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(w[i], i == v ? 1.0 : 0.0) << "vertex " << v;
      EXPECT_LE(distance(x, point(w, kA, kB, kC)), bruteForceDistance(x, kA, kB, kC, 200) + 1e-14);
    }
    // Edge regions: out from a point a quarter along the edge; the opposite weight is an
    // exact 0 and the other two give that point.
    const int edge[3][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}};  // (p, q, opposite)
    const Vec3 out[3] = {nAB, nBC, nCA};
    for (int e = 0; e < 3; ++e) {
      const Vec3& p = vertices[edge[e][0]];
      const Vec3& q = vertices[edge[e][1]];
      const Vec3 onEdge = add(p, sub(q, p), 0.25);
      const Vec3 x = add(add(onEdge, out[e], 0.5), lift);
      const auto w = geometry::closestPointOnTriangle(x, kA, kB, kC);
      EXPECT_EQ(w[edge[e][2]], 0.0) << "edge " << e;
      EXPECT_NEAR(w[edge[e][0]], 0.75, 1e-14) << "edge " << e;
      EXPECT_NEAR(w[edge[e][1]], 0.25, 1e-14) << "edge " << e;
      expectConvex(w);
      EXPECT_LE(distance(point(w, kA, kB, kC), onEdge), 1e-14);
      EXPECT_LE(distance(x, point(w, kA, kB, kC)), bruteForceDistance(x, kA, kB, kC, 200) + 1e-14);
    }
    // Interior: the foot of the perpendicular, at the chosen weights.
    const std::array<double, 3> inside{0.2, 0.5, 0.3};
    const Vec3 x = add(point(inside, kA, kB, kC), lift);
    const auto w = geometry::closestPointOnTriangle(x, kA, kB, kC);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(w[i], inside[i], 1e-14);
    expectConvex(w);
    EXPECT_NEAR(distance(x, point(w, kA, kB, kC)), std::abs(height), 1e-14);
  }
}

TEST(ContactSearch, closestPointIsTheClosestForRandomPoints) {
  // Points all around the triangle: the returned point is no farther than any point of a
  // fine sample of the triangle, and no nearer than the sample allows (h/2 with h the grid
  // spacing along the longest edge, ~0.011 here).
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> coordinate(-1.5, 3.0);
  const int n = 200;
  const double h = 2.0 / n;  // longest edge < 2
  for (int k = 0; k < 300; ++k) {
    const Vec3 x{coordinate(rng), coordinate(rng) - 0.5, coordinate(rng) - 0.8};
    const auto w = geometry::closestPointOnTriangle(x, kA, kB, kC);
    expectConvex(w);
    const double found = distance(x, point(w, kA, kB, kC));
    const double sampled = bruteForceDistance(x, kA, kB, kC, n);
    EXPECT_LE(found, sampled + 1e-13) << "point " << k;
    EXPECT_GE(found, sampled - h) << "point " << k;
  }
}

TEST(ContactSearch, matchingMeshesPairNodeToNode) {
  const auto m = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {4, 4});
  const auto r = search(m, 1e-6);
  const auto slaves = geometry::sideSetNodes(m, m.sideSet("lower_z1"));
  ASSERT_EQ(slaves.size(), 25u);
  ASSERT_EQ(r.pairs.size(), 25u);
  EXPECT_TRUE(r.unpaired.empty());
  EXPECT_EQ(r.overlapping, 0);
  EXPECT_EQ(r.largestOverlap, 0.0);
  for (size_t i = 0; i < r.pairs.size(); ++i) {
    const auto& p = r.pairs[i];
    EXPECT_EQ(p.slaveNode, slaves[i]);  // ascending slave node
    expectConsistentPair(m, p);
    // A unit weight vector on the coincident master node.
    int ones = 0;
    for (double w : p.weights) {
      EXPECT_TRUE(w == 0.0 || w == 1.0) << w;
      ones += w == 1.0;
    }
    EXPECT_EQ(ones, 1);
    EXPECT_EQ(m.coords[p.nearestMasterNode()], m.coords[p.slaveNode]);
    EXPECT_GE(p.nearestMasterNode(), 5 * 5 * 2);  // an upper-body node (the lower box has 5 x 5 x 2 nodes)
    EXPECT_EQ(p.gap, 0.0);
    EXPECT_EQ(p.distance, 0.0);
    // From the lower (slave) body into the upper (master) one.
    EXPECT_EQ(p.normal[0], 0.0);
    EXPECT_EQ(p.normal[1], 0.0);
    EXPECT_EQ(p.normal[2], 1.0);
  }
}

TEST(ContactSearch, nonMatchingProjectionsLieOnTheMasterPlane) {
  // 4x4 slave cells against 5x5 master cells on the same 2x2 footprint.
  const auto m = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {5, 5});
  const auto r = search(m, 1e-6);
  ASSERT_EQ(r.pairs.size(), 25u);
  EXPECT_TRUE(r.unpaired.empty());
  EXPECT_EQ(r.overlapping, 0);
  int unitWeights = 0;
  for (const auto& p : r.pairs) {
    SCOPED_TRACE("slave node " + std::to_string(p.slaveNode));
    expectConsistentPair(m, p);
    expectConvex(p.weights);
    const auto& xs = m.coords[p.slaveNode];
    const auto xp = projection(m, p);
    // The interpolated master point is the slave node itself: same x, y on the plane z = 1.
    EXPECT_NEAR(xp[0], xs[0], 1e-15);
    EXPECT_NEAR(xp[1], xs[1], 1e-15);
    EXPECT_NEAR(xp[2], 1.0, 1e-15);
    EXPECT_EQ(p.gap, 0.0);
    EXPECT_LE(p.distance, 1e-15);
    EXPECT_NEAR(p.normal[0], 0.0, 1e-15);
    EXPECT_NEAR(p.normal[1], 0.0, 1e-15);
    EXPECT_NEAR(p.normal[2], 1.0, 1e-15);
    unitWeights += std::count(p.weights.begin(), p.weights.end(), 1.0);
  }
  // Slave x, y in {0, .5, 1, 1.5, 2}, master in {0, .4, .8, 1.2, 1.6, 2}: only the four
  // corners coincide with master vertices.
  EXPECT_EQ(unitWeights, 4);
}

TEST(ContactSearch, projectionsOnMasterEdgesAndVertices) {
  // 4x4 slave cells (h = 1/2) against 2x2 master cells (h = 1), all coordinates binary
  // fractions, so the arithmetic is exact: the 9 slave nodes with x, y in {0, 1, 2} sit on
  // master vertices, the other 16 on master edges — the grid lines, and the cell centres on
  // the cells' diagonals — at their midpoints. None is interior to a master face.
  const auto m = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {2, 2});
  const auto r = search(m, 1e-6);
  ASSERT_EQ(r.pairs.size(), 25u);
  int onVertex = 0, onEdge = 0;
  for (const auto& p : r.pairs) {
    SCOPED_TRACE("slave node " + std::to_string(p.slaveNode));
    expectConsistentPair(m, p);
    const auto& xs = m.coords[p.slaveNode];
    const bool gridX = xs[0] == std::floor(xs[0]), gridY = xs[1] == std::floor(xs[1]);
    const int nonzero = static_cast<int>(std::count_if(p.weights.begin(), p.weights.end(), [](double w) { return w != 0.0; }));
    if (gridX && gridY) {
      ++onVertex;
      EXPECT_EQ(nonzero, 1);
      EXPECT_EQ(m.coords[p.nearestMasterNode()][0], xs[0]);
      EXPECT_EQ(m.coords[p.nearestMasterNode()][1], xs[1]);
    } else {
      ++onEdge;
      EXPECT_EQ(nonzero, 2);
      for (double w : p.weights) EXPECT_TRUE(w == 0.0 || w == 0.5) << w;
    }
    const auto xp = projection(m, p);
    EXPECT_EQ(xp[0], xs[0]);
    EXPECT_EQ(xp[1], xs[1]);
    EXPECT_EQ(xp[2], 1.0);
    EXPECT_EQ(p.gap, 0.0);
  }
  EXPECT_EQ(onVertex, 9);
  EXPECT_EQ(onEdge, 16);
}

TEST(ContactSearch, slaveNodesBeyondTheSearchDistanceAreUnpaired) {
  // The slave top is 3 long, the master bottom 2: slave nodes at x = 2.5 are 0.5 from the
  // master's edge x = 2, those at x = 3 are 1 from it.
  const auto m = stacked({3.0, 2.0}, {6, 4}, {2.0, 2.0}, {2, 2});
  const auto slaves = geometry::sideSetNodes(m, m.sideSet("lower_z1"));
  ASSERT_EQ(slaves.size(), 35u);
  auto beyond = [&](double x0) {
    std::vector<LO> nodes;
    for (LO n : slaves)
      if (m.coords[n][0] > x0) nodes.push_back(n);
    return nodes;
  };
  {
    const auto r = search(m, 0.25);
    EXPECT_EQ(r.unpaired, beyond(2.0));  // x = 2.5 and 3: 10 nodes, ascending
    EXPECT_EQ(r.unpaired.size(), 10u);
    EXPECT_EQ(r.pairs.size(), 25u);
    for (const auto& p : r.pairs) EXPECT_LE(m.coords[p.slaveNode][0], 2.0);
  }
  {
    // Within 0.75 the nodes at x = 2.5 are 0.5 from the master's edge x = 2, but beside the
    // master, not over it (MasterSurface: kBesideTheSurface): its edge is no point of contact
    // for them. They paired with it, at a zero gap along the normal (0, 0, 1), until a bolt
    // head's nodes over the clearance of its hole took most of its pretension that way.
    const auto r = search(m, 0.75);
    EXPECT_EQ(r.unpaired, beyond(2.0));
    EXPECT_EQ(r.pairs.size(), 25u);
  }
  // Search distance 0 still pairs coincident surfaces; a negative one is an input error.
  EXPECT_EQ(search(m, 0.0).pairs.size(), 25u);
  EXPECT_THROW(search(m, -1.0), core::InputError);
}

TEST(ContactSearch, overlapGivesNegativeGapsAndIsCounted) {
  // The master body lowered 1/8 into the slave body: every slave node is 1/8 inside it.
  {
    const auto m = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {5, 5}, 0.875);
    const auto r = search(m, 0.2);
    ASSERT_EQ(r.pairs.size(), 25u);
    EXPECT_EQ(r.overlapping, 25);
    EXPECT_NEAR(r.largestOverlap, 0.125, 1e-15);  // (5x5 weights sum to 1 within an ulp)
    for (const auto& p : r.pairs) {
      EXPECT_NEAR(p.gap, -0.125, 1e-15);
      EXPECT_NEAR(p.distance, 0.125, 1e-15);
      EXPECT_NEAR(p.normal[2], 1.0, 1e-15);
    }
    // A search distance below the overlap: every node is inside the master body, paired whatever
    // the distance (issue 41; it was "nothing within reach", the bodies left inside each other).
    const auto inside = search(m, 0.1);
    EXPECT_EQ(inside.pairs.size(), 25u);
    EXPECT_TRUE(inside.unpaired.empty());
    for (const auto& p : inside.pairs) EXPECT_NEAR(p.gap, -0.125, 1e-15);
  }
  // Lifted by 1/4: an open gap, positive, not counted as overlap; below the search distance the
  // nodes outside the master body are out of reach.
  {
    const auto m = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {5, 5}, 1.25);
    const auto r = search(m, 0.3);
    ASSERT_EQ(r.pairs.size(), 25u);
    EXPECT_EQ(r.overlapping, 0);
    EXPECT_EQ(r.largestOverlap, 0.0);
    for (const auto& p : r.pairs) EXPECT_NEAR(p.gap, 0.25, 1e-15);
    EXPECT_EQ(search(m, 0.2).unpaired.size(), 25u);
  }
  // Partly overlapping: the master bottom tilted so that it dips below z = 1 over half the
  // footprint. Move the master's bottom nodes to z = 1 + (x - 1) / 8 (x in [0, 2]).
  {
    auto m = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {4, 4});
    for (LO n : m.nodeSet("upper_z0").nodes) m.coords[n][2] = 1.0 + (m.coords[n][0] - 1.0) / 8.0;
    const auto r = search(m, 0.5);
    ASSERT_EQ(r.pairs.size(), 25u);
    int negative = 0;
    double largest = 0.0;
    for (const auto& p : r.pairs) {
      const double x = m.coords[p.slaveNode][0];
      if (x < 1.0) {
        EXPECT_LT(p.gap, 0.0) << "x = " << x;
        ++negative;
        largest = std::max(largest, -p.gap);
      } else {
        EXPECT_GE(p.gap, 0.0) << "x = " << x;
      }
      // Along the tilted master normal: gap = signed distance to the plane z = 1 + (x-1)/8.
      const double expected = ((1.0 + (x - 1.0) / 8.0) - 1.0) / std::sqrt(1.0 + 1.0 / 64.0);
      EXPECT_NEAR(p.gap, expected, 1e-14) << "x = " << x;
    }
    EXPECT_EQ(negative, 10);
    EXPECT_EQ(r.overlapping, 10);
    EXPECT_NEAR(r.largestOverlap, largest, 0.0);
    EXPECT_NEAR(r.largestOverlap, 0.125 / std::sqrt(1.0 + 1.0 / 64.0), 1e-14);
  }
}

TEST(ContactSearch, searchCostPerSlaveNodeIsBounded) {
  // Master surfaces of ~10^2, 10^3, 10^4 triangles (2 n^2 for n x n cells) against a
  // non-matching slave grid: the closest-point evaluations per slave node stay below a
  // small constant. A search over all master faces would cost 2 n^2 per node (up to 10^4).
  // A count, not a time. Two search distances: tiny, and half the footprint (the tree must
  // prune by the best face found, not only by the search distance).
  for (int n : {7, 22, 71}) {
    const int slaveCells = n + 3;
    const auto m = stacked({2.0, 2.0}, {slaveCells, slaveCells}, {2.0, 2.0}, {n, n});
    const auto faces = m.sideSet("upper_z0").elements.size();
    EXPECT_EQ(faces, static_cast<size_t>(2 * n * n));
    for (double searchDistance : {1e-6, 1.0}) {
      const auto r = search(m, searchDistance);
      const double slaves = static_cast<double>((slaveCells + 1) * (slaveCells + 1));
      ASSERT_EQ(r.pairs.size(), static_cast<size_t>(slaves));
      const double perNode = r.facesTested / slaves;
      std::printf("master faces %6zu, slave nodes %5.0f, search distance %g: %.2f closest-point evaluations per slave node\n",
                  faces, slaves, searchDistance, perNode);
      EXPECT_GE(perNode, 1.0);  // every paired node evaluated at least its own face
      EXPECT_LT(perNode, 40.0) << faces << " master faces";
    }
  }
}

TEST(ContactSearch, masterFacesFacingAwayCannotBeTouched) {
  // The master surface named as the upper box's top (upper_z1, facing +z, away from the lower
  // box's top): every slave node within reach finds only faces that face away, so the sets
  // are wrong — an input error naming both sets.
  const auto m = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {2, 2});
  try {
    geometry::searchContactPairs(m, "lower_z1", "upper_z1", 5.0);
    ADD_FAILURE() << "no error";
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("upper_z1"), std::string::npos) << what;
    EXPECT_NE(what.find("lower_z1"), std::string::npos) << what;
    EXPECT_NE(what.find("faces away"), std::string::npos) << what;
  }
  // Some nodes facing away, others not: the slave set is the lower box's top and its side
  // x = 0 together. The side's nodes below the top edge (normal -x) see the master bottom
  // (normal into the upper box +z) edge-on: they cannot touch it and get no rows, the rest pair.
  auto m2 = stacked({2.0, 2.0}, {4, 4}, {2.0, 2.0}, {2, 2});
  mesh::SideSet both = m2.sideSet("lower_z1");
  both.name = "lower_top_and_side";
  both.id = 1000;
  const auto& side = m2.sideSet("lower_x0");
  both.elements.insert(both.elements.end(), side.elements.begin(), side.elements.end());
  both.sides.insert(both.sides.end(), side.sides.begin(), side.sides.end());
  m2.sideSets.push_back(both);
  const auto r = geometry::searchContactPairs(m2, "lower_top_and_side", "upper_z0", 2.0);
  EXPECT_EQ(r.facingAway, 5);  // x = 0, z = 0: 5 nodes along y
  EXPECT_EQ(r.unpaired.size(), 5u);
  for (LO n : r.unpaired) EXPECT_EQ(m2.coords[n][2], 0.0);
  EXPECT_EQ(r.pairs.size(), 25u);  // the top's 25 nodes (its x = 0 edge included)
}

TEST(ContactSearch, nodalNormalsDoNotDependOnHowFacetsAreCut) {
  // A roof: the top of a box of 2 x 1 x 1 cells of Kuhn tetrahedra, bent along x = 1 into two
  // flat facets sloping down by 0.3 per unit of x on either side. Every cell's top is cut along
  // the same diagonal, so a node on the ridge has one triangle of one facet and two of the
  // other. Weighted by area its normal leaned towards the facet with two (by 1/6 of the angle
  // between the facets, what read a shrink fit's interference as a tangential slip); weighted by
  // the faces' angles at the node each facet counts with its 90-degree corner: the bisector,
  // +z, exactly by the roof's symmetry.
  auto m = test::boxMesh({0.0, 0.0, 0.0}, {2.0, 1.0, 1.0}, {2, 1, 1}, "roof");
  for (auto& x : m.coords)
    if (x[2] == 1.0) x[2] = 1.0 - 0.3 * std::abs(x[0] - 1.0);
  const auto normals = geometry::unitNodalNormals(m, m.sideSet("roof_z1"));
  int ridgeNodes = 0;
  for (size_t n = 0; n < m.coords.size(); ++n) {
    const Vec3& x = m.coords[n];
    if (x[0] != 1.0 || x[2] != 1.0) continue;
    ++ridgeNodes;
    EXPECT_NEAR(normals[n][0], 0.0, 1e-14) << "ridge node at y = " << x[1];
    EXPECT_NEAR(normals[n][2], 1.0, 1e-14);
  }
  EXPECT_EQ(ridgeNodes, 2);
  // A node inside a facet's edge (x = 0) has that facet's normal, however many triangles meet.
  const Vec3 facet = unit({-0.3, 0.0, 1.0});
  for (size_t n = 0; n < m.coords.size(); ++n)
    if (m.coords[n][0] == 0.0 && m.coords[n][2] > 0.5)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(normals[n][c], facet[c], 1e-14);
}

TEST(ContactSearch, normalsOnSymmetryPlanesLieInThem) {
  // Held along x (a symmetry plane x = const) with a normal 1.7 degrees out of the plane: the
  // x part goes; 15 degrees out (more than the ~11.5 degrees of the rule) it stays; a node held
  // along nothing (0) keeps its normal.
  const Vec3 lean = unit({0.03, 1.0, 0.0}), far = unit({0.27, 1.0, 0.0});
  const Vec3 inPlane = geometry::inSymmetryPlanes(lean, 1);
  EXPECT_EQ(inPlane[0], 0.0);
  EXPECT_DOUBLE_EQ(inPlane[1], 1.0);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(geometry::inSymmetryPlanes(far, 1)[c], far[c], 1e-15);
  EXPECT_EQ(geometry::inSymmetryPlanes(lean, 0), lean);
  EXPECT_EQ(geometry::inSymmetryPlanes(lean, 2), lean);  // held along y: its y part is no lean
  // On the roof above, its x = 0 edge held along x: the normals there (-0.29, 0, 0.96) stay
  // (0.29 is past the rule); the same roof sloping by 0.1 gets them to +z.
  auto m = test::boxMesh({0.0, 0.0, 0.0}, {2.0, 1.0, 1.0}, {2, 1, 1}, "roof");
  for (auto& x : m.coords)
    if (x[2] == 1.0) x[2] = 1.0 - 0.1 * std::abs(x[0] - 1.0);
  geometry::HeldAxes held(m.coords.size(), 0);
  for (size_t n = 0; n < m.coords.size(); ++n)
    if (m.coords[n][0] == 0.0) held[n] = 1;
  const auto normals = geometry::unitNodalNormals(m, m.sideSet("roof_z1"), held);
  for (size_t n = 0; n < m.coords.size(); ++n)
    if (m.coords[n][0] == 0.0 && m.coords[n][2] > 0.5) {
      EXPECT_EQ(normals[n][0], 0.0);
      EXPECT_DOUBLE_EQ(normals[n][2], 1.0);
    }
  auto steep = test::boxMesh({0.0, 0.0, 0.0}, {2.0, 1.0, 1.0}, {2, 1, 1}, "roof");
  for (auto& x : steep.coords)
    if (x[2] == 1.0) x[2] = 1.0 - 0.3 * std::abs(x[0] - 1.0);
  const auto kept = geometry::unitNodalNormals(steep, steep.sideSet("roof_z1"), held);
  const Vec3 facet = unit({-0.3, 0.0, 1.0});
  for (size_t n = 0; n < steep.coords.size(); ++n)
    if (steep.coords[n][0] == 0.0 && steep.coords[n][2] > 0.5)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(kept[n][c], facet[c], 1e-14);
  // Held axes for another mesh's nodes are refused.
  EXPECT_THROW(geometry::unitNodalNormals(m, m.sideSet("roof_z1"), geometry::HeldAxes(3, 1)), std::invalid_argument);
}

TEST(ContactSearch, pairsOnSymmetryPlanesGetNormalsInThem) {
  // The gently sloping roof above as the master surface (held along x at x = 0), a flat box
  // above it as the slave: a slave node over the first facet gets the normal interpolated from
  // the x = 0 nodes' and the ridge's. With the held axes both are +z, so the pair's is -z
  // (to round-off); without them the x = 0 nodes lean with their facet and so does the pair's normal.
  auto roof = test::boxMesh({0.0, 0.0, 0.0}, {2.0, 1.0, 1.0}, {2, 1, 1}, "roof");
  for (auto& x : roof.coords)
    if (x[2] == 1.0) x[2] = 1.0 - 0.1 * std::abs(x[0] - 1.0);
  const auto m = test::mergeMeshes(roof, test::boxMesh({0.0, 0.0, 1.1}, {2.0, 1.0, 0.5}, {4, 2, 1}, "top"));
  geometry::HeldAxes held(m.coords.size(), 0);
  for (size_t n = 0; n < m.coords.size(); ++n)
    if (m.coords[n][0] == 0.0) held[n] = 1;
  const auto in = geometry::searchContactPairs(m, "top_z0", "roof_z1", 1.0, held);
  const auto out = geometry::searchContactPairs(m, "top_z0", "roof_z1", 1.0);
  ASSERT_EQ(in.pairs.size(), 15u);
  ASSERT_EQ(out.pairs.size(), 15u);
  int overFirstFacet = 0;
  for (size_t p = 0; p < in.pairs.size(); ++p) {
    if (m.coords[in.pairs[p].slaveNode][0] >= 1.0) continue;
    ++overFirstFacet;
    EXPECT_NEAR(in.pairs[p].normal[0], 0.0, 1e-14);
    EXPECT_DOUBLE_EQ(in.pairs[p].normal[2], -1.0);
    EXPECT_GT(out.pairs[p].normal[0], 0.01);  // leaning with the facet (-0.1, 0, 1), reversed
  }
  EXPECT_EQ(overFirstFacet, 6);  // x = 0 and 0.5, three nodes along y each
}

TEST(ContactSearch, quadraticFacesGiveTheirOwnNormals) {
  // The top of a box of 10-node Kuhn tetrahedra mapped onto a sphere of radius 3 (every node of
  // the top, mid-edge nodes included, on the sphere): 6-node faces that follow it. Each nodal
  // normal against the sphere's: from the faces' own (quadratic) geometry within 1e-2 rad
  // (6.3e-3 measured); the chord triangles' normals, the rule before, were off by up to
  // 0.126 rad (measured with the straight-face rule on this mesh).
  const double radius = 3.0;
  auto m = test::boxMesh({-1.0, -1.0, 0.0}, {2.0, 2.0, 1.0}, {4, 4, 1}, "cap",
                         test::CellElements::QuadraticKuhnTetrahedra);
  for (auto& x : m.coords)
    if (x[2] == 1.0) x[2] = 1.0 - radius + std::sqrt(radius * radius - x[0] * x[0] - x[1] * x[1]);
  const auto normals = geometry::unitNodalNormals(m, m.sideSet("cap_z1"));
  double worst = 0.0;
  int onTop = 0;
  for (size_t n = 0; n < m.coords.size(); ++n) {
    const Vec3& x = m.coords[n];
    if (x[2] < 0.6) continue;  // the top reaches down to 0.65; a vertical edge's mid node is at 0.5
    ++onTop;
    const Vec3 exact = unit({x[0], x[1], x[2] - (1.0 - radius)});
    worst = std::max(worst, std::acos(std::min(1.0, dot(normals[n], exact))));
  }
  std::printf("largest angle from the sphere's normal: %.3g rad over %d nodes\n", worst, onTop);
  EXPECT_EQ(onTop, 81);  // (2 x 4 + 1)^2 top nodes, vertices and mid-edge nodes
  EXPECT_LT(worst, 1e-2);
}

TEST(ContactSearch, aPointBesideTheMasterSurfacePairsWithNoFace) {
  // The master (upper_z0) covers 0 <= x, y <= 2 at z = 1. A point beyond its edge x = 2 lies
  // beside it whatever the distance: the edge's closest point is no point of contact. A point
  // over the surface, under its edge or under an edge between two of its faces pairs.
  const auto m = stacked({3.0, 2.0}, {6, 4}, {2.0, 2.0}, {2, 2});
  const geometry::MasterSurface master(m, "upper_z0");
  const double reach = 1.0;
  for (const Vec3& beside : {Vec3{2.5, 1.0, 1.0}, Vec3{2.25, 0.7, 0.6}, Vec3{2.1, 2.1, 1.0}, Vec3{-0.3, 1.0, 0.9}})
    EXPECT_EQ(master.pairingProjection(beside, reach).face, -1) << beside[0] << " " << beside[1] << " " << beside[2];
  for (const Vec3& over : {Vec3{1.5, 1.0, 0.8}, Vec3{2.0, 1.0, 0.9}, Vec3{2.0 + 1e-6, 1.0, 0.9}, Vec3{1.0, 1.0, 0.7},
                           Vec3{2.0, 2.0, 1.0}, Vec3{1.5, 1.0, 1.2}}) {
    const auto p = master.pairingProjection(over, reach);
    EXPECT_GE(p.face, 0) << over[0] << " " << over[1] << " " << over[2];
    EXPECT_NEAR(p.point[0], std::min(over[0], 2.0), 1e-15);
  }
}
