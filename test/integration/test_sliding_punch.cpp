// A punch slid along a plate over several elements in load steps (issue 41): the contact
// forces must follow the punch. Plate [0,4] x [0,1] x [0,1] (16 x 4 x 4 hexahedra, held at its
// bottom), punch [0.5,1.5] x [0,1] x [1,1.5] (4 x 4 x 2 hexahedra, the slave), symmetry plane
// y = 0, frictionless. Step 1 presses the punch's top down by 0.01; steps 2-5 slide it along x
// by 1, four of the plate's elements, still pressed. The plate carries only the contact forces,
// vertical (frictionless): by its moment balance the vertical reactions under it have their
// centroid where the contact forces act on it. The punch's footprint is centred at x = 1 before
// the slide and at x = 2 after it.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "BoxMesh.hpp"
#include "BoxScene.hpp"

namespace tribos {
namespace {

using test::CellElements;
using test::displacementCondition;
using test::with;

/// The punch's left end at x = `at`.
mesh::Mesh punchOnPlate(double at = 0.5) {
  auto m = test::mergeMeshes(test::boxMesh({0, 0, 0}, {4, 1, 1}, {16, 4, 4}, "plate", CellElements::Hexahedron),
                             test::boxMesh({at, 0, 1}, {1, 1, 0.5}, {4, 4, 2}, "punch", CellElements::Hexahedron));
  m.validate("test");
  return m;
}

std::vector<std::string> slidingScene(int pairingUpdates) {
  std::vector<std::string> o = {
      "Mesh/Subdomains=4",
      "Materials/plate/Young Modulus=70000", "Materials/plate/Poisson Ratio=0.33",
      "Materials/punch/Young Modulus=210000", "Materials/punch/Poisson Ratio=0.3",
      "Contact/Friction Model=None", "Contact/Slave Side Set=punch_z0", "Contact/Master Side Set=plate_z1",
      "Contact/Search Distance=0.01",
      "Load Steps/Number Of Steps=5", "Load Steps/slide/Factors={0, 0.25, 0.5, 0.75, 1}",
      "Load Steps/press/Factors={1, 1, 1, 1, 1}",
      "Solver/Tolerance=1e-10", "Solver/Verbose=false",
      "Solver/Pairing Updates=" + std::to_string(pairingUpdates)};
  o = with(o, displacementCondition("support", "plate_z0", "xyz"));
  o = with(o, displacementCondition("plate_symmetry", "plate_y0", "y"));
  o = with(o, displacementCondition("punch_symmetry", "punch_y0", "y"));
  o = with(o, displacementCondition("press", "punch_z1", "z", "{0, 0, -0.01}"));
  return with(o, displacementCondition("slide", "punch_z1", "x", "{1, 0, 0}"));
}

/// The x of the centroid of the vertical reactions under the plate (rank 0), and their sum.
std::array<double, 2> reactionCentroid(const test::SolvedBoxScene& s) {
  double moment = 0.0, total = 0.0;
  for (LO n : s.scene.mesh.nodeSet("plate_z0").nodes) {
    moment += s.contact.reaction[n][2] * s.scene.mesh.coords[n][0];
    total += s.contact.reaction[n][2];
  }
  return {moment / total, total};
}

int worldRank() {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

TEST(slidingPunch, theContactForcesFollowThePunch) {
  const auto followed = test::solveBoxScene(punchOnPlate(), slidingScene(3));
  ASSERT_TRUE(followed.contact.contact.converged) << followed.contact.contact.message;
  ASSERT_EQ(followed.contact.steps.size(), 5u);
  const auto& updates = followed.contact.pairingUpdates;
  ASSERT_GE(updates.size(), 2u);
  EXPECT_GT(updates.front().movedOn, 0) << "no node was seen to slide past its master nodes";
  EXPECT_FALSE(updates.back().solvedAgain);
  // On the reference pairing the punch's rows hold it to the faces it started on: the check
  // after the solve finds it inside the plate, off those faces, and the run is not converged.
  const auto fixed = test::solveBoxScene(punchOnPlate(), slidingScene(0));
  EXPECT_FALSE(fixed.contact.contact.converged);
  EXPECT_NE(fixed.contact.contact.message.find("having slid off the master faces"), std::string::npos)
      << fixed.contact.contact.message;
  // Frictionless and elastic, the end state does not depend on the path: the punch meshed where
  // the slide ends and pressed alone, one step, every node paired from the start.
  auto there = slidingScene(0);
  there.erase(std::remove_if(there.begin(), there.end(), [](const std::string& o) { return o.rfind("Load Steps", 0) == 0; }),
              there.end());
  std::replace(there.begin(), there.end(), std::string("Boundary/slide/Displacement={1, 0, 0}"),
               std::string("Boundary/slide/Displacement={0, 0, 0}"));  // held along x where it is
  const auto pressed = test::solveBoxScene(punchOnPlate(1.5), there);
  ASSERT_TRUE(pressed.contact.contact.converged) << pressed.contact.contact.message;
  if (worldRank() != 0) return;
  const auto centroid = reactionCentroid(followed), reference = reactionCentroid(pressed);
  const auto& F = followed.contact.totalContactForce;
  std::printf("vertical reactions under the plate after the slide: centroid x %.4f, sum %.6g (%zu pairing checks); "
              "contact force (%.6g, %.6g, %.6g)\n",
              centroid[0], centroid[1], updates.size(), F[0], F[1], F[2]);
  std::printf("the punch pressed where the slide ends: centroid x %.4f, sum %.6g\n", reference[0], reference[1]);
  EXPECT_NEAR(centroid[0], 2.0, 0.05) << "the contact forces stayed behind the punch";
  EXPECT_NEAR(centroid[0], reference[0], 0.02);
  EXPECT_NEAR(centroid[1] / reference[1], 1.0, 0.02);
}

}  // namespace
}  // namespace tribos
