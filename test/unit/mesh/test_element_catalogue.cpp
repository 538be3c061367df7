// The element catalogue against Trilinos's own tables, as Amesos2 serves as the direct-solve
// reference: every element type's node, vertex and side counts and its sides' node lists in
// Exodus order against Shards' cell topologies, and the shape functions and their
// derivatives of every element and face type against Intrepid2's HGRAD bases at random
// points of the reference cell (the same reference cells: the unit simplex, [-1, 1]^3, the
// unit triangle times [-1, 1]).
#include <gtest/gtest.h>

#include <Intrepid2_HGRAD_HEX_C1_FEM.hpp>
#include <Intrepid2_HGRAD_QUAD_C1_FEM.hpp>
#include <Intrepid2_HGRAD_TET_C1_FEM.hpp>
#include <Intrepid2_HGRAD_TET_C2_FEM.hpp>
#include <Intrepid2_HGRAD_TRI_C1_FEM.hpp>
#include <Intrepid2_HGRAD_TRI_C2_FEM.hpp>
#include <Intrepid2_HGRAD_WEDGE_C1_FEM.hpp>
#include <Shards_BasicTopologies.hpp>
#include <Teuchos_RCP.hpp>  // the definitions of the RCP conversions Intrepid2's getHostBasis uses

#include <algorithm>
#include <random>

#include "tribos/mesh/ElementTypes.hpp"
#include "tribos/mesh/ShapeFunctions.hpp"

using namespace tribos;
using mesh::ElementType;
using mesh::FaceType;

namespace {
using Device = Kokkos::HostSpace::device_type;
using View = Kokkos::DynRankView<double, Device>;

const CellTopologyData* shardsTopology(ElementType type) {
  switch (type) {
    case ElementType::Tet4: return shards::getCellTopologyData<shards::Tetrahedron<4>>();
    case ElementType::Tet10: return shards::getCellTopologyData<shards::Tetrahedron<10>>();
    case ElementType::Hex8: return shards::getCellTopologyData<shards::Hexahedron<8>>();
    case ElementType::Wedge6: return shards::getCellTopologyData<shards::Wedge<6>>();
  }
  return nullptr;
}

/// Random points inside the reference cell of `dimension` coordinates: `simplex` coordinates
/// (the first ones) with sum <= 1 and >= 0, the rest in [-1, 1].
std::vector<std::array<double, 3>> referencePoints(int simplex, int dimension, int count) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0), box(-1.0, 1.0);
  std::vector<std::array<double, 3>> points;
  while (static_cast<int>(points.size()) < count) {
    std::array<double, 3> x{0.0, 0.0, 0.0};
    double sum = 0.0;
    for (int d = 0; d < dimension; ++d) {
      x[d] = d < simplex ? unit(random) : box(random);
      if (d < simplex) sum += x[d];
    }
    if (sum <= 1.0) points.push_back(x);
  }
  return points;
}

/// Compares N and dN of Tribos (`tribos(xi, N, dN)`) with an Intrepid2 basis at the points.
template <class Basis, class Tribos>
void expectSameBasis(const Basis& basis, int dimension, const std::vector<std::array<double, 3>>& points,
                     Tribos tribos) {
  const int n = basis.getCardinality(), p = static_cast<int>(points.size());
  View x("points", p, dimension), values("values", n, p), gradients("gradients", n, p, dimension);
  for (int q = 0; q < p; ++q)
    for (int d = 0; d < dimension; ++d) x(q, d) = points[q][d];
  basis.getValues(values, x, Intrepid2::OPERATOR_VALUE);
  basis.getValues(gradients, x, Intrepid2::OPERATOR_GRAD);
  for (int q = 0; q < p; ++q) {
    double N[mesh::kMaxElementNodes] = {}, dN[mesh::kMaxElementNodes][3] = {};
    tribos(points[q].data(), N, dN);
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(N[k], values(k, q), 1e-13) << "node " << k << " at point " << q;
      for (int d = 0; d < dimension; ++d)
        EXPECT_NEAR(dN[k][d], gradients(k, q, d), 1e-12) << "node " << k << ", d/dxi_" << d << " at point " << q;
    }
  }
}

template <class Basis>
void expectSameElement(const Basis& basis, ElementType type, int simplex) {
  SCOPED_TRACE(mesh::elementShape(type).description);
  ASSERT_EQ(basis.getCardinality(), mesh::elementShape(type).numNodes);
  expectSameBasis(basis, 3, referencePoints(simplex, 3, 25),
                  [type](const double* xi, double* N, double (*dN)[3]) { mesh::shapeFunctions(type, xi, N, dN); });
}

