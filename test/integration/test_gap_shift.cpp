// An initial gap that closes is the zero-gap problem shifted by a rigid motion. A box held
// by contact and friction only (no Dirichlet row of its own) is pressed by a uniform
// traction onto a clamped box: (a) touching, (b) lifted by d. In (b) the normal rows read
// N u <= d, and d = N R t for the rigid translation t = (0, 0, -d) of the upper box, a
// direction in range(G^T) that the T-FETI projector removes from the dual problem: the
// multipliers are the same and the upper box's rigid-body coefficients take up t. So
// u_b = u_a - (0, 0, d) on the upper box, u_b = u_a on the lower one, and every contact node
// has the same status. Both meshes have the same cells and numbering (only the upper box's
// z is shifted), so the METIS decomposition is the same too. ctest runs this on 1 and 2 ranks.
// Measured (Solver/Tolerance 1e-10, max |u_a| = 1.72e-4, d = 58 max |u_a|): the upper box's
// u_b - u_a + (0, 0, d) is 8.2e-11 of max |u_a| on 1 rank (1.0e-10 on 2), the lower box's
// u_b - u_a 1.1e-10 (1.1e-10); statuses (no contact, stick, slip) = (0, 16, 9) in both, the
// stick zone in the middle fixing the upper box laterally; total normal force 40 = 10 x 4.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "BoxMesh.hpp"
#include "BoxScene.hpp"

namespace {
using namespace tribos;
using test::with;
using test::worldRank;

constexpr double kLift = 0.01;

/// Lower body [0,2]^2 x [0,1] with 4x4x2 cells, upper body [0,2]^2 x [1+lift, 2+lift] with 4x4x3.
mesh::Mesh stackedBoxes(double lift) {
  auto m = test::mergeMeshes(test::boxMesh({0, 0, 0}, {2, 2, 1}, {4, 4, 2}, "lower"),
                             test::boxMesh({0, 0, 1 + lift}, {2, 2, 1}, {4, 4, 3}, "upper"));
  m.validate("test");
  return m;
}

std::vector<std::string> pressedBox(const std::string& frictionModel) {
  return {"Mesh/Subdomains=4",
          "Materials/lower/Young Modulus=70000", "Materials/lower/Poisson Ratio=0.33",
          "Materials/upper/Young Modulus=210000", "Materials/upper/Poisson Ratio=0.3",
          "Loads/pressure/Side Set=upper_z1", "Loads/pressure/Traction={0, 0, -10}",
          "Boundary/Dirichlet Node Sets={lower_z0}",  // clamped, all components
          "Contact/Friction Model=" + frictionModel, "Contact/F1=0.3", "Contact/F2=0.3",
          "Contact/Slave Side Set=lower_z1", "Contact/Master Side Set=upper_z0",
          "Contact/Search Distance=0.5",
          "Solver/Tolerance=1e-10", "Solver/Verbose=false"};
}

/// The rigid motions of the bodies that no row of B restrains, in words.
std::vector<std::string> freeMotions(const mesh::Mesh& mesh, const std::vector<std::string>& overrides) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const test::ExodusScene input(mesh, overrides);
  const auto scene = input.build();
  const auto B = feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), size);
  std::vector<std::string> motions;
  for (const auto& m : feti::freeRigidMotions(scene.mesh, scene.decomposition, B)) motions.push_back(m.description);
  return motions;
}
}  // namespace

TEST(gapShift, liftedBoxHeldByFrictionIsTheTouchingSolutionShifted) {
  const auto touching = stackedBoxes(0.0), lifted = stackedBoxes(kLift);
  // With friction the tangential rows hold the upper box laterally (the solvability check
  // treats every row as bilateral); without, its sliding and spinning are free.
  EXPECT_TRUE(freeMotions(lifted, pressedBox("Coulomb")).empty());
  const auto frictionless = freeMotions(lifted, pressedBox("None"));
  ASSERT_EQ(frictionless.size(), 3u);
  EXPECT_EQ(frictionless[0], "body \"upper\": translation x");
  EXPECT_EQ(frictionless[1], "body \"upper\": translation y");
  EXPECT_EQ(frictionless[2], "body \"upper\": rotation about z");

  const auto a = test::solveBoxScene(touching, pressedBox("Coulomb"));
  const auto b = test::solveBoxScene(lifted, pressedBox("Coulomb"));
  EXPECT_TRUE(a.contact.contact.converged) << a.contact.contact.message;
  EXPECT_TRUE(b.contact.contact.converged) << b.contact.contact.message;
  if (worldRank() != 0) return;
  ASSERT_EQ(a.B.contact.size(), 25u);  // every slave node of the 4x4 face paired
  ASSERT_EQ(b.B.contact.size(), 25u);
  for (size_t i = 0; i < a.B.contact.size(); ++i) {
    EXPECT_NEAR(a.B.contact[i].gap, 0.0, 1e-14);
    EXPECT_NEAR(b.B.contact[i].gap, kLift, 1e-14);
  }
  const LO lowerNodes = 5 * 5 * 3;  // mergeMeshes numbers the lower box's nodes first
  const auto& ua = a.displacement();
  const auto& ub = b.displacement();
  ASSERT_EQ(ua.size(), ub.size());
  double scale = 0.0, lowerDiff = 0.0, upperDiff = 0.0;
  for (LO n = 0; n < static_cast<LO>(ua.size()); ++n)
    for (int c = 0; c < 3; ++c) {
      scale = std::max(scale, std::abs(ua[n][c]));
      const double shift = (n >= lowerNodes && c == 2) ? -kLift : 0.0;
      double& diff = n >= lowerNodes ? upperDiff : lowerDiff;
      diff = std::max(diff, std::abs(ub[n][c] - (ua[n][c] + shift)));
    }
  const auto& ra = a.contact.contact;
  const auto& rb = b.contact.contact;
  std::printf("lifted by d = %g: max |u_b - u_a + (0, 0, d)| / max |u_a| = %.2e (upper box), max |u_b - u_a| / "
              "max |u_a| = %.2e (lower box), max |u_a| = %.4e; status (no contact, stick, slip) (%d, %d, %d) and "
              "(%d, %d, %d); total normal force %.10g and %.10g\n",
              kLift, upperDiff / scale, lowerDiff / scale, scale, ra.statusCounts[0], ra.statusCounts[1],
              ra.statusCounts[2], rb.statusCounts[0], rb.statusCounts[1], rb.statusCounts[2],
              a.contact.totalNormalForce, b.contact.totalNormalForce);
  EXPECT_LE(upperDiff, 1e-8 * scale);
  EXPECT_LE(lowerDiff, 1e-8 * scale);
  EXPECT_EQ(ra.statusCounts, rb.statusCounts);
  int differentStatus = 0;
  for (size_t n = 0; n < a.contact.contactStatus.size(); ++n)
    differentStatus += a.contact.contactStatus[n] != b.contact.contactStatus[n];
  EXPECT_EQ(differentStatus, 0);
  // The upper box rests on the lower one with the load's resultant, 10 * 2 * 2.
  EXPECT_NEAR(a.contact.totalNormalForce, 40.0, 1e-8 * 40.0);
  EXPECT_NEAR(b.contact.totalNormalForce, 40.0, 1e-8 * 40.0);
}
