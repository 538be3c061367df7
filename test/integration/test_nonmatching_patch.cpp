// A contact patch test: two stacked boxes of different materials pressed together by a
// uniform pressure p, held only by symmetry planes, frictionless. The exact solution is a
// uniform strain in each body (sigma_zz = -p in both; the bodies slide freely against each
// other as their lateral expansions differ) with a uniform contact pressure p. On matching
// interface meshes the discrete problem contains it (linear fields, node-to-node rows), so
// T-FETI + SMALSE-M must reproduce it to round-off. On non-matching meshes (4x4 against
// 5x5 cells) node-to-surface rows transfer the slave's nodal forces to the master with the
// interpolation weights, which are not the master's consistent nodal forces of a uniform
// pressure: the discrete solution deviates from the uniform one. The test reports that
// deviation (VALIDATION.md) and bounds it; the total force and its direction stay exact. The
// dual mortar rows with segment-based integrals (geometry/MortarSegments.hpp) pass it to
// round-off on every pair of face types, structured or not (issue 41).
// The same patch with hexahedra (quadrilateral contact faces, bilinear dual basis) and with
// hexahedra against tetrahedra both ways (issue 32). ctest runs this on 1 and 2 ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "BoxMesh.hpp"
#include "BoxScene.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/stack/GlobalFields.hpp"

