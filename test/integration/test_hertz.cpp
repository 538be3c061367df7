// Hertz validation on separately meshed, non-matching gmsh bodies (input/hertz_*.xml,
// VALIDATION.md): the nodal contact pressure (normal force / tributary area, the driver's
// contact_pressure) against Hertz's p0 and contact half-width b / radius a, and the force
// balance, frictionless and with Coulomb friction F = 0.2 (equal-sign loading: Hertz holds up
// to Goodman's small correction for dissimilar materials). The tolerances are the issue's: the
// peak within 5 % of p0, the edge of the contact zone within one (slave) element of Hertz's,
// the resultant of the contact forces equal to the applied load to 1e-6.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "RunCommand.hpp"
#include "TestPaths.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/mesh/ShapeFunctions.hpp"

using tribos::test::quote;
using tribos::test::runCommand;

namespace {
constexpr double kPi = 3.14159265358979323846;
// VALIDATION.md: steel R = 10 on aluminium.
const double kEStar = 1.0 / ((1 - 0.3 * 0.3) / 210000.0 + (1 - 0.33 * 0.33) / 70000.0);
constexpr double kRadius = 10.0;

struct HertzCase {
  std::string scene;        ///< input/<scene>.xml
  std::string friction;     ///< Contact/Friction Model
  std::string loadedSet;    ///< side set carrying the traction
  double traction;          ///< |t_z| on it
  double p0, edge;          ///< Hertz: peak pressure and half-width b or radius a
  bool line;                ///< cylinder (distance from the axis x = 0) or sphere (from the z axis)
  double slaveElement;      ///< element size of the slave (block) surface at the contact
  std::string mesh = {};    ///< input/meshes/<mesh>.exo in place of the scene's mesh; empty: the scene's
};

/// The area of a side set's faces as the load integrates it: a 6-node triangle with its curved
/// edges (the rim of the loaded face), by the face's quadrature rule.
double faceArea(const tribos::mesh::Mesh& mesh, const std::string& sideSet) {
  using namespace tribos::mesh;
  const auto& set = mesh.sideSet(sideSet);
  double area = 0.0;
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const FaceNodes face = mesh.faceNodes(set.elements[f], set.sides[f]);
    const FaceType type = faceType(face.numVertices, face.numNodes);
    std::array<double, 3> x[kMaxFaceNodes];
    for (int k = 0; k < face.numNodes; ++k) x[k] = mesh.coords[face.node[k]];
    for (const auto& q : faceRule(type)) area += q.weight * faceGeometry(type, x, q.xi[0], q.xi[1]).areaElement();
  }
  return area;
}

void checkHertz(const HertzCase& c) {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_hertz_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto exo = (dir / "result.exo").string(), summary = (dir / "summary.json").string();
  const auto root = tribos::test::sourceDir();
  const std::string meshOption =
      c.mesh.empty() ? "" : " --set " + quote("Mesh/File=" + root + "/input/meshes/" + c.mesh + ".exo");
  const auto run = runCommand(std::string(TRIBOS_DRIVER) + " --input " + quote(root + "/input/" + c.scene + ".xml") +
                              " --set 'Contact/Friction Model=" + c.friction + "' --set Solver/Verbose=false --set Solver/Tolerance=1e-7" +
                              meshOption + " --output " + quote(exo) + " --summary " + quote(summary));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(summary);
  const auto j = nlohmann::json::parse(in);
  const auto data = tribos::mesh::readExodus(exo);
  const auto& mesh = data.mesh;

  // Force balance: the vertical resultant of the contact forces on the master (curved) body
  // equals the load applied to it (computed from the faceted loaded face). Its horizontal
  // resultant is not zero in a half / quarter model: the symmetry planes carry it.
  const double load = c.traction * faceArea(mesh, c.loadedSet);
  const auto force = j["total_contact_force"];
  EXPECT_NEAR(force[2].get<double>(), load, 1e-6 * load) << "the master body's load";

  // The nodal pressure on the slave surface: peak and the edge of the contact zone.
  const std::vector<double>* pressure = nullptr;
  for (const auto& f : data.steps.back().nodal)
    if (f.name == "contact_pressure") pressure = &f.values;
  ASSERT_NE(pressure, nullptr);
  double peak = 0.0, lastIn = 0.0, firstOut = 1e300;
  const double noise = 1e-6 * c.p0;  // below: the iterative solver's round-off, not contact
  for (auto n : mesh.nodeSet("block_contact").nodes) {
    const auto& x = mesh.coords[n];
    const double r = c.line ? std::abs(x[0]) : std::hypot(x[0], x[1]);
    const double p = (*pressure)[n];
    peak = std::max(peak, p);
    if (p > noise) lastIn = std::max(lastIn, r);
  }
  for (auto n : mesh.nodeSet("block_contact").nodes) {  // first node out beyond the last one in
    const auto& x = mesh.coords[n];
    const double r = c.line ? std::abs(x[0]) : std::hypot(x[0], x[1]);
    if ((*pressure)[n] <= noise && r > lastIn) firstOut = std::min(firstOut, r);
  }
  std::printf("%s%s%s, %s: peak %.1f vs p0 %.1f (%+.2f %%), edge in [%.4f, %.4f] vs %.4f, %lld PFP applications\n",
              c.scene.c_str(), c.mesh.empty() ? "" : " on ", c.mesh.c_str(), c.friction.c_str(), peak, c.p0, 100.0 * (peak / c.p0 - 1.0), lastIn, firstOut, c.edge,
              j["pfp_applications"].get<long long>());
  EXPECT_NEAR(peak, c.p0, 0.05 * c.p0);
  EXPECT_LE(lastIn, c.edge + c.slaveElement) << "contact reaches beyond Hertz's zone by more than an element";
  EXPECT_GE(firstOut, c.edge - c.slaveElement) << "contact ends short of Hertz's zone by more than an element";
  std::filesystem::remove_all(dir);
}