template <class Basis>
void expectSameFace(const Basis& basis, FaceType type, int simplex) {
  ASSERT_EQ(basis.getCardinality(), mesh::faceNodeCount(type));
  expectSameBasis(basis, 2, referencePoints(simplex, 2, 25), [type](const double* xi, double* N, double (*dN)[3]) {
    const double point[3] = {xi[0], xi[1], 0.0};
    mesh::faceShapeFunctions(type, point, N, dN);
  });
}
}  // namespace

TEST(ElementCatalogue, countsAndSidesAreShardsTopologies) {
  for (int t = 0; t < mesh::kNumElementTypes; ++t) {
    const auto type = static_cast<ElementType>(t);
    const mesh::ElementShape& ours = mesh::elementShape(type);
    const CellTopologyData* shards = shardsTopology(type);
    SCOPED_TRACE(std::string(ours.description) + " against Shards' " + shards->name);
    EXPECT_EQ(ours.numNodes, static_cast<int>(shards->node_count));
    EXPECT_EQ(ours.numVertices, static_cast<int>(shards->vertex_count));
    ASSERT_EQ(ours.numFaces, static_cast<int>(shards->side_count));
    for (int s = 0; s < ours.numFaces; ++s) {
      const mesh::FaceShape& face = ours.faces[s];
      const CellTopologyData* side = shards->side[s].topology;
      EXPECT_EQ(face.numNodes, static_cast<int>(side->node_count)) << "side " << s;
      EXPECT_EQ(face.numVertices, static_cast<int>(side->vertex_count)) << "side " << s;
      for (int k = 0; k < face.numNodes; ++k)
        EXPECT_EQ(face.nodes[k], static_cast<int>(shards->side[s].node[k])) << "side " << s << ", node " << k;
    }
  }
}

TEST(ElementCatalogue, shapeFunctionsAreIntrepid2Bases) {
  expectSameElement(Intrepid2::Basis_HGRAD_TET_C1_FEM<Device>(), ElementType::Tet4, 3);
  expectSameElement(Intrepid2::Basis_HGRAD_TET_C2_FEM<Device>(), ElementType::Tet10, 3);
  expectSameElement(Intrepid2::Basis_HGRAD_HEX_C1_FEM<Device>(), ElementType::Hex8, 0);
  expectSameElement(Intrepid2::Basis_HGRAD_WEDGE_C1_FEM<Device>(), ElementType::Wedge6, 2);
}

TEST(ElementCatalogue, faceShapeFunctionsAreIntrepid2Bases) {
  expectSameFace(Intrepid2::Basis_HGRAD_TRI_C1_FEM<Device>(), FaceType::Tri3, 2);
  expectSameFace(Intrepid2::Basis_HGRAD_TRI_C2_FEM<Device>(), FaceType::Tri6, 2);
  expectSameFace(Intrepid2::Basis_HGRAD_QUAD_C1_FEM<Device>(), FaceType::Quad4, 0);
}

namespace {
/// The reference nodes of a basis (Intrepid2's degree-of-freedom coordinates), `dimension` each.
template <class Basis>
std::vector<std::array<double, 3>> referenceNodes(const Basis& basis, int dimension) {
  View coords("coords", basis.getCardinality(), dimension);
  basis.getDofCoords(coords);
  std::vector<std::array<double, 3>> nodes(basis.getCardinality(), {0.0, 0.0, 0.0});
  for (int k = 0; k < basis.getCardinality(); ++k)
    for (int d = 0; d < dimension; ++d) nodes[k][d] = coords(k, d);
  return nodes;
}

/// det J of an element of `type` with nodes x at the reference point xi.
double jacobianDeterminant(ElementType type, const std::vector<std::array<double, 3>>& x, const double xi[3]) {
  double N[mesh::kMaxElementNodes], dN[mesh::kMaxElementNodes][3], J[3][3], coords[mesh::kMaxElementNodes][3];
  for (size_t k = 0; k < x.size(); ++k)
    for (int d = 0; d < 3; ++d) coords[k][d] = x[k][d];
  mesh::shapeFunctions(type, xi, N, dN);
  return mesh::jacobian(type, coords, dN, J);
}

template <class Basis>
void expectMirrorReverses(const Basis& basis, ElementType type) {
  const mesh::ElementShape& shape = mesh::elementShape(type);
  SCOPED_TRACE(shape.description);
  const auto x = referenceNodes(basis, 3);  // the reference element itself: det J = 1
  const double xi[3] = {0.2, 0.25, 0.1};
  EXPECT_NEAR(jacobianDeterminant(type, x, xi), 1.0, 1e-14);
  std::vector<std::array<double, 3>> mirrored(x.size()), fromGmsh(x.size());
  std::vector<int> seen(x.size(), 0), seenGmsh(x.size(), 0);
  for (int k = 0; k < shape.numNodes; ++k) {
    mirrored[k] = x[shape.mirrorNode[k]];
    ++seen[shape.mirrorNode[k]];
    ++seenGmsh[shape.gmshNode[k]];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), shape.numNodes) << "mirrorNode is not a permutation";
  EXPECT_EQ(std::count(seenGmsh.begin(), seenGmsh.end(), 1), shape.numNodes) << "gmshNode is not a permutation";
  EXPECT_LT(jacobianDeterminant(type, mirrored, xi), 0.0);
  // A mirror of a mirror is the element itself.
  for (int k = 0; k < shape.numNodes; ++k) EXPECT_EQ(shape.mirrorNode[shape.mirrorNode[k]], k);
}

