// Element types beyond the linear tetrahedron in the mesh layer (issue 32): gmsh's 8-node
// hexahedra, 10-node tetrahedra (its mid-edge order mapped to Exodus'), 6-node prisms and
// their quadrilateral and 6-node triangular surface elements; bodies of mixed types; the
// Exodus round trip of such bodies (one Exodus block per type, joined back by name); and
// the check that refuses a hexahedron inverted at one corner; dual mortar rows on quadrilaterals
// and 6-node triangles; the projection on a warped quadrilateral.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include "BoxMesh.hpp"
#include "TypedBoxMesh.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/mesh/BoundaryFaces.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/mesh/GmshReader.hpp"
#include "tribos/geometry/MortarCoupling.hpp"

using namespace tribos;
using namespace tribos::mesh;
using namespace tribos::geometry;

namespace {
struct GmshElement {
  int type;
  std::vector<long long> nodes;
};

/// A gmsh 4.1 file: nodes 1..n, the volume elements in Physical Volume "body" (tag 2), the
/// surface elements in Physical Surface "face" (tag 1); one entity per dimension.
std::string gmshText(const std::vector<std::array<double, 3>>& nodes, const std::vector<GmshElement>& volumes,
                     const std::vector<GmshElement>& surfaces) {
  std::ostringstream out;
  out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 1 \"face\"\n3 2 \"body\"\n$EndPhysicalNames\n"
      << "$Entities\n0 0 1 1\n1 0 0 0 1 1 1 1 1 0\n1 0 0 0 1 1 1 1 2 0\n$EndEntities\n";
  const size_t n = nodes.size();
  out << "$Nodes\n1 " << n << " 1 " << n << "\n3 1 0 " << n << "\n";
  for (size_t i = 0; i < n; ++i) out << i + 1 << "\n";
  for (const auto& x : nodes) out << x[0] << " " << x[1] << " " << x[2] << "\n";
  out << "$EndNodes\n$Elements\n";
  std::vector<std::pair<int, std::vector<const GmshElement*>>> blocks;  // (dim, elements) per type, in order
  size_t total = 0, tag = 0;
  auto group = [&](int dim, const std::vector<GmshElement>& all) {
    for (const auto& e : all) {
      if (blocks.empty() || blocks.back().second.front()->type != e.type || blocks.back().first != dim)
        blocks.push_back({dim, {}});
      blocks.back().second.push_back(&e);
      ++total;
    }
  };
  group(2, surfaces);
  group(3, volumes);
  out << blocks.size() << " " << total << " 1 " << total << "\n";
  for (const auto& [dim, elements] : blocks) {
    out << dim << " 1 " << elements.front()->type << " " << elements.size() << "\n";
    for (const GmshElement* e : elements) {
      out << ++tag;
      for (long long v : e->nodes) out << " " << v;
      out << "\n";
    }
  }
  out << "$EndElements\n";
  return out.str();
}

const std::vector<std::array<double, 3>> kCube = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                                                  {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

std::string tempFile(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("tribos_types_" + std::to_string(::getpid()) + "_" + name)).string();
}
}  // namespace

TEST(ElementTypes, gmshHexahedraWithQuadrilateralFacesInEitherOrientation) {
  for (bool mirrored : {false, true}) {
    SCOPED_TRACE(mirrored ? "top and bottom swapped" : "gmsh's orientation");
    std::vector<long long> hex = {1, 2, 3, 4, 5, 6, 7, 8};
    if (mirrored) hex = {5, 6, 7, 8, 1, 2, 3, 4};
    const Mesh m = parseGmsh(gmshText(kCube, {{5, hex}}, {{3, {1, 4, 3, 2}}}), "hex.msh", false);
    ASSERT_EQ(m.numElements(), 1);
    EXPECT_EQ(m.elementType(0), ElementType::Hex8);
    EXPECT_NEAR(m.elementVolume(0), 1.0, 1e-15);
    const SideSet& face = m.sideSet("face");
    ASSERT_EQ(face.elements.size(), 1u);
    const auto normal = m.faceNormal(face.elements[0], face.sides[0]);
    EXPECT_NEAR(normal[2], -2.0, 1e-15);  // outward (down), twice the area
    EXPECT_EQ(m.nodeSet("face").nodes.size(), 4u);
  }
}