// Line contact, plane strain: P = 4000 N/mm on the full cylinder (the half model carries 2000
// N/mm: 200 MPa on the top face x in [0, R]); hc = 0.1, block elements 1.3 hc.
HertzCase cylinder(const std::string& friction) {
  const double P = 4000.0, b = std::sqrt(4.0 * P * kRadius / (kPi * kEStar));
  return {"hertz_cylinder", friction, "cylinder_top", 200.0, 2.0 * P / (kPi * b), b, true, 0.13};
}

// Point contact: P chosen for a = 1 mm; the quarter model carries P/4 as P / (pi R^2) on its
// top face; hc = 0.075, block elements 1.3 hc.
HertzCase sphere(const std::string& friction) {
  const double a = 1.0, P = 4.0 * kEStar * a * a * a / (3.0 * kRadius);
  return {"hertz_sphere", friction, "sphere_top", P / (kPi * kRadius * kRadius), 3.0 * P / (2.0 * kPi * a * a), a,
          false, 0.0975};
}
}  // namespace

// Hexahedra (issue 32): the line contact on both bodies meshed with 8-node hexahedra at
// hc = 0.4 (input/meshes/hertz_cylinder_hex_h0.4.exo, 645 nodes; block elements 0.46-0.48 at
// the contact), where linear tetrahedra of the same size miss p0 by 7.6 % (doc/elements.md);
// the point contact with a hexahedral block (slave quadrilaterals) under the tetrahedral
// sphere, the block's first cell 0.20 (hertz_sphere_hexblock_h0.15.exo).
namespace {
HertzCase withMesh(HertzCase c, const std::string& mesh, double slaveElement) {
  c.mesh = mesh;
  c.slaveElement = slaveElement;
  return c;
}
}  // namespace
TEST(hertz, cylinderHexahedraFrictionless) { checkHertz(withMesh(cylinder("None"), "hertz_cylinder_hex_h0.4", 0.48)); }
TEST(hertz, cylinderHexahedraCoulomb) { checkHertz(withMesh(cylinder("Coulomb"), "hertz_cylinder_hex_h0.4", 0.48)); }
TEST(hertz, sphereHexahedralBlockFrictionless) {
  checkHertz(withMesh(sphere("None"), "hertz_sphere_hexblock_h0.15", 0.22));
}
// 10-node tetrahedra (issue 32): 6-node contact faces, the dual basis of the transformed
// quadratic basis on the slave; the gmsh meshes of input/hertz_*.xml at hc = 0.4 (cylinder)
// and 0.3 (sphere) with -order 2, where linear tetrahedra miss p0 by +7.6 % and -4.3 %.
TEST(hertz, cylinderQuadraticTetrahedraFrictionless) {
  checkHertz(withMesh(cylinder("None"), "hertz_cylinder_tet10_h0.4", 0.52));
}
TEST(hertz, cylinderQuadraticTetrahedraCoulomb) {
  checkHertz(withMesh(cylinder("Coulomb"), "hertz_cylinder_tet10_h0.4", 0.52));
}
TEST(hertz, sphereQuadraticTetrahedraFrictionless) {
  checkHertz(withMesh(sphere("None"), "hertz_sphere_tet10_h0.3", 0.39));
}

TEST(hertz, cylinderFrictionless) { checkHertz(cylinder("None")); }
TEST(hertz, cylinderCoulomb) { checkHertz(cylinder("Coulomb")); }
TEST(hertz, sphereFrictionless) { checkHertz(sphere("None")); }
TEST(hertz, sphereCoulomb) { checkHertz(sphere("Coulomb")); }

// A loose tolerance must still give a solution: at eps = 1e-2 the KKT acceptance tolerance
// max(100 eps, 1e-8) is 1, and when the status tests used it too every node counted as out of
// contact, nothing held the cylinder's rigid motion and the run ended "no equilibrium found"
// (error 147 %). The status tests are now capped at 1e-3; the residuals must meet eps itself.
TEST(hertz, cylinderCoulombAtALooseToleranceConverges) {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_hertz_loose_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto summary = (dir / "summary.json").string();
  const auto root = tribos::test::sourceDir();
  const auto run = runCommand(std::string(TRIBOS_DRIVER) + " --input " + quote(root + "/input/hertz_cylinder.xml") +
                              " --set 'Contact/Friction Model=Coulomb' --set Solver/Verbose=false" +
                              " --set Solver/Tolerance=1e-2 --summary " + quote(summary));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(summary);
  const auto j = nlohmann::json::parse(in);
  EXPECT_TRUE(j["converged"].get<bool>()) << j["message"];
  EXPECT_GT(j["contact_nodes"]["stick"].get<int>() + j["contact_nodes"]["slip"].get<int>(), 0);
  for (const auto& [name, value] : j["kkt"].items())
    if (name != "tolerance") EXPECT_LE(value.get<double>(), 1e-2) << name;
  std::filesystem::remove_all(dir);
}