namespace {
using namespace tribos;
using test::displacementCondition;
using test::with;
using test::worldRank;

constexpr double kP = 10.0;                 // pressure on the top of the upper body
constexpr double kE1 = 70000.0, kNu1 = 0.33;   // lower body (slave)
constexpr double kE2 = 210000.0, kNu2 = 0.3;   // upper body (master)
constexpr double kArea = 4.0;               // 2 x 2 footprint

using test::CellElements;

/// Lower body [0,2]^2 x [0,1] with 4x4x2 cells, upper body [0,2]^2 x [1,2] with upperCells,
/// each cell filled as given.
mesh::Mesh patchMesh(std::array<int, 3> upperCells, CellElements lower = CellElements::KuhnTetrahedra,
                     CellElements upper = CellElements::KuhnTetrahedra) {
  auto m = test::mergeMeshes(test::boxMesh({0, 0, 0}, {2, 2, 1}, {4, 4, 2}, "lower", lower),
                             test::boxMesh({0, 0, 1}, {2, 2, 1}, upperCells, "upper", upper));
  m.validate("test");
  return m;
}

std::vector<std::string> patchScene() {
  std::vector<std::string> o = {
      "Mesh/Subdomains=4",
      "Materials/lower/Young Modulus=70000", "Materials/lower/Poisson Ratio=0.33",
      "Materials/upper/Young Modulus=210000", "Materials/upper/Poisson Ratio=0.3",
      "Loads/pressure/Side Set=upper_z1", "Loads/pressure/Traction={0, 0, -10}",
      "Contact/Friction Model=None", "Contact/Slave Side Set=lower_z1", "Contact/Master Side Set=upper_z0",
      "Contact/Search Distance=1e-6",
      "Solver/Tolerance=1e-12", "Solver/Verbose=false"};
  o = with(o, displacementCondition("lower_symmetry_x", "lower_x0", "x"));
  o = with(o, displacementCondition("upper_symmetry_x", "upper_x0", "x"));
  o = with(o, displacementCondition("lower_symmetry_y", "lower_y0", "y"));
  o = with(o, displacementCondition("upper_symmetry_y", "upper_y0", "y"));
  return with(o, displacementCondition("lower_support", "lower_z0", "z"));
}

/// The uniform-strain solution: lower u = (nu1 p/E1 x, nu1 p/E1 y, -p/E1 z); upper
/// u = (nu2 p/E2 x, nu2 p/E2 y, -p/E1 - p/E2 (z - 1)) (u_z continuous at z = 1).
std::array<double, 3> exact(const std::array<double, 3>& x, bool upper) {
  if (!upper) return {kNu1 * kP / kE1 * x[0], kNu1 * kP / kE1 * x[1], -kP / kE1 * x[2]};
  return {kNu2 * kP / kE2 * x[0], kNu2 * kP / kE2 * x[1], -kP / kE1 - kP / kE2 * (x[2] - 1.0)};
}

/// Per body: max |u - exact| / max |exact| over its nodes.
std::array<double, 2> displacementErrors(const test::SolvedBoxScene& s) {
  const auto& m = s.scene.mesh;
  std::vector<int> body(m.numNodes(), -1);
  for (LO e = 0; e < m.numElements(); ++e)
    for (LO n : m.elementNodes(e)) body[n] = m.blockOf(e);
  std::array<double, 2> diff{0, 0}, norm{0, 0};
  for (LO n = 0; n < m.numNodes(); ++n) {
    const int b = body[n];
    const auto u0 = exact(m.coords[n], b == 1);
    for (int c = 0; c < 3; ++c) {
      diff[b] = std::max(diff[b], std::abs(s.displacement()[n][c] - u0[c]));
      norm[b] = std::max(norm[b], std::abs(u0[c]));
    }
  }
  return {diff[0] / norm[0], diff[1] / norm[1]};
}

struct PressureStats {
  double minDev = INFINITY, maxDev = -INFINITY, meanAbsDev = 0.0, maxAbsDev = 0.0;
  int nodes = 0;
};

/// Relative deviation (pressure - p) / p over the slave nodes.
PressureStats pressureStats(const test::SolvedBoxScene& s) {
  PressureStats st;
  for (LO n : s.scene.mesh.nodeSet("lower_z1").nodes) {
    const double dev = (s.contact.contactPressure[n] - kP) / kP;
    st.minDev = std::min(st.minDev, dev);
    st.maxDev = std::max(st.maxDev, dev);
    st.meanAbsDev += std::abs(dev);
    st.maxAbsDev = std::max(st.maxAbsDev, std::abs(dev));
    ++st.nodes;
  }
  st.meanAbsDev /= st.nodes;
  return st;
}

/// The discrete equations node by node, with the undecomposed stiffness (independent of
/// T-FETI): K u - f is the contact force each node receives — -s F_r nu at slave node r (s its
/// weight in the row, ContactNode::sides; a mid-edge node's row reaches its edge's ends too) and
/// sum_r w_r(m) F_r nu at master node m, F_r the reported normal force (of the slave on the
/// master) — and zero at every other node, except in prescribed components (reactions).
/// And every slave node, all in contact, sits on the interpolated master surface:
/// (u_s - sum_i w_i u_m_i) . nu = d = 0. Returns the largest mismatch of each, relative to
/// p * area and to max |u|.
std::array<double, 2> nodeToSurfaceResiduals(const test::SolvedBoxScene& s) {
  const auto& m = s.scene.mesh;
  const auto global = fem::assembleGlobal(m, s.scene.materials, s.scene.loads);
  const size_t n3 = 3 * static_cast<size_t>(m.numNodes());
  std::vector<double> u(n3), Ku(n3), expected(n3, 0.0);
  double uMax = 0.0;
  for (LO n = 0; n < m.numNodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      u[3 * n + c] = s.displacement()[n][c];
      uMax = std::max(uMax, std::abs(u[3 * n + c]));
    }
  global.K.apply(u.data(), Ku.data());
  std::vector<char> prescribed(n3, 0);
  for (const auto& cond : s.scene.displacementConditions)
    for (LO n : m.nodeSet(cond.nodeSet).nodes)
      for (int c = 0; c < 3; ++c)
        if (cond.components[c]) prescribed[3 * n + c] = 1;
  double gapMismatch = 0.0;
  for (const auto& node : s.B.contact) {
    const double F = s.contact.contactNormal[node.slaveNode];
    double jump = 0.0;
    for (const auto& [n, weight] : node.sides())  // the slave node(s) +, the master nodes -
      for (int c = 0; c < 3; ++c) {
        expected[3 * n + c] -= weight * F * node.normal[c];
        jump += weight * u[3 * n + c] * node.normal[c];
      }
    gapMismatch = std::max(gapMismatch, std::abs(jump - node.gap));
  }
  double forceMismatch = 0.0;
  for (size_t i = 0; i < n3; ++i)
    if (!prescribed[i]) forceMismatch = std::max(forceMismatch, std::abs(Ku[i] - global.f[i] - expected[i]));
  return {forceMismatch / (kP * kArea), gapMismatch / uMax};
}

void expectConvergedWithExactResultants(const test::SolvedBoxScene& s) {
  const auto& r = s.contact.contact;
  EXPECT_TRUE(r.converged) << r.message;
  if (worldRank() != 0) return;
  const auto slaveNodes = s.scene.mesh.nodeSet("lower_z1").nodes.size();  // 25, and mid-edge nodes
  EXPECT_EQ(s.B.contact.size(), slaveNodes);   // every slave node paired
  EXPECT_EQ(s.B.unpairedSlaveNodes(), 0);
  EXPECT_EQ(r.statusCounts[0], 0);             // all in contact
  EXPECT_EQ(r.statusCounts[2], static_cast<int>(slaveNodes));  // frictionless: every contact node slides
  // The upper body carries p over the area to the lower one: sum of the normal forces.
  EXPECT_NEAR(s.contact.totalNormalForce, kP * kArea, 1e-8 * kP * kArea);
  EXPECT_NEAR(s.contact.totalContactForce[2], kP * kArea, 1e-8 * kP * kArea);
  // Normals are exactly z on the flat surfaces: no force in x or y.
  EXPECT_NEAR(s.contact.totalContactForce[0], 0.0, 1e-12 * kP * kArea);
  EXPECT_NEAR(s.contact.totalContactForce[1], 0.0, 1e-12 * kP * kArea);
  // The reported forces and displacements solve the node-to-surface equations.
  const auto residuals = nodeToSurfaceResiduals(s);
  std::printf("node-to-surface equations: force mismatch %.2e (of p * area), gap mismatch %.2e (of max |u|)\n",
              residuals[0], residuals[1]);
  EXPECT_LE(residuals[0], 1e-8);
  EXPECT_LE(residuals[1], 1e-8);
}
}  // namespace