template <class Basis>
void expectFaceCatalogue(const Basis& basis, FaceType type, double referenceArea) {
  const mesh::FaceTypeShape& shape = mesh::faceTypeShape(type);
  SCOPED_TRACE(shape.description);
  const auto nodes = referenceNodes(basis, 2);
  ASSERT_EQ(static_cast<int>(nodes.size()), shape.numNodes);
  for (int k = 0; k < shape.numNodes; ++k)
    for (int d = 0; d < 2; ++d) EXPECT_EQ(shape.referenceNodes[k][d], nodes[k][d]) << "node " << k;
  // The search triangles tile the reference face, each positively oriented.
  double area = 0.0;
  for (int t = 0; t < shape.numSearchTriangles; ++t) {
    const double* a = shape.referenceNodes[shape.searchTriangles[t][0]];
    const double* b = shape.referenceNodes[shape.searchTriangles[t][1]];
    const double* c = shape.referenceNodes[shape.searchTriangles[t][2]];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    EXPECT_GT(twice, 0.0) << "search triangle " << t;
    area += twice / 2;
  }
  EXPECT_NEAR(area, referenceArea, 1e-15);
  EXPECT_EQ(shape.curved, type != FaceType::Tri3);
}
}  // namespace

TEST(ElementCatalogue, mirrorsReverseElementsAndGmshOrdersArePermutations) {
  expectMirrorReverses(Intrepid2::Basis_HGRAD_TET_C1_FEM<Device>(), ElementType::Tet4);
  expectMirrorReverses(Intrepid2::Basis_HGRAD_TET_C2_FEM<Device>(), ElementType::Tet10);
  expectMirrorReverses(Intrepid2::Basis_HGRAD_HEX_C1_FEM<Device>(), ElementType::Hex8);
  expectMirrorReverses(Intrepid2::Basis_HGRAD_WEDGE_C1_FEM<Device>(), ElementType::Wedge6);
}

TEST(ElementCatalogue, faceReferenceNodesAreIntrepid2sAndSearchTrianglesTileTheFace) {
  expectFaceCatalogue(Intrepid2::Basis_HGRAD_TRI_C1_FEM<Device>(), FaceType::Tri3, 0.5);
  expectFaceCatalogue(Intrepid2::Basis_HGRAD_TRI_C2_FEM<Device>(), FaceType::Tri6, 0.5);
  expectFaceCatalogue(Intrepid2::Basis_HGRAD_QUAD_C1_FEM<Device>(), FaceType::Quad4, 4.0);
}

TEST(ElementCatalogue, readersFindEveryTypeByItsNames) {
  for (int t = 0; t < mesh::kNumElementTypes; ++t) {
    const auto type = static_cast<ElementType>(t);
    const mesh::ElementShape& shape = mesh::elementShape(type);
    ElementType found;
    ASSERT_TRUE(mesh::elementTypeOfGmsh(shape.gmshType, found)) << shape.description;
    EXPECT_EQ(found, type);
    ASSERT_TRUE(mesh::elementTypeOfExodus(shape.exodusName, shape.numNodes, found)) << shape.description;
    EXPECT_EQ(found, type);
    EXPECT_FALSE(mesh::elementTypeOfExodus(shape.exodusName, shape.numNodes + 1, found)) << shape.description;
  }
  ElementType found;
  EXPECT_FALSE(mesh::elementTypeOfGmsh(7, found));  // a pyramid
  EXPECT_FALSE(mesh::elementTypeOfExodus("HEX20", 20, found));
}