TEST(ElementTypes, gmshQuadraticTetrahedraAreRenumberedToExodusOrder) {
  // Vertices, then gmsh's mid-edge nodes (0,1) (1,2) (2,0) (0,3) (2,3) (1,3).
  std::vector<std::array<double, 3>> nodes = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const int gmshEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {2, 3}, {1, 3}};
  for (const auto& e : gmshEdges) {
    std::array<double, 3> x;
    for (int c = 0; c < 3; ++c) x[c] = (nodes[e[0]][c] + nodes[e[1]][c]) / 2;
    nodes.push_back(x);
  }
  // The 6-node triangle of the face (0, 2, 1) at z = 0: vertices, then mid-edges (0,2) (2,1) (1,0).
  const Mesh m = parseGmsh(gmshText(nodes, {{11, {1, 2, 3, 4, 5, 6, 7, 8, 9, 10}}}, {{9, {1, 3, 2, 7, 6, 5}}}),
                           "tet10.msh", false);
  ASSERT_EQ(m.elementType(0), ElementType::Tet10);
  EXPECT_NEAR(m.elementVolume(0), 1.0 / 6, 1e-15);
  // Exodus mid-edge k + 4 lies halfway along its edge (0,1) (1,2) (2,0) (0,3) (1,3) (2,3).
  const int exodusEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const auto element = m.elementNodes(0);
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(m.coords[element[4 + k]][c],
                (m.coords[element[exodusEdges[k][0]]][c] + m.coords[element[exodusEdges[k][1]]][c]) / 2);
  const SideSet& face = m.sideSet("face");
  ASSERT_EQ(face.elements.size(), 1u);
  const FaceNodes f = m.faceNodes(face.elements[0], face.sides[0]);
  EXPECT_EQ(f.numNodes, 6);
  EXPECT_EQ(m.nodeSet("face").nodes.size(), 6u);  // the mid-edge nodes belong to the surface
  for (LO n : f) EXPECT_EQ(m.coords[n][2], 0.0);
}

TEST(ElementTypes, aBodyOfHexahedraAndPrismsIsOneBlockWithEachTypeTogether) {
  // A hexahedron and, beside it (x in [1, 2]), the two prisms of a cube split along a diagonal.
  std::vector<std::array<double, 3>> nodes = kCube;
  for (const auto& x : std::vector<std::array<double, 3>>{{2, 0, 0}, {2, 1, 0}, {2, 0, 1}, {2, 1, 1}}) nodes.push_back(x);
  // nodes 9 (2,0,0) 10 (2,1,0) 11 (2,0,1) 12 (2,1,1); the cube x in [1,2] has 2 3 10 9 / 6 7 12 11.
  const std::vector<GmshElement> volumes = {
      {6, {2, 9, 10, 6, 11, 12}}, {5, {1, 2, 3, 4, 5, 6, 7, 8}}, {6, {2, 10, 3, 6, 12, 7}}};
  const Mesh m = parseGmsh(gmshText(nodes, volumes, {}), "mixed.msh", false);
  ASSERT_EQ(m.numBlocks(), 1);
  ASSERT_EQ(m.numElements(), 3);
  EXPECT_EQ(m.elementType(0), ElementType::Hex8);  // sorted by type within the body
  EXPECT_EQ(m.elementType(1), ElementType::Wedge6);
  EXPECT_EQ(m.elementType(2), ElementType::Wedge6);
  double volume = 0.0;
  for (LO e = 0; e < 3; ++e) volume += m.elementVolume(e);
  EXPECT_NEAR(volume, 2.0, 1e-15);
}

TEST(ElementTypes, exodusRoundTripOfMixedAndQuadraticBodies) {
  for (auto kind : {test::BoxElements::HexAndWedge, test::BoxElements::Tet10, test::BoxElements::Wedge6}) {
    Mesh m = test::typedBox(kind, 2, 0.5, 0.1);
    m.blocks[0].name = "cube";
    const std::string path = tempFile("round.exo");
    TimeStep step;
    step.time = 1.0;
    Field id{"element_id", {}};
    for (LO e = 0; e < m.numElements(); ++e) id.values.push_back(e);
    step.element.push_back(id);
    writeExodus(path, m, {step});
    const ExodusData back = readExodus(path);
    std::filesystem::remove(path);
    ASSERT_EQ(back.mesh.numBlocks(), 1);  // the Exodus blocks of one name are one body again
    EXPECT_EQ(back.mesh.blocks[0].name, "cube");
    EXPECT_TRUE(back.mesh.elements == m.elements);
    EXPECT_EQ(back.mesh.coords, m.coords);
    ASSERT_EQ(back.steps.size(), 1u);
    EXPECT_EQ(back.steps[0].element[0].values, id.values);
  }
}

