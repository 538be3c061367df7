// Consistent loads (paper Section 2): a constant traction p on a face set has resultant
// p * area and moment (area * centroid) x p; a volume force b has resultant b * volume; and
// each face / element is loaded by exactly one subdomain.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "FemTestSupport.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {
const fem::Material kAluminium{2.792e4, 2.593e4}, kSteel{6.360e4, 8.301e4};
const std::vector<fem::Material> kMaterials{kAluminium, kSteel};
}  // namespace

TEST(Loads, tractionResultantAndMomentMatchTheFace) {
  // Box 3 x 2 x 4 cubes of h = 0.5 with jittered interior: faces planar, areas known.
  const double h = 0.5;
  const mesh::Mesh box = fem::testing::structuredBox(3, 2, 4, h, 0.15, 11);
  const double L[3] = {3 * h, 2 * h, 4 * h};
  const double p[3] = {1.5, -2.0, 20.0};
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (int axis = 0; axis < 3; ++axis)
    for (int end = 0; end < 2; ++end) {
      fem::Loads loads;
      loads.tractions = {{names[axis][end], {p[0], p[1], p[2]}}};
      const auto sys = fem::assembleGlobal(box, {kSteel}, loads);
      const double area = L[(axis + 1) % 3] * L[(axis + 2) % 3];
      double centroid[3] = {L[0] / 2, L[1] / 2, L[2] / 2};
      centroid[axis] = end == 0 ? 0.0 : L[axis];
      double force[3] = {0, 0, 0}, moment[3] = {0, 0, 0};
      for (LO a = 0; a < box.numNodes(); ++a) {
        const auto& x = box.coords[a];
        const double* f = &sys.f[3 * a];
        for (int c = 0; c < 3; ++c) force[c] += f[c];
        moment[0] += x[1] * f[2] - x[2] * f[1];
        moment[1] += x[2] * f[0] - x[0] * f[2];
        moment[2] += x[0] * f[1] - x[1] * f[0];
      }
      const double expectedMoment[3] = {area * (centroid[1] * p[2] - centroid[2] * p[1]),
                                        area * (centroid[2] * p[0] - centroid[0] * p[2]),
                                        area * (centroid[0] * p[1] - centroid[1] * p[0])};
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(force[c], p[c] * area, 1e-12 * 20.0 * area) << names[axis][end] << " component " << c;
        EXPECT_NEAR(moment[c], expectedMoment[c], 1e-12 * 20.0 * area * 2.0) << names[axis][end] << " moment " << c;
      }
    }
}

TEST(Loads, subdomainLoadsSumToPTimesAreaAndToTheGlobalLoad) {
  const mesh::TwoBricksSpec spec{{4, 2, 2}, 2};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  struct Case {
    const char* set;
    double area;  // TwoBricks.hpp: brick faces in mm^2
  };
  for (const Case& c : {Case{"load_end", 100.0}, Case{"load_top", 200.0}, Case{"contact_aluminium", 200.0},
                        Case{"dirichlet_steel", 100.0}}) {
    fem::Loads loads;
    loads.tractions = {{c.set, {1.0, -2.0, 20.0}}};
    const auto global = fem::assembleGlobal(mesh, kMaterials, loads);
    std::vector<double> scattered(global.f.size(), 0.0);
    double total[3] = {0, 0, 0};
    for (const auto& s : d.subdomains) {
      const auto sys = fem::assembleSubdomain(mesh, s, kMaterials, loads);
      for (LO i = 0; i < sys.K.n; ++i) {
        total[i % 3] += sys.f[i];
        scattered[3 * s.nodes[i / 3] + i % 3] += sys.f[i];
      }
    }
    const double expected[3] = {1.0 * c.area, -2.0 * c.area, 20.0 * c.area};
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(total[k], expected[k], 1e-12 * 20.0 * c.area) << c.set << " " << k;
    for (size_t i = 0; i < scattered.size(); ++i) EXPECT_NEAR(scattered[i], global.f[i], 1e-14 * 20.0 * c.area);
  }
}

