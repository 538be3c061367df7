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
