// P1 tetrahedron (paper Section 2): K_e is symmetric with exactly the 6 rigid body modes in
// its kernel, its energy is V sigma:eps for a constant strain, and an assembled patch passes
// the constant-strain patch test to round-off; the recovered stress of a linear field is its
// exact constant stress.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "FemTestSupport.hpp"
#include "tribos/fem/ElementKernels.hpp"
#include "tribos/fem/SubdomainSystem.hpp"

using namespace tribos;
using fem::testing::denseSolve;
using fem::testing::structuredBox;
using fem::testing::symmetricEigenvalues;

namespace {
const fem::Material kSteel{6.360e4, 8.301e4};  // paper Section 6 (MPa)

// A regular-ish tet, a sliver-like flat one and a needle-like one, all positively oriented.
const double kTets[3][4][3] = {
    {{0.1, 0.0, 0.2}, {1.3, 0.1, 0.0}, {0.2, 0.9, 0.1}, {0.3, 0.2, 1.1}},
    {{0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.4, 0.3, 0.05}},
    {{5.0, 5.0, 5.0}, {5.1, 5.0, 5.0}, {5.0, 5.1, 5.0}, {5.02, 5.03, 9.0}}};

// Linear displacement u = A x + c and its constant stress sigma = lambda tr(eps) I + 2 mu eps.
const double kA[3][3] = {{1e-3, 2e-4, -3e-4}, {5e-4, -1e-3, 1e-4}, {-2e-4, 3e-4, 2e-3}};
const double kC[3] = {0.1, -0.2, 0.05};

void linearStress(const fem::Material& m, double sigma[3][3]) {
  double eps[3][3], trace = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) eps[i][j] = 0.5 * (kA[i][j] + kA[j][i]);
  for (int i = 0; i < 3; ++i) trace += eps[i][i];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) sigma[i][j] = 2.0 * m.mu * eps[i][j] + (i == j ? m.lambda * trace : 0.0);
}
}  // namespace

TEST(ElementKernels, stiffnessIsSymmetricWithExactlySixZeroEigenvalues) {
  for (const auto& x : kTets) {
    double Ke[12][12];
    ASSERT_GT(fem::tetStiffness(x, kSteel.lambda, kSteel.mu, Ke), 0.0);
    std::vector<double> A(144);
    double maxEntry = 0.0;
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        A[12 * i + j] = Ke[i][j];
        maxEntry = std::max(maxEntry, std::abs(Ke[i][j]));
      }
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < i; ++j) EXPECT_LE(std::abs(Ke[i][j] - Ke[j][i]), 1e-14 * maxEntry);
    const auto ev = symmetricEigenvalues(A, 12);
    // 6 rigid body modes (3 translations, 3 infinitesimal rotations) and nothing else.
    for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev[i]), 1e-12 * ev.back()) << "eigenvalue " << i;
    for (int i = 6; i < 12; ++i) EXPECT_GT(ev[i], 1e-6 * ev.back()) << "eigenvalue " << i;
  }
}

TEST(ElementKernels, energyOfALinearFieldIsVolumeTimesSigmaEps) {
  double sigma[3][3];
  linearStress(kSteel, sigma);
  double density = 0.0;  // sigma : eps = sigma : grad u (sigma symmetric)
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) density += sigma[i][j] * kA[i][j];
  for (const auto& x : kTets) {
    double Ke[12][12], u[12];
    const double V = fem::tetStiffness(x, kSteel.lambda, kSteel.mu, Ke);
    for (int v = 0; v < 4; ++v)
      for (int i = 0; i < 3; ++i) u[3 * v + i] = kC[i] + kA[i][0] * x[v][0] + kA[i][1] * x[v][1] + kA[i][2] * x[v][2];
    // The translation c contributes nothing but round-off of the size eps sum |u_i K_ij u_j|.
    double energy = 0.0, roundOff = 0.0;
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        energy += u[i] * Ke[i][j] * u[j];
        roundOff += std::abs(u[i] * Ke[i][j] * u[j]);
      }
    EXPECT_NEAR(energy, V * density, 1e-14 * roundOff + 1e-14 * V * density);
  }
}