TEST(Loads, volumeForceResultantIsDensityTimesVolumePerBody) {
  const mesh::TwoBricksSpec spec{{2, 1, 1}, 3};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  fem::Loads gravity;
  gravity.volumeForce = {{0.5, 0.0, -1.0}, {0.0, 3.0, -2.0}};  // per block: aluminium, steel
  double total[3] = {0, 0, 0};
  for (const auto& s : d.subdomains) {
    const auto sys = fem::assembleSubdomain(mesh, s, kMaterials, gravity);
    for (LO i = 0; i < sys.K.n; ++i) total[i % 3] += sys.f[i];
  }
  const double volume = 2000.0;  // each brick is 20 x 10 x 10
  const double expected[3] = {0.5 * volume, 3.0 * volume, -3.0 * volume};
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(total[c], expected[c], 1e-12 * 3.0 * 2 * volume) << c;
  // Box with jittered interior: total volume still exact.
  const mesh::Mesh box = fem::testing::structuredBox(2, 3, 2, 0.75, 0.15, 5);
  fem::Loads b;
  b.volumeForce = {{1.0, 2.0, 3.0}};
  const auto sys = fem::assembleGlobal(box, {kSteel}, b);
  const double boxVolume = 2 * 3 * 2 * 0.75 * 0.75 * 0.75;
  double fz[3] = {0, 0, 0};
  for (LO i = 0; i < sys.K.n; ++i) fz[i % 3] += sys.f[i];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(fz[c], (c + 1.0) * boxVolume, 1e-12 * 3.0 * boxVolume);
}

TEST(Loads, pressureOnACurvedFacePushesAlongItsNormalWithTheProjectedAreaResultant) {
  // Box [0, 2] x [0, 0.5] x [0, 1] whose top bulges into the arc z = 1 + sqrt(R^2 - (x - 1)^2) -
  // sqrt(R^2 - 1), R = 1.5 (the nodes below follow in proportion to their height). A pressure q
  // on the top pushes every face along its inward normal: the resultant is -q times the
  // projected area 2 x 0.5 along z and nothing along x and y (the arc is symmetric, its ends at
  // one height), exactly for the faceted surface too (its vector area is fixed by its edge).
  mesh::Mesh box = fem::testing::structuredBox(8, 2, 4, 0.25);
  constexpr double kR = 1.5, kQ = 3.0;
  for (auto& x : box.coords) x[2] += x[2] * (std::sqrt(kR * kR - (x[0] - 1.0) * (x[0] - 1.0)) - std::sqrt(kR * kR - 1.0));
  fem::Loads loads;
  loads.tractions = {{"zmax", {0.0, 0.0, 0.0}, kQ}};
  const auto sys = fem::assembleGlobal(box, {kSteel}, loads);
  double force[3] = {0, 0, 0};
  for (LO a = 0; a < box.numNodes(); ++a)
    for (int c = 0; c < 3; ++c) force[c] += sys.f[3 * a + c];
  EXPECT_NEAR(force[0], 0.0, 1e-12 * kQ);
  EXPECT_NEAR(force[1], 0.0, 1e-12 * kQ);
  EXPECT_NEAR(force[2], -kQ * 2.0 * 0.5, 1e-12 * kQ);
  // Off the crest the face tilts, and the load with it, towards the crest: an x-component of
  // the sign of 1 - x.
  for (LO a = 0; a < box.numNodes(); ++a) {
    const double dx = box.coords[a][0] - 1.0;
    if (sys.f[3 * a + 2] == 0.0 || std::abs(dx) < 0.3) continue;
    EXPECT_LT(sys.f[3 * a] * dx, 0.0) << "node " << a;
  }
  // On a flat face a pressure is the traction -q n: the same loads to round-off.
  fem::Loads pressure, traction;
  pressure.tractions = {{"zmin", {0.0, 0.0, 0.0}, kQ}};
  traction.tractions = {{"zmin", {0.0, 0.0, kQ}}};  // the bottom's outward normal is -z
  const auto byPressure = fem::assembleGlobal(box, {kSteel}, pressure);
  const auto byTraction = fem::assembleGlobal(box, {kSteel}, traction);
  for (size_t i = 0; i < byPressure.f.size(); ++i) EXPECT_NEAR(byPressure.f[i], byTraction.f[i], 1e-14 * kQ);
}
