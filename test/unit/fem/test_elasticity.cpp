// P1 elasticity: element properties, constant-strain patch test, subdomain kernels,
// assembly consistency, load resultants.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tribos/fem/ElementKernels.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {
const fem::Material kAluminium{2.792e4, 2.593e4}, kSteel{6.360e4, 8.301e4};

// Eigenvalues of a small symmetric matrix by cyclic Jacobi rotations (written for this test).
std::vector<double> symmetricEigenvalues(std::vector<std::vector<double>> A) {
  const size_t n = A.size();
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0;
    for (size_t p = 0; p < n; ++p)
      for (size_t q = p + 1; q < n; ++q) off += A[p][q] * A[p][q];
    if (off < 1e-30) break;
    for (size_t p = 0; p < n; ++p)
      for (size_t q = p + 1; q < n; ++q) {
        if (std::abs(A[p][q]) < 1e-300) continue;
        const double theta = (A[q][q] - A[p][p]) / (2.0 * A[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (size_t k = 0; k < n; ++k) {
          const double akp = A[k][p], akq = A[k][q];
          A[k][p] = c * akp - s * akq;
          A[k][q] = s * akp + c * akq;
        }
        for (size_t k = 0; k < n; ++k) {
          const double apk = A[p][k], aqk = A[q][k];
          A[p][k] = c * apk - s * aqk;
          A[q][k] = s * apk + c * aqk;
        }
      }
  }
  std::vector<double> ev(n);
  for (size_t i = 0; i < n; ++i) ev[i] = A[i][i];
  std::sort(ev.begin(), ev.end());
  return ev;
}

std::vector<double> dense(const fem::CsrMatrix& K, LO i) {
  std::vector<double> row(K.n, 0.0);
  for (LO k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) row[K.colInd[k]] = K.values[k];
  return row;
}
}  // namespace

TEST(tetStiffness, isSymmetricWithExactlySixZeroEigenvalues) {
  const double x[4][3] = {{0.1, 0.0, 0.2}, {1.3, 0.1, 0.0}, {0.2, 0.9, 0.1}, {0.3, 0.2, 1.1}};
  double Ke[12][12];
  ASSERT_GT(fem::tetStiffness(x, kSteel.lambda, kSteel.mu, Ke), 0.0);
  std::vector<std::vector<double>> A(12, std::vector<double>(12));
  double maxEntry = 0.0;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      A[i][j] = Ke[i][j];
      maxEntry = std::max(maxEntry, std::abs(Ke[i][j]));
    }
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) EXPECT_NEAR(Ke[i][j], Ke[j][i], 1e-14 * maxEntry);
  const auto ev = symmetricEigenvalues(A);
  for (int i = 0; i < 6; ++i) EXPECT_LT(std::abs(ev[i]), 1e-12 * ev.back());
  for (int i = 6; i < 12; ++i) EXPECT_GT(ev[i], 1e-6 * ev.back());
}

TEST(tetStiffness, constantStrainPatchTestIsExactToRoundOff) {
  // A 2x2x2-cube patch (5-tet split): prescribe u = A x + c on the boundary nodes, solve for
  // the interior node, which must reproduce the linear field; the interior residual of the
  // linear field itself is zero.
  const mesh::Mesh patch = mesh::generateTwoBricks({{4, 2, 2}, 1});  // brick 1: 4x2x2 cubes, 3 interior nodes
  const auto sys = fem::assembleGlobal(patch, {kAluminium, kSteel}, {});
  const double A[3][3] = {{1e-3, 2e-4, -3e-4}, {5e-4, -1e-3, 1e-4}, {-2e-4, 3e-4, 2e-3}}, c[3] = {0.1, -0.2, 0.05};
  std::vector<double> u(sys.K.n);
  for (LO n = 0; n < patch.numNodes(); ++n)
    for (int i = 0; i < 3; ++i) {
      u[3 * n + i] = c[i];
      for (int j = 0; j < 3; ++j) u[3 * n + i] += A[i][j] * patch.coords[n][j];
    }
  std::vector<double> Ku(sys.K.n);
  sys.K.apply(u.data(), Ku.data());
  // Interior nodes of brick 1 (x in (0,20), y in (0,10), z in (0,10)): residual zero.
  std::vector<LO> interior;
  for (LO n = 0; n < patch.numNodes(); ++n) {
    const auto& x = patch.coords[n];
    if (n < patch.numNodes() / 2 && x[0] > 0 && x[0] < 20 && x[1] > 0 && x[1] < 10 && x[2] > 0 && x[2] < 10)
      interior.push_back(n);
  }
  ASSERT_EQ(interior.size(), 3u);
  double scale = 0.0;
  for (double v : sys.K.values) scale = std::max(scale, std::abs(v));
  for (LO n : interior)
    for (int i = 0; i < 3; ++i) EXPECT_LT(std::abs(Ku[3 * n + i]), 1e-13 * scale * 10.0);
  // Solve K_ii u_i = -K_ib u_b (dense Gauss elimination on the 9 interior dofs).
  const size_t ni = 3 * interior.size();
  std::vector<std::vector<double>> Kii(ni, std::vector<double>(ni + 1, 0.0));
  for (size_t a = 0; a < interior.size(); ++a)
    for (int i = 0; i < 3; ++i) {
      const LO row = 3 * interior[a] + i;
      const auto full = dense(sys.K, row);
      double rhs = 0.0;
      for (LO col = 0; col < sys.K.n; ++col) {
        const auto it = std::find(interior.begin(), interior.end(), col / 3);
        if (it != interior.end()) Kii[3 * a + i][3 * (it - interior.begin()) + col % 3] = full[col];
        else rhs -= full[col] * u[col];
      }
      Kii[3 * a + i][ni] = rhs;
    }
  for (size_t p = 0; p < ni; ++p)
    for (size_t r = p + 1; r < ni; ++r) {
      const double f = Kii[r][p] / Kii[p][p];
      for (size_t k = p; k <= ni; ++k) Kii[r][k] -= f * Kii[p][k];
    }
  std::vector<double> ui(ni);
  for (size_t p = ni; p-- > 0;) {
    double s = Kii[p][ni];
    for (size_t k = p + 1; k < ni; ++k) s -= Kii[p][k] * ui[k];
    ui[p] = s / Kii[p][p];
  }
  for (size_t a = 0; a < interior.size(); ++a)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(ui[3 * a + i], u[3 * interior[a] + i], 1e-12 * 0.1);
}