TEST(nonmatchingPatch, matchingMeshesReproduceTheUniformSolution) {
  // Both footprints 4x4 (the upper body 3 cells high against the lower's 2).
  const auto s = test::solveBoxScene(patchMesh({4, 4, 3}), patchScene());
  expectConvergedWithExactResultants(s);
  if (worldRank() != 0) return;
  const auto errors = displacementErrors(s);
  const auto st = pressureStats(s);
  std::printf("matching: displacement error lower %.3e, upper %.3e; contact pressure deviation from p: min %.3e, "
              "max %.3e, mean |.| %.3e\n",
              errors[0], errors[1], st.minDev, st.maxDev, st.meanAbsDev);
  EXPECT_LE(errors[0], 1e-10);
  EXPECT_LE(errors[1], 1e-10);
  EXPECT_LE(st.maxAbsDev, 1e-10);  // p at every node, edges and corners included
  // u_z linear in z across both bodies: in particular -p/E1 on the interface and
  // -p/E1 - p/E2 on the top.
  for (LO n : s.scene.mesh.nodeSet("upper_z1").nodes)
    EXPECT_NEAR(s.displacement()[n][2], -kP / kE1 - kP / kE2, 1e-10 * kP / kE1);
}

namespace {
/// Solves the 4x4 (slave) against 5x5 (master) patch with the given contact discretisation;
/// checks the resultants and the mean pressure; returns the pressure statistics and the
/// displacement errors (rank 0).
std::pair<PressureStats, std::array<double, 2>> nonMatchingPatch(const std::string& discretization,
                                                                 CellElements lower = CellElements::KuhnTetrahedra,
                                                                 CellElements upper = CellElements::KuhnTetrahedra) {
  const auto s = test::solveBoxScene(patchMesh({5, 5, 3}, lower, upper),
                                     with(patchScene(), {"Contact/Discretization=" + discretization}));
  expectConvergedWithExactResultants(s);
  if (worldRank() != 0) return {};
  const auto errors = displacementErrors(s);
  const auto st = pressureStats(s);
  std::printf("non-matching 4x4 / 5x5, %s: displacement error lower %.3e, upper %.3e; contact pressure deviation "
              "from p: min %+.3e, max %+.3e, mean |.| %.3e\n",
              discretization.c_str(), errors[0], errors[1], st.minDev, st.maxDev, st.meanAbsDev);
  // Pressure p on average: the total force is exact and the tributary areas add up to the
  // footprint, so sum_i A_i (pressure_i - p) = 0.
  double weighted = 0.0;
  const auto area = stack::tributaryArea(s.scene.mesh, "lower_z1");
  for (LO n : s.scene.mesh.nodeSet("lower_z1").nodes) weighted += area[n] * (s.contact.contactPressure[n] - kP);
  EXPECT_NEAR(weighted, 0.0, 1e-8 * kP * kArea);
  return {st, errors};
}
}  // namespace

