// Components eliminated from a floating subdomain (FETI/Displacement Conditions = Eliminated,
// feti/src/EliminatedComponents.hpp): u_y = 0 on one face of a brick subdomain leaves the
// rigid modes that keep that face in its plane (translations x and z, rotation about y).
#include <gtest/gtest.h>

#include <cmath>

#include "EliminatedComponents.hpp"
#include "RandomSpd.hpp"
#include "tribos/feti/SubdomainSolver.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {
struct Piece {
  fem::SubdomainSystem system, original;
  std::vector<std::array<double, 3>> coords;
  std::vector<LO> dofs;  // the y components of the nodes on the face y = min
};

Piece brickWithFaceHeldInY(int hOverH = 2) {
  const mesh::TwoBricksSpec spec{{2, 1, 1}, hOverH};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  Piece p;
  p.system = fem::assembleSubdomain(mesh, d.subdomains[0], {{2.792e4, 2.593e4}, {6.360e4, 8.301e4}}, {});
  for (LO n : d.subdomains[0].nodes) p.coords.push_back(mesh.coords[n]);
  double yMin = 1e300;
  for (const auto& x : p.coords) yMin = std::min(yMin, x[1]);
  for (size_t k = 0; k < p.coords.size(); ++k)
    if (p.coords[k][1] == yMin) p.dofs.push_back(static_cast<LO>(3 * k + 1));
  p.system.f = test::randomVector(p.system.f.size(), 7);
  p.original = p.system;
  return p;
}
}  // namespace

TEST(EliminatedComponents, threeModesLeftOrthonormalVanishingThereInTheKernel) {
  Piece p = brickWithFaceHeldInY();
  int live = 0;
  const auto rows = feti::eliminateComponents(p.system, p.dofs, live);
  ASSERT_EQ(live, 3);
  const LO n = p.system.K.n;
  const auto& R = p.system.R;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) {
      double dot = 0.0;
      for (LO k = 0; k < n; ++k) dot += R[static_cast<size_t>(i) * n + k] * R[static_cast<size_t>(j) * n + k];
      EXPECT_NEAR(dot, i == j && i < live ? 1.0 : 0.0, 1e-12) << i << " " << j;
    }
  std::vector<double> KR(n);
  for (int j = 0; j < live; ++j) {
    const double* r = &R[static_cast<size_t>(j) * n];
    for (LO d : p.dofs) EXPECT_EQ(r[d], 0.0);
    p.system.K.apply(r, KR.data());
    double largest = 0.0;
    for (double v : KR) largest = std::max(largest, std::abs(v));
    EXPECT_LE(largest, 1e-9 * p.system.K.frobeniusNorm());
  }
  // The eliminated rows and columns keep their diagonal only; the loads there are 0.
  for (LO d : p.dofs) {
    EXPECT_EQ(p.system.f[d], 0.0);
    for (LO i = 0; i < n; ++i) {
      EXPECT_EQ(p.system.K.at(d, i), i == d ? p.original.K.at(d, d) : 0.0);
      EXPECT_EQ(p.system.K.at(i, d), i == d ? p.original.K.at(d, d) : 0.0);
    }
  }
  EXPECT_EQ(rows.dof, p.dofs);
}

TEST(EliminatedComponents, generalizedInverseAndReactionsOfTheReducedSystem) {
  Piece p = brickWithFaceHeldInY();
  int live = 0;
  const auto rows = feti::eliminateComponents(p.system, p.dofs, live);
  feti::SubdomainSolver solver;
  solver.compute(p.system, p.coords, feti::Factorization::Cholmod);
  const LO n = p.system.K.n;
  // u = K^dagger f for the load made orthogonal to the live modes: K u = f, u = 0 where eliminated.
  std::vector<double> f = p.system.f, u(n), Ku(n);
  for (int j = 0; j < live; ++j) {
    const double* r = &p.system.R[static_cast<size_t>(j) * n];
    double c = 0.0;
    for (LO k = 0; k < n; ++k) c += r[k] * f[k];
    for (LO k = 0; k < n; ++k) f[k] -= c * r[k];
  }
  solver.applyPseudoInverse(f.data(), u.data());
  p.system.K.apply(u.data(), Ku.data());
  double residual = 0.0, scale = 0.0;
  for (LO k = 0; k < n; ++k) {
    residual = std::max(residual, std::abs(Ku[k] - f[k]));
    scale = std::max(scale, std::abs(f[k]));
  }
  EXPECT_LE(residual, 1e-9 * scale);
  for (LO d : p.dofs) EXPECT_NEAR(u[d], 0.0, 1e-14);
  // Reactions: (K u)_d - f_d with K and f as they were.
  std::vector<double> KoriginalU(n);
  p.original.K.apply(u.data(), KoriginalU.data());
  const auto reaction = feti::eliminatedReactions(rows, u);
  ASSERT_EQ(reaction.size(), p.dofs.size());
  for (size_t i = 0; i < p.dofs.size(); ++i)
    EXPECT_NEAR(reaction[i], KoriginalU[p.dofs[i]] - p.original.f[p.dofs[i]], 1e-9 * scale);
}

// How firmly eliminated components hold the modes they restrain (the rule that ConstraintMatrix
// uses to keep a subdomain's rows): a whole face held in y holds its three modes firmly; y held
// at two neighbouring nodes of a 7 x 7 x 7 node subdomain restrains the translation and a
// rotation weakly.
TEST(EliminatedComponents, aWholeFaceHoldsFirmlyTwoNodesDoNot) {
  const Piece p = brickWithFaceHeldInY(6);
  EXPECT_GE(feti::weakestRestraint(p.coords, p.dofs), 1e-2);
  const std::vector<LO> twoNodes = {p.dofs[0], p.dofs[1]};
  const double weak = feti::weakestRestraint(p.coords, twoNodes);
  EXPECT_LT(weak, 1e-2);
  EXPECT_GT(weak, 0.0);
  EXPECT_TRUE(std::isinf(feti::weakestRestraint(p.coords, {})));
}