TEST(ElementTypes, aHexahedronInvertedAtOneCornerIsRefused) {
  Mesh m;
  m.coords = kCube;
  m.coords[6] = {0.3, 0.3, 0.3};  // the corner (1,1,1) pushed through the element: folded there
  m.elements.add(ElementType::Hex8, {0, 1, 2, 3, 4, 5, 6, 7});
  m.blocks.push_back({"body", 1, 0, 1});
  ASSERT_GT(m.elementVolume(0), 0.0);  // positive in total: only the corner check sees it
  try {
    m.validate("folded.exo");
    FAIL() << "no error";
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("type HEX8"), std::string::npos) << what;
    EXPECT_NE(what.find("inverted or distorted at a corner"), std::string::npos) << what;
  }
}

// The mortar rows of a distorted quadrilateral slave surface reproduce affine functions:
// sum_j w_ij f(x_j) = f(x_i) for the master nodes j, because the dual basis is biorthogonal
// to the bilinear one (int psi_i f = D_i f(x_i) for every f in its span, affine ones
// included, on any quadrilateral). Lumping instead (psi = phi) misses this on distorted
// faces by a fraction of the mesh size.
TEST(ElementTypes, dualMortarRowsOnDistortedQuadrilateralsAndSixNodeTrianglesReproduceAffineFunctions) {
  for (auto fill : {test::CellElements::Hexahedron, test::CellElements::QuadraticKuhnTetrahedra}) {
  SCOPED_TRACE(fill == test::CellElements::Hexahedron ? "hex8" : "tet10");
  Mesh lower = test::boxMesh({0, 0, 0}, {2, 2, 1}, {4, 4, 1}, "lower", fill);
  const Mesh upper = test::boxMesh({0, 0, 1}, {2, 2, 1}, {5, 5, 1}, "upper", test::CellElements::Hexahedron);
  // Move the interior nodes of the slave surface within its plane (by up to 0.15 of h = 0.5),
  // and the mid-edge nodes with them (to the middle of their edges).
  for (int j = 1; j < 4; ++j)
    for (int i = 1; i < 4; ++i) {
      auto& x = lower.coords[i + 5 * (j + 5)];
      x[0] += 0.075 * std::sin(3.0 * i + 7.0 * j);
      x[1] += 0.075 * std::cos(5.0 * i + 2.0 * j);
    }
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (LO e = 0; e < lower.numElements(); ++e) {
    if (lower.elementType(e) != ElementType::Tet10) continue;
    const auto nodes = lower.elementNodes(e);
    for (int k = 0; k < 6; ++k)
      for (int c = 0; c < 3; ++c)
        lower.coords[nodes[4 + k]][c] = (lower.coords[nodes[edges[k][0]]][c] + lower.coords[nodes[edges[k][1]]][c]) / 2;
  }
  const Mesh m = test::mergeMeshes(lower, upper);
  m.validate("distorted.exo");
  const auto search = searchContactPairs(m, "lower_z1", "upper_z0", 1e-6);
  const MasterSurface master(m, "upper_z0");
  const auto rows = dualMortarRows(m, "lower_z1", master, search, 1e-6);
  const size_t slaveNodes = m.nodeSet("lower_z1").nodes.size();  // 25 and, on tet10, the mid-edge nodes
  ASSERT_EQ(rows.size(), slaveNodes);
  double worst = 0.0;
  size_t mortarRows = 0;
  for (size_t p = 0; p < rows.size(); ++p) {
    if (rows[p].nodeToSurface) continue;
    ++mortarRows;
    for (int c = 0; c < 2; ++c) {  // the row applied to f = x and to f = y: zero
      double row = rows[p].slaveWeight * m.coords[search.pairs[p].slaveNode][c];
      for (size_t k = 0; k < rows[p].slaveNodes.size(); ++k)
        row += rows[p].slaveWeights[k] * m.coords[rows[p].slaveNodes[k]][c];
      for (size_t k = 0; k < rows[p].masterNodes.size(); ++k) row -= rows[p].weights[k] * m.coords[rows[p].masterNodes[k]][c];
      worst = std::max(worst, std::abs(row));
    }
  }
  std::printf("%zu mortar rows: affine functions reproduced to %.2e (h = 0.5)\n", mortarRows, worst);
  EXPECT_EQ(mortarRows, slaveNodes);
  EXPECT_LT(worst, 1e-3);
  }
}