TEST(ElementKernels, invertedTetReportsNegativeVolumeAndLeavesKeAlone) {
  double x[4][3];
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) x[v][c] = kTets[0][v][c];
  std::swap(x[2], x[3]);
  double Ke[12][12];
  Ke[0][0] = 42.0;
  EXPECT_LT(fem::tetStiffness(x, kSteel.lambda, kSteel.mu, Ke), 0.0);
  EXPECT_EQ(Ke[0][0], 42.0);
}

TEST(ElementKernels, tractionAndVolumeForceAreSplitEquallyOverVertices) {
  const double tri[3][3] = {{0, 0, 0}, {3, 0, 0}, {0, 4, 1}};
  const double p[3] = {1.0, -2.0, 0.5};
  double fe[9];
  const double area = fem::triangleTraction(tri, p, fe);
  EXPECT_NEAR(area, 0.5 * 3.0 * std::sqrt(17.0), 1e-14);
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(fe[3 * v + c], area / 3.0 * p[c]);
  double fv[12];
  const double V = fem::tetVolumeForce(kTets[0], p, fv);
  double Ke[12][12];
  EXPECT_DOUBLE_EQ(V, fem::tetStiffness(kTets[0], 1.0, 1.0, Ke));
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(fv[3 * v + c], V / 4.0 * p[c]);
}

// Patch test on a 3x3x3 box of Kuhn tets with jittered interior nodes (8 interior nodes):
//  (a) K u_lin equals the consistent load of the constant traction sigma n on the six faces
//      (each face loaded through fem::Loads), so interior residuals vanish, forces balance;
//  (b) prescribing u_lin on the boundary and solving for the interior reproduces u_lin.
TEST(ElementKernels, constantStrainPatchTestIsExactToRoundOff) {
  const double h = 2.5;
  const mesh::Mesh patch = structuredBox(3, 3, 3, h, 0.12, 7);
  patch.validate("patch");  // jitter keeps every element positive
  double sigma[3][3];
  linearStress(kSteel, sigma);
  fem::Loads boundaryTraction;
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (int axis = 0; axis < 3; ++axis)
    for (int end = 0; end < 2; ++end) {
      const double sign = end == 0 ? -1.0 : 1.0;  // outward normal +-e_axis
      boundaryTraction.tractions.push_back(
          {names[axis][end], {sign * sigma[0][axis], sign * sigma[1][axis], sign * sigma[2][axis]}});
    }
  const auto sys = fem::assembleGlobal(patch, {kSteel}, boundaryTraction);
  const LO n = sys.K.n;
  std::vector<double> u(n), Ku(n);
  for (LO a = 0; a < patch.numNodes(); ++a)
    for (int i = 0; i < 3; ++i)
      u[3 * a + i] = kC[i] + kA[i][0] * patch.coords[a][0] + kA[i][1] * patch.coords[a][1] +
                     kA[i][2] * patch.coords[a][2];
  sys.K.apply(u.data(), Ku.data());

  // (a) Residual row by row against its own round-off scale sum_j |K_ij u_j|.
  double resultant[3] = {0, 0, 0}, resultantScale = 0.0;
  for (LO i = 0; i < n; ++i) {
    double scale = 0.0;
    for (LO k = sys.K.rowPtr[i]; k < sys.K.rowPtr[i + 1]; ++k) scale += std::abs(sys.K.values[k] * u[sys.K.colInd[k]]);
    EXPECT_LE(std::abs(Ku[i] - sys.f[i]), 1e-12 * scale) << "dof " << i;
    resultant[i % 3] += Ku[i];
    resultantScale += std::abs(Ku[i]);
  }
  for (int c = 0; c < 3; ++c) EXPECT_LE(std::abs(resultant[c]), 1e-13 * resultantScale);

  // (b) Boundary = nodes on a side set face; solve K_II u_I = -K_IB u_B.
  std::vector<char> onBoundary(patch.numNodes(), 0);
  for (const auto& set : patch.sideSets)
    for (size_t f = 0; f < set.elements.size(); ++f)
      for (LO n : patch.faceNodes(set.elements[f], set.sides[f])) onBoundary[n] = 1;
  std::vector<LO> interiorDof(n, -1), interior;
  for (LO i = 0; i < n; ++i)
    if (!onBoundary[i / 3]) {
      interiorDof[i] = static_cast<LO>(interior.size());
      interior.push_back(i);
    }
  ASSERT_EQ(interior.size(), 3u * 8u);
  const size_t m = interior.size();
  std::vector<double> Kii(m * m, 0.0), rhs(m, 0.0);
  for (size_t r = 0; r < m; ++r)
    for (LO k = sys.K.rowPtr[interior[r]]; k < sys.K.rowPtr[interior[r] + 1]; ++k) {
      const LO col = sys.K.colInd[k];
      if (interiorDof[col] >= 0) Kii[r * m + interiorDof[col]] = sys.K.values[k];
      else rhs[r] -= sys.K.values[k] * u[col];
    }
  const auto uI = denseSolve(Kii, rhs);
  double uMax = 0.0;
  for (double v : u) uMax = std::max(uMax, std::abs(v));
  for (size_t r = 0; r < m; ++r) EXPECT_NEAR(uI[r], u[interior[r]], 1e-12 * uMax) << "interior dof " << interior[r];
}