TEST(nonmatchingPatch, mortarRowsPassThePatchTestOnNonMatchingMeshes) {
  // The dual mortar rows (the default) transfer a uniform pressure as uniform: with the
  // master faces clipped against each slave face, the master hat functions' kinks lie on the
  // pieces' edges and the integrals are exact (geometry/MortarSegments.hpp). Measured (1 and 2
  // ranks alike): pressure deviation between -2.6e-12 and +8.5e-13 of p, displacement error
  // 9.5e-13 (lower) and 2.5e-13 (upper) of max |u| — against 20 % and 10 % with node-to-surface
  // rows (below), and 8.8e-4 / 2.5e-4 with the element-based quadrature this replaced.
  const auto [st, errors] = nonMatchingPatch("Mortar");
  if (worldRank() != 0) return;
  EXPECT_LE(st.maxAbsDev, 1e-10);
  EXPECT_LE(errors[0], 1e-10);
  EXPECT_LE(errors[1], 1e-10);
}

TEST(nonmatchingPatch, nodeToSurfaceRowsKeepTheResultantAndReportThePressureDeviation) {
  const auto [st, errors] = nonMatchingPatch("Node To Surface");
  if (worldRank() != 0) return;
  // The deviation is the method's, not the solver's (the node-to-surface equations hold to
  // 1e-13 above): node-to-surface rows fail this patch test (Taylor & Papadopoulos 1991).
  // Measured (1 and 2 ranks alike): pressure deviation from p between -19.6 % (the corner at
  // (2, 2)) and +7.9 %, mean |.| 6.3 %, lower at the edges and corners, higher inside; the
  // displacement error, largest in u_z at the interface (1.5e-5 against p/E1 = 1.4e-4), is
  // 10.5 % of max |u| in the lower body and 7.9 % in the upper one. The bounds below leave
  // about a third on top of these (the problem is deterministic: the same numbers on 1 and
  // 2 ranks), so they catch a change that makes the transfer clearly worse; a wrong weight
  // or normal in the rows themselves breaks the equations above.
  EXPECT_GT(st.maxAbsDev, 1e-3);  // not exact: if this fails, the method became exact here, tighten the bounds
  EXPECT_LE(st.maxAbsDev, 0.25);
  EXPECT_LE(st.meanAbsDev, 0.085);
  EXPECT_LE(errors[0], 0.14);
  EXPECT_LE(errors[1], 0.11);
}

// Hexahedra on both sides, matching: node-to-node rows on the quadrilateral faces reproduce
// the uniform solution to round-off, as on tetrahedra.
TEST(nonmatchingPatch, matchingHexahedraReproduceTheUniformSolution) {
  const auto s = test::solveBoxScene(patchMesh({4, 4, 3}, CellElements::Hexahedron, CellElements::Hexahedron),
                                     patchScene());
  expectConvergedWithExactResultants(s);
  if (worldRank() != 0) return;
  const auto errors = displacementErrors(s);
  const auto st = pressureStats(s);
  std::printf("matching hexahedra: displacement error lower %.3e, upper %.3e; pressure deviation max |.| %.3e\n",
              errors[0], errors[1], st.maxAbsDev);
  EXPECT_LE(errors[0], 1e-10);
  EXPECT_LE(errors[1], 1e-10);
  EXPECT_LE(st.maxAbsDev, 1e-10);
}

// Non-matching quadrilateral faces (bilinear dual basis on the slave, bilinear master shape
// functions), 6-node triangles (the dual of the transformed quadratic basis on the slave,
// quadratic master shape functions), and hexahedra against linear and quadratic tetrahedra and
// prisms: the segment-based mortar rows pass the patch test to round-off, as on triangles.
// Measured (1 and 2 ranks alike): pressure within 1.1e-11 of p (tet10 / hex8; 1.6e-12 and less
// for the linear faces), displacements within 2.2e-12 of max |u| (the element-based quadrature
// before: 1.2e-3 and 1.2e-3).
TEST(nonmatchingPatch, mortarRowsOnQuadrilateralsAndMixedPairsPassThePatchTest) {
  struct Pair {
    const char* name;
    CellElements lower, upper;
  };
  for (const Pair& pair : {Pair{"hex8 / hex8", CellElements::Hexahedron, CellElements::Hexahedron},
                           Pair{"hex8 / tet4", CellElements::Hexahedron, CellElements::KuhnTetrahedra},
                           Pair{"tet4 / hex8", CellElements::KuhnTetrahedra, CellElements::Hexahedron},
                           Pair{"wedge6 / hex8", CellElements::TwoPrisms, CellElements::Hexahedron},
                           Pair{"tet10 / tet10", CellElements::QuadraticKuhnTetrahedra,
                                CellElements::QuadraticKuhnTetrahedra},
                           Pair{"tet10 / hex8", CellElements::QuadraticKuhnTetrahedra, CellElements::Hexahedron},
                           Pair{"hex8 / tet10", CellElements::Hexahedron, CellElements::QuadraticKuhnTetrahedra}}) {
    SCOPED_TRACE(pair.name);
    if (worldRank() == 0) std::printf("slave / master %s:\n", pair.name);
    const auto [st, errors] = nonMatchingPatch("Mortar", pair.lower, pair.upper);
    if (worldRank() != 0) continue;
    EXPECT_LE(st.maxAbsDev, 1e-10);
    EXPECT_LE(errors[0], 1e-10);
    EXPECT_LE(errors[1], 1e-10);
  }
}