// On a warped quadrilateral master face (one vertex lifted out of the plane of the others)
// the projection is the closest point of the bilinear face: no point of a fine grid over the
// face is closer, the weights are its bilinear shape functions there, and a query on a
// vertex gets exactly that vertex.
TEST(ElementTypes, projectionOnAWarpedQuadrilateralIsTheClosestPointOfTheBilinearFace) {
  Mesh m;
  m.coords = kCube;
  m.coords[6] = {1.0, 1.0, 1.3};  // the top face (4, 5, 6, 7) is warped
  m.elements.add(ElementType::Hex8, {0, 1, 2, 3, 4, 5, 6, 7});
  m.blocks.push_back({"body", 1, 0, 1});
  m.sideSets.push_back({"top", 1, {0}, {5}});
  const MasterSurface master(m, "top");
  auto bilinearPoint = [&](double xi, double eta) {
    const int top[4] = {4, 5, 6, 7};
    const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    std::array<double, 3> p{0, 0, 0};
    for (int k = 0; k < 4; ++k)
      for (int d = 0; d < 3; ++d)
        p[d] += (1 + corner[k][0] * xi) * (1 + corner[k][1] * eta) / 4 * m.coords[top[k]][d];
    return p;
  };
  auto distance = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  };
  for (const std::array<double, 3>& x : std::vector<std::array<double, 3>>{
           {0.3, 0.6, 1.6}, {0.9, 0.8, 1.5}, {0.1, 0.2, 1.2}, {1.4, 0.5, 1.4}, {0.7, 0.95, 2.0}}) {
    const auto p = master.project(x, 10.0);
    ASSERT_EQ(p.face, 0);
    double sum = 0.0, brute = INFINITY;
    std::array<double, 3> weighted{0, 0, 0};
    for (int v = 0; v < 4; ++v) {
      sum += p.weights[v];
      for (int d = 0; d < 3; ++d) weighted[d] += p.weights[v] * m.coords[p.nodes[v]][d];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14);
    EXPECT_LT(distance(weighted, p.point), 1e-14);  // the point is the weights' point of the face
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; j <= 400; ++j) brute = std::min(brute, distance(x, bilinearPoint(-1 + i / 200.0, -1 + j / 200.0)));
    EXPECT_LE(p.distance, brute + 1e-12);
    EXPECT_GE(p.distance, brute - 1e-4);  // the grid is within 1e-4 of the true closest point
  }
  const auto atVertex = master.project(m.coords[6], 1.0);
  for (int v = 0; v < 4; ++v) EXPECT_EQ(atVertex.weights[v], atVertex.nodes[v] == 6 ? 1.0 : 0.0);
}

// A warped interface (z += 0.15 (x - 1) (y - 1): every hexahedron's top face is a twisted
// bilinear quadrilateral that holds the surface exactly): every slave node lies on the master
// surface and pairs at the default search distance, with a zero gap, though it lies up to
// twist / 4 off the master's search triangles (the search reaches that much farther).
TEST(ElementTypes, slaveNodesOnAWarpedQuadrilateralMasterPairAtTheDefaultSearchDistance) {
  const Mesh lower = test::boxMesh({0, 0, 0}, {2, 2, 1}, {4, 4, 1}, "lower", test::CellElements::Hexahedron);
  const Mesh upper = test::boxMesh({0, 0, 1}, {2, 2, 1}, {3, 3, 1}, "upper", test::CellElements::Hexahedron);
  Mesh m = test::mergeMeshes(lower, upper);
  for (auto& x : m.coords) x[2] += 0.15 * (x[0] - 1.0) * (x[1] - 1.0);
  m.validate("warped.exo");
  const auto search = searchContactPairs(m, "lower_z1", "upper_z0", 1e-6);
  EXPECT_EQ(search.pairs.size(), 25u);
  EXPECT_TRUE(search.unpaired.empty());
  double largestGap = 0.0;
  for (const auto& pair : search.pairs) largestGap = std::max(largestGap, std::abs(pair.gap));
  EXPECT_LT(largestGap, 1e-12);
}

// A side set may hold every face of its elements: 6 of a lone hexahedron (the reader once
// capped side sets at 4 faces per element, the tetrahedron's count, and called this corrupt).
TEST(ElementTypes, aSideSetOfEveryFaceOfAHexahedronReadsBack) {
  Mesh m;
  m.coords = kCube;
  m.elements.add(ElementType::Hex8, {0, 1, 2, 3, 4, 5, 6, 7});
  m.blocks.push_back({"body", 1, 0, 1});
  m.sideSets.push_back({"skin", 1, {0, 0, 0, 0, 0, 0}, {0, 1, 2, 3, 4, 5}});
  const std::string path = tempFile("skin.exo");
  writeExodus(path, m);
  const ExodusData back = readExodus(path);
  std::filesystem::remove(path);
  EXPECT_EQ(back.mesh.sideSet("skin").sides, (std::vector<int>{0, 1, 2, 3, 4, 5}));
}