// Stress recovery: a linear field gives its exact constant stress on every tet (whatever the
// translation part), the strain energy V sigma:eps/2 equals u^T K_e u / 2, and von Mises is
// sqrt(3 J2): p under uniaxial stress p, sqrt(3) tau under pure shear tau, 0 under pressure.
TEST(ElementKernels, stressOfALinearFieldIsExactAndEnergyMatchesStiffness) {
  double sigma[3][3];
  linearStress(kSteel, sigma);
  const int row[6] = {0, 1, 2, 0, 1, 0}, col[6] = {0, 1, 2, 1, 2, 2};
  for (const auto& x : kTets) {
    double u[12], eps[6], s[6], Ke[12][12];
    for (int v = 0; v < 4; ++v)
      for (int i = 0; i < 3; ++i) u[3 * v + i] = kC[i] + kA[i][0] * x[v][0] + kA[i][1] * x[v][1] + kA[i][2] * x[v][2];
    const double V = fem::tetStress(x, u, kSteel.lambda, kSteel.mu, eps, s);
    ASSERT_GT(V, 0.0);
    double scale = 0.0;
    for (int k = 0; k < 6; ++k) scale = std::max(scale, std::abs(sigma[row[k]][col[k]]));
    for (int k = 0; k < 6; ++k) EXPECT_NEAR(s[k], sigma[row[k]][col[k]], 1e-10 * scale) << "component " << k;
    fem::tetStiffness(x, kSteel.lambda, kSteel.mu, Ke);
    double energy = 0.0, roundOff = 0.0;
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        energy += 0.5 * u[i] * Ke[i][j] * u[j];
        roundOff += std::abs(u[i] * Ke[i][j] * u[j]);
      }
    EXPECT_NEAR(V * fem::strainEnergyDensity(eps, s), energy, 1e-12 * roundOff);
  }
  const double uniaxial[6] = {0, 0, -3.5, 0, 0, 0}, shear[6] = {0, 0, 0, 0, 2.0, 0}, pressure[6] = {-4, -4, -4, 0, 0, 0};
  EXPECT_NEAR(fem::vonMisesStress(uniaxial), 3.5, 1e-15);
  EXPECT_NEAR(fem::vonMisesStress(shear), 2.0 * std::sqrt(3.0), 1e-14);
  EXPECT_EQ(fem::vonMisesStress(pressure), 0.0);
}

TEST(ElementKernels, invertedTetLeavesStressAlone) {
  double x[4][3];
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) x[v][c] = kTets[0][v][c];
  std::swap(x[2], x[3]);
  const double u[12] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
  double eps[6] = {42, 0, 0, 0, 0, 0}, s[6] = {42, 0, 0, 0, 0, 0};
  EXPECT_LT(fem::tetStress(x, u, kSteel.lambda, kSteel.mu, eps, s), 0.0);
  EXPECT_EQ(eps[0], 42.0);
  EXPECT_EQ(s[0], 42.0);
}