namespace {
/// Max |u - u0| / max |u0| over the nodes, u0 the one-material uniform solution (nu p/E x,
/// nu p/E y, -p/E z) of the lower body's material.
double oneMaterialError(const test::SolvedBoxScene& s) {
  double error = 0.0, scale = 0.0;
  const auto& m = s.scene.mesh;
  for (LO n = 0; n < m.numNodes(); ++n) {
    const auto& x = m.coords[n];
    const std::array<double, 3> u0{kNu1 * kP / kE1 * x[0], kNu1 * kP / kE1 * x[1], -kP / kE1 * x[2]};
    for (int c = 0; c < 3; ++c) {
      error = std::max(error, std::abs(s.displacement()[n][c] - u0[c]));
      scale = std::max(scale, std::abs(u0[c]));
    }
  }
  return error / scale;
}

/// The one-material scene (the patch, both bodies of the lower one's material) with `model`.
std::vector<std::string> oneMaterialScene(const std::string& model) {
  return with(patchScene(), {"Materials/upper/Young Modulus=70000", "Materials/upper/Poisson Ratio=0.33",
                             "Contact/Friction Model=" + model, "Contact/F1=0.3", "Contact/F2=0.3"});
}

/// Checks a one-material solve: converged, the uniform solution to round-off, and with Coulomb
/// no tangential force (sum |f_t| <= 1e-10 of the normal resultant: issue 41's acceptance).
void expectOneBody(const test::SolvedBoxScene& s, const std::string& model, const char* pair) {
  if (s.contactProblem) {
    EXPECT_TRUE(s.contact.contact.converged) << s.contact.contact.message;
  } else {
    EXPECT_TRUE(s.linear.converged);
  }
  if (worldRank() != 0) return;
  const double error = oneMaterialError(s);
  std::printf("%s %s, one material: displacement error %.3e of max |u|", model.c_str(), pair, error);
  EXPECT_LE(error, 1e-10);
  if (model == "Coulomb") {
    const auto& i = s.contact.interfaces.at(0);
    std::printf(", sum |f_t| %.3e of the normal resultant", i.frictionForce / i.normalForce);
    EXPECT_NEAR(i.normalForce, kP * kArea, 1e-8 * kP * kArea);
    EXPECT_LE(i.frictionForce, 1e-10 * i.normalForce);
  }
  std::printf("\n");
}

/// Moves the upper body's interface nodes inside the footprint within the plane z = 1 by up to
/// 0.15 of its cell (a fixed pseudo-random pattern), and a 10-node tetrahedron's mid-edge nodes
/// back to their edges' middles: an unstructured master face mesh, still flat and conforming.
void perturbUpperInterface(mesh::Mesh& m, double cell) {
  std::vector<char> upper(m.numNodes(), 0);
  for (LO e = 0; e < m.numElements(); ++e)
    if (m.blockOf(e) == 1)
      for (LO n : m.elementNodes(e)) upper[n] = 1;
  for (LO n = 0; n < m.numNodes(); ++n) {
    auto& x = m.coords[n];
    if (!upper[n] || x[2] != 1.0 || x[0] <= 0.0 || x[0] >= 2.0 || x[1] <= 0.0 || x[1] >= 2.0) continue;
    const double phase = 12.9898 * x[0] + 78.233 * x[1];
    x[0] += 0.15 * cell * std::sin(phase);
    x[1] += 0.15 * cell * std::cos(1.7 * phase);
  }
  static constexpr int kEdge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};  // Exodus TETRA10
  for (LO e = 0; e < m.numElements(); ++e) {
    const auto nodes = m.elementNodes(e);
    if (m.blockOf(e) != 1 || nodes.size() != 10) continue;
    for (int k = 0; k < 6; ++k)
      for (int c = 0; c < 3; ++c)
        m.coords[nodes[4 + k]][c] = 0.5 * (m.coords[nodes[kEdge[k][0]]][c] + m.coords[nodes[kEdge[k][1]]][c]);
  }
}
}  // namespace