// Two Physical Volumes of one name would be one body after an Exodus round trip (the reader
// joins blocks of one name): the gmsh reader refuses them, naming both tags.
TEST(ElementTypes, twoPhysicalVolumesOfOneNameAreRefused) {
  std::ostringstream text;
  text << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3 2 \"body\"\n3 3 \"body\"\n$EndPhysicalNames\n"
       << "$Entities\n0 0 0 2\n1 0 0 0 1 1 1 1 2 0\n2 1 0 0 2 1 1 1 3 0\n$EndEntities\n"
       << "$Nodes\n1 12 1 12\n3 1 0 12\n";
  for (int n = 1; n <= 12; ++n) text << n << "\n";
  for (const auto& x : kCube) text << x[0] << " " << x[1] << " " << x[2] << "\n";
  text << "2 0 0\n2 1 0\n2 0 1\n2 1 1\n$EndNodes\n$Elements\n2 2 1 2\n"
       << "3 1 5 1\n1 1 2 3 4 5 6 7 8\n3 2 5 1\n2 2 9 10 3 6 11 12 7\n$EndElements\n";
  try {
    parseGmsh(text.str(), "twins.msh", false);
    FAIL() << "no error";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("Physical Volumes 2 and 3 are both named \"body\""), std::string::npos)
        << e.what();
  }
}

// The closest point of a 6-node master face to a point beside one of its edges lies on that
// edge where the distance is smallest, also on a face whose reference map is skewed (an
// equilateral face: dX/dr . dX/ds != 0); the first version clamped the free Gauss-Newton step
// and stopped 0.058 edge lengths off (review).
TEST(ElementTypes, projectionBesideAnEdgeOfASixNodeTriangleIsTheClosestPoint) {
  Mesh m;
  const double h = std::sqrt(3.0) / 2;
  m.coords = {{0, 0, 0}, {1, 0, 0}, {0.5, h, 0}, {0.5, 0.3, 0.8}};
  const int edges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (const auto& e : edges) {
    std::array<double, 3> x;
    for (int c = 0; c < 3; ++c) x[c] = (m.coords[e[0]][c] + m.coords[e[1]][c]) / 2;
    m.coords.push_back(x);
  }
  m.elements.add(ElementType::Tet10, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  if (m.elementVolume(0) < 0.0) {  // the face z = 0 must face down: orient the element positively
    std::swap(m.coords[1], m.coords[2]);
    std::swap(m.coords[4], m.coords[6]);
    std::swap(m.coords[8], m.coords[9]);
  }
  ASSERT_GT(m.elementVolume(0), 0.0);
  m.blocks.push_back({"body", 1, 0, 1});
  m.sideSets.push_back({"bottom", 1, {0}, {3}});  // Exodus side 4: (0, 2, 1) at z = 0
  const MasterSurface master(m, "bottom");
  for (const std::array<double, 3>& x : std::vector<std::array<double, 3>>{
           {0.3, -0.1, 0.0}, {0.3, -0.1, -0.05}, {0.9, 0.4, -0.02}, {-0.1, 0.3, 0.0}, {1.2, -0.1, 0.0}}) {
    const auto p = master.project(x, 10.0);
    ASSERT_EQ(p.face, 0);
    // Brute force: the face is flat with straight edges, so its points are the triangle's.
    double brute = INFINITY;
    const auto& a = m.coords[0];
    const auto& b = m.coords[1];
    const auto& c = m.coords[2];
    for (int i = 0; i <= 400; ++i)
      for (int j = 0; i + j <= 400; ++j) {
        const double u = i / 400.0, v = j / 400.0;
        double d2 = 0.0;
        for (int k = 0; k < 3; ++k) {
          const double y = (1 - u - v) * a[k] + u * b[k] + v * c[k] - x[k];
          d2 += y * y;
        }
        brute = std::min(brute, std::sqrt(d2));
      }
    EXPECT_LE(p.distance, brute + 1e-12);
    EXPECT_GE(p.distance, brute - 3e-3);  // the grid is within 1/400 of the true closest point
  }
}