TEST(assembleSubdomain, rigidBodyModesSpanTheKernelAndAreOrthonormal) {
  const mesh::TwoBricksSpec spec{{4, 2, 2}, 3};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  for (int s : {0, 5, 17, 31}) {
    const auto sys = fem::assembleSubdomain(mesh, d.subdomains[s], {kAluminium, kSteel}, {});
    const size_t n = sys.K.n;
    std::vector<double> KR(n);
    for (int j = 0; j < 6; ++j) {
      sys.K.apply(&sys.R[j * n], KR.data());
      double norm = 0.0;
      for (double v : KR) norm += v * v;
      EXPECT_LE(std::sqrt(norm), 1e-10 * sys.K.frobeniusNorm());
      for (int k = 0; k < 6; ++k) {
        double dot = 0.0;
        for (size_t i = 0; i < n; ++i) dot += sys.R[j * n + i] * sys.R[k * n + i];
        EXPECT_NEAR(dot, j == k ? 1.0 : 0.0, 1e-14);
      }
    }
  }
}

TEST(assembleSubdomain, subdomainMatricesSumToTheGlobalMatrix) {
  const mesh::TwoBricksSpec spec{{2, 1, 1}, 3};
  const auto mesh = mesh::generateTwoBricks(spec);
  for (const auto& part : {mesh::structuredPartition(mesh, spec), mesh::metisPartition(mesh, 7)}) {
    const auto d = mesh::buildDecomposition(mesh, part);
    const auto global = fem::assembleGlobal(mesh, {kAluminium, kSteel}, {});
    std::vector<double> sum(global.K.values.size(), 0.0);
    for (const auto& s : d.subdomains) {
      const auto sys = fem::assembleSubdomain(mesh, s, {kAluminium, kSteel}, {});
      for (LO i = 0; i < sys.K.n; ++i)
        for (LO k = sys.K.rowPtr[i]; k < sys.K.rowPtr[i + 1]; ++k) {
          const LO gi = 3 * s.nodes[i / 3] + i % 3, gj = 3 * s.nodes[sys.K.colInd[k] / 3] + sys.K.colInd[k] % 3;
          const auto first = global.K.colInd.begin() + global.K.rowPtr[gi];
          const auto it = std::lower_bound(first, global.K.colInd.begin() + global.K.rowPtr[gi + 1], gj);
          ASSERT_EQ(*it, gj);
          sum[it - global.K.colInd.begin()] += sys.K.values[k];
        }
    }
    const double scale = global.K.frobeniusNorm();
    for (size_t k = 0; k < sum.size(); ++k) EXPECT_NEAR(sum[k], global.K.values[k], 1e-14 * scale);
  }
}

TEST(assembleSubdomain, tractionAndVolumeForceResultantsMatchLoadTimesMeasure) {
  const mesh::TwoBricksSpec spec{{4, 2, 2}, 2};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  struct Case {
    const char* set;
    double area;
  };
  for (const Case& c : {Case{"load_end", 100.0}, Case{"load_top", 200.0}, Case{"contact_aluminium", 200.0}}) {
    fem::Loads loads;
    loads.tractions = {{c.set, {1.0, -2.0, 20.0}}};
    double total[3] = {0, 0, 0};
    for (const auto& s : d.subdomains) {
      const auto sys = fem::assembleSubdomain(mesh, s, {kAluminium, kSteel}, loads);
      for (LO i = 0; i < sys.K.n; ++i) total[i % 3] += sys.f[i];
    }
    EXPECT_NEAR(total[0], 1.0 * c.area, 1e-12 * c.area * 20);
    EXPECT_NEAR(total[1], -2.0 * c.area, 1e-12 * c.area * 20);
    EXPECT_NEAR(total[2], 20.0 * c.area, 1e-12 * c.area * 20);
  }
  fem::Loads gravity;
  gravity.volumeForce = {{0.0, 0.0, -1.0}, {0.0, 0.0, -2.0}};
  double fz = 0.0;
  for (const auto& s : d.subdomains) {
    const auto sys = fem::assembleSubdomain(mesh, s, {kAluminium, kSteel}, gravity);
    for (LO i = 2; i < sys.K.n; i += 3) fz += sys.f[i];
  }
  EXPECT_NEAR(fz, -1.0 * 2000.0 - 2.0 * 2000.0, 1e-9);
}