// Bonded and Coulomb interfaces between hexahedra and tetrahedra (issue 32), on 1 and 2 ranks:
// with one material in both bodies the bonded pair is one body under a uniform pressure, and so
// is the frictional pair (no lateral mismatch, no tangential force): the uniform solution u =
// (nu p/E x, nu p/E y, -p/E z) to round-off, and no friction force where none acts. Measured
// (1 and 2 ranks alike): displacement errors <= 1.2e-12 of max |u|, sum |f_t| = 0; with the
// element-based quadrature this replaced: 7.1e-4 and 3.0e-4 of the normal resultant (hex8 / tet4).
TEST(nonmatchingPatch, bondedAndCoulombBetweenHexahedraAndTetrahedra) {
  struct Pair {
    const char* name;
    CellElements lower, upper;
  };
  for (const Pair& pair : {Pair{"hex8 / tet4", CellElements::Hexahedron, CellElements::KuhnTetrahedra},
                           Pair{"tet4 / tet4", CellElements::KuhnTetrahedra, CellElements::KuhnTetrahedra},
                           Pair{"tet10 / hex8", CellElements::QuadraticKuhnTetrahedra, CellElements::Hexahedron}})
    for (const std::string model : {"Bonded", "Coulomb"}) {
      SCOPED_TRACE(std::string(pair.name) + " " + model);
      const auto s = test::solveBoxScene(patchMesh({5, 5, 3}, pair.lower, pair.upper), oneMaterialScene(model));
      expectOneBody(s, model, pair.name);
      if (worldRank() == 0) EXPECT_EQ(s.B.contact.size(), s.scene.mesh.nodeSet("lower_z1").nodes.size());
    }
}

// An unstructured master face mesh (the upper body's interface nodes moved within the plane,
// perturbUpperInterface), tetrahedra of both orders: the segment-based mortar rows still pass
// the patch test to round-off, frictionless with two materials and with Coulomb friction on one.
// Measured (1 and 2 ranks alike): pressure within 3.2e-12 of p, displacements within 1.2e-12 of
// max |u|, sum |f_t| = 0 (the element-based quadrature: 7.3e-4, 2.0e-4 and 6.7e-5).
TEST(nonmatchingPatch, unstructuredMasterFacesPassThePatchTest) {
  for (const CellElements fill : {CellElements::KuhnTetrahedra, CellElements::QuadraticKuhnTetrahedra}) {
    const char* name = fill == CellElements::KuhnTetrahedra ? "tet4 / perturbed tet4" : "tet10 / perturbed tet10";
    SCOPED_TRACE(name);
    auto mesh = patchMesh({5, 5, 3}, fill, fill);
    perturbUpperInterface(mesh, 2.0 / 5);
    mesh.validate("test");
    const auto s = test::solveBoxScene(mesh, patchScene());
    expectConvergedWithExactResultants(s);
    if (worldRank() == 0) {
      const auto errors = displacementErrors(s);
      const auto st = pressureStats(s);
      std::printf("%s: displacement error lower %.3e, upper %.3e; pressure deviation max |.| %.3e\n", name,
                  errors[0], errors[1], st.maxAbsDev);
      EXPECT_LE(st.maxAbsDev, 1e-10);
      EXPECT_LE(errors[0], 1e-10);
      EXPECT_LE(errors[1], 1e-10);
    }
    expectOneBody(test::solveBoxScene(mesh, oneMaterialScene("Coulomb")), "Coulomb", name);
  }
}

namespace {
/// The patch's two bodies with the upper one lowered by `overlap` into the lower one (< 0: lifted
/// by a gap), each held at its far face (lower z = 0, upper top) and on the symmetry planes.
std::vector<std::string> heldAtTheirFarFaces(const std::vector<std::string>& base) {
  std::vector<std::string> o;
  for (const auto& option : base)
    if (option.rfind("Loads/", 0) != 0) o.push_back(option);  // no pressure: the overlap loads them
  return with(o, displacementCondition("upper_held", "upper_z1", "z"));
}

mesh::Mesh overlappingMesh(double overlap, CellElements fill) {
  auto m = test::mergeMeshes(test::boxMesh({0, 0, 0}, {2, 2, 1}, {4, 4, 2}, "lower", fill),
                             test::boxMesh({0, 0, 1 - overlap}, {2, 2, 1}, {5, 5, 3}, "upper", fill));
  m.validate("test");
  return m;
}
}  // namespace

// An interference fit as a user meshes it (issue 41): the upper body overlaps the lower by
// delta = 1e-3 and the default Search Distance (1e-6) is far below it. Every slave node lies
// inside the master body and is paired whatever the distance (it was "0 paired", no contact
// force, exit 0 with the bodies inside each other). Both bodies held at their far faces: the
// exact solution is a uniaxial stress, pressure p = delta / (1/E1 + 1/E2) in both (lengths 1),
// in the discrete space of the non-matching meshes: pressure uniform to round-off. Measured (1 and
// 2 ranks alike, tet4 and hex8): p within 2e-12, all 25 slave nodes paired beyond the distance.
// The same at the default Search Distance (0: the slave surface's largest face, which reaches
// the overlap anyway): the same pressure.
TEST(nonmatchingPatch, anInterferenceIsPairedBeyondTheSearchDistance) {
  constexpr double kOverlap = 1e-3;
  const double p = kOverlap / (1.0 / kE1 + 1.0 / kE2);
  for (const CellElements fill : {CellElements::KuhnTetrahedra, CellElements::Hexahedron}) {
    SCOPED_TRACE(fill == CellElements::Hexahedron ? "hex8" : "tet4");
    const auto beyond = heldAtTheirFarFaces(patchScene());  // Search Distance 1e-6
    auto atDefault = beyond;
    atDefault.erase(std::remove(atDefault.begin(), atDefault.end(), std::string("Contact/Search Distance=1e-6")),
                    atDefault.end());
    const auto& defaulted = atDefault;
    for (const auto* scene : {&beyond, &defaulted}) {
      const auto s = test::solveBoxScene(overlappingMesh(kOverlap, fill), *scene);
      EXPECT_TRUE(s.contact.contact.converged) << s.contact.contact.message;
      if (worldRank() != 0) continue;
      ASSERT_EQ(s.B.interfaces.size(), 1u);
      EXPECT_EQ(s.B.interfaces[0].pairedSlaveNodes, 25);
      EXPECT_EQ(s.B.interfaces[0].pairedInside, scene == &beyond ? 25 : 0);
      EXPECT_EQ(s.B.interfaces[0].unpairedSlaveNodes, 0);
      double deviation = 0.0;
      for (LO n : s.scene.mesh.nodeSet("lower_z1").nodes)
        deviation = std::max(deviation, std::abs(s.contact.contactPressure[n] - p) / p);
      std::printf("overlap %g, Search Distance %s: pressure within %.3e of %.6g\n", kOverlap,
                  scene == &beyond ? "1e-6" : "the default", deviation, p);
      EXPECT_LE(deviation, 1e-10);
    }
  }
}

// No run ends "converged" with bodies inside each other (issue 41). The upper body 0.01 above the
// lower one, Search Distance 1e-6 (no pairs), and pressed down by 0.05 at its top: nothing
// holds it, and the solve alone would end converged with every node of the lower surface 0.04
// inside it. Pairing on the reference mesh alone (Solver/Pairing Updates = 0), the check after the
// solve names the interface and the depth, and the run is not converged (exit 3). With Search
// Distance 0.1 the gap is paired and closes: converged, no overlap. With the default pairing
// updates the nodes found inside are paired on the deformed bodies and the problem solved again:
// converged, every slave node paired, the uniaxial pressure 0.04 / (1/E1 + 1/E2) of both to 1e-10.
// (The default Search Distance, a face's size, pairs the gap from the start.)
TEST(nonmatchingPatch, aSlaveNodeInsideTheMasterAfterTheSolveIsNotConverged) {
  auto scene = with(heldAtTheirFarFaces(patchScene()),
                    displacementCondition("upper_held", "upper_z1", "z", "{0, 0, -0.05}"));  // Search Distance 1e-6
  const auto unpaired = test::solveBoxScene(overlappingMesh(-0.01, CellElements::Hexahedron),
                                            with(scene, {"Solver/Pairing Updates=0"}));
  EXPECT_FALSE(unpaired.contact.contact.converged);
  const std::string& message = unpaired.contact.contact.message;
  EXPECT_NE(message.find("contact check after the solve"), std::string::npos) << message;
  EXPECT_NE(message.find("lies 0.04 inside the master body"), std::string::npos) << message;
  EXPECT_NE(message.find("with no contact rows"), std::string::npos) << message;
  const auto paired = test::solveBoxScene(overlappingMesh(-0.01, CellElements::Hexahedron),
                                          with(scene, {"Contact/Search Distance=0.1"}));
  EXPECT_TRUE(paired.contact.contact.converged) << paired.contact.contact.message;
  if (worldRank() == 0) EXPECT_EQ(paired.B.interfaces.at(0).pairedSlaveNodes, 25);
  const auto updated = test::solveBoxScene(overlappingMesh(-0.01, CellElements::Hexahedron), scene);
  EXPECT_TRUE(updated.contact.contact.converged) << updated.contact.contact.message;
  const auto& updates = updated.contact.pairingUpdates;
  ASSERT_FALSE(updates.empty());
  EXPECT_EQ(updates.front().newlyInside, 25);
  EXPECT_TRUE(updates.front().solvedAgain);
  EXPECT_FALSE(updates.back().solvedAgain);
  if (worldRank() != 0) return;
  const double p = 0.04 / (1.0 / kE1 + 1.0 / kE2);
  for (const auto* run : {&paired, &updated}) {
    double deviation = 0.0;
    for (LO n : run->scene.mesh.nodeSet("lower_z1").nodes)
      deviation = std::max(deviation, std::abs(run->contact.contactPressure[n] - p) / p);
    EXPECT_LE(deviation, 1e-10) << (run == &paired ? "Search Distance 0.1" : "pairing updates");
  }
}

// Contact/Interference (issue 41): the same fit on nominal geometry, the bodies touching and the
// overlap given as a parameter, is the geometric overlap's solution (pressure delta / (1/E1 +
// 1/E2) to round-off); in two load steps it follows the ramp: half the pressure in step 1.
TEST(nonmatchingPatch, anInterferenceGivenAsAParameterIsClosedLikeAnOverlap) {
  constexpr double kInterference = 1e-3;
  const double p = kInterference / (1.0 / kE1 + 1.0 / kE2);
  const auto scene = with(heldAtTheirFarFaces(patchScene()), {"Contact/Interference=1e-3", "Load Steps/Number Of Steps=2"});
  const auto s = test::solveBoxScene(overlappingMesh(0.0, CellElements::Hexahedron), scene);
  EXPECT_TRUE(s.contact.contact.converged) << s.contact.contact.message;
  if (worldRank() != 0) return;
  ASSERT_EQ(s.contact.earlierSteps.size(), 1u);
  EXPECT_EQ(s.B.interfaces.at(0).overlappingPairs, 0);  // no geometric overlap: the parameter's
  double last = 0.0, first = 0.0;
  for (LO n : s.scene.mesh.nodeSet("lower_z1").nodes) {
    last = std::max(last, std::abs(s.contact.contactPressure[n] - p) / p);
    first = std::max(first, std::abs(s.contact.earlierSteps[0].contactPressure[n] - p / 2) / p);
  }
  std::printf("Interference %g in 2 steps: pressure within %.3e (step 1: of p/2) and %.3e (step 2: of p = %.6g)\n",
              kInterference, first, last, p);
  EXPECT_LE(first, 1e-10);
  EXPECT_LE(last, 1e-10);
}

// A contact surface of interior faces (issue 44: accepted, and the solve ended as exit 3 with a
// friction-capacity message): the faces of the lower body at z = 0.5, inside it, given as the
// master surface, are an input error naming the interface, the set and a face.
TEST(nonmatchingPatch, aContactSurfaceOfInteriorFacesIsAnInputError) {
  auto mesh = patchMesh({5, 5, 3}, CellElements::Hexahedron, CellElements::Hexahedron);
  mesh::SideSet inside{"lower_middle", 99, {}, {}};
  for (LO e = 0; e < mesh.numElements(); ++e) {
    bool upperLayer = false;  // the lower body's cells in 0.5 <= z <= 1: their bottom faces
    for (LO n : mesh.elementNodes(e)) upperLayer = upperLayer || mesh.coords[n][2] == 1.0;
    if (mesh.blockOf(e) != 0 || !upperLayer) continue;
    for (int side = 0; side < mesh.numSides(e); ++side) {
      const mesh::FaceNodes face = mesh.faceNodes(e, side);
      bool atMiddle = true;
      for (LO n : face.vertices()) atMiddle = atMiddle && mesh.coords[n][2] == 0.5;
      if (!atMiddle) continue;
      inside.elements.push_back(e);
      inside.sides.push_back(side);
    }
  }
  ASSERT_EQ(inside.elements.size(), 16u);
  mesh.sideSets.push_back(inside);
  try {
    test::solveBoxScene(mesh, with(patchScene(), {"Contact/Slave Side Set=upper_z0", "Contact/Master Side Set=lower_middle"}));
    FAIL() << "an interior contact surface was accepted";
  } catch (const core::InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("in side set \"lower_middle\" is interior to the mesh"), std::string::npos) << message;
  }
}
