// Per-subdomain T-FETI operators (paper Section 4.1, ALGORITHMS.md 1): K_s R_s = 0 with
// orthonormal R_s, subdomain matrices sum to the undecomposed one, CSR layout, and errors
// that name what is wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "FemTestSupport.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {
const fem::Material kAluminium{2.792e4, 2.593e4}, kSteel{6.360e4, 8.301e4};  // paper Section 6
const std::vector<fem::Material> kMaterials{kAluminium, kSteel};

void expectKernelAndOrthonormality(const fem::SubdomainSystem& sys, const std::string& where) {
  const size_t n = sys.K.n;
  ASSERT_EQ(sys.R.size(), 6 * n) << where;
  std::vector<double> KR(n);
  for (int j = 0; j < 6; ++j) {
    sys.K.apply(&sys.R[j * n], KR.data());
    double norm = 0.0;
    for (double v : KR) norm += v * v;
    EXPECT_LE(std::sqrt(norm), 1e-10 * sys.K.frobeniusNorm()) << where << ", mode " << j;
    for (int k = 0; k < 6; ++k) {
      double dot = 0.0;
      for (size_t i = 0; i < n; ++i) dot += sys.R[j * n + i] * sys.R[k * n + i];
      EXPECT_NEAR(dot, j == k ? 1.0 : 0.0, 2e-15 * 6) << where << ", R^T R (" << j << ", " << k << ")";
    }
  }
}
}  // namespace

TEST(SubdomainSystem, rigidBodyModesSpanTheKernelAndAreOrthonormal) {
  const mesh::TwoBricksSpec spec{{4, 2, 2}, 3};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto structured = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  for (int s : {0, 5, 17, 31})
    expectKernelAndOrthonormality(fem::assembleSubdomain(mesh, structured.subdomains[s], kMaterials, {}),
                                  "structured subdomain " + std::to_string(s));
  // METIS subdomains: irregular shapes, centroid anywhere.
  const auto metis = mesh::buildDecomposition(mesh, mesh::metisPartition(mesh, 9));
  for (int s = 0; s < metis.numSubdomains(); s += 2)
    expectKernelAndOrthonormality(fem::assembleSubdomain(mesh, metis.subdomains[s], kMaterials, {}),
                                  "METIS subdomain " + std::to_string(s));
}

TEST(SubdomainSystem, rigidBodyModesOfFarAwayNodesStayOrthonormal) {
  // Far from the origin: centring on the centroid keeps Gram-Schmidt accurate.
  std::vector<std::array<double, 3>> x;
  for (int k = 0; k < 40; ++k) x.push_back({1e4 + 0.37 * k, -2e4 + std::sin(k), 3e4 + std::cos(1.7 * k)});
  const auto R = fem::rigidBodyModes(x);
  const size_t n = 3 * x.size();
  for (int j = 0; j < 6; ++j)
    for (int k = 0; k < 6; ++k) {
      double dot = 0.0;
      for (size_t i = 0; i < n; ++i) dot += R[j * n + i] * R[k * n + i];
      EXPECT_NEAR(dot, j == k ? 1.0 : 0.0, 1e-14);
    }
  const std::vector<std::array<double, 3>> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}};
  EXPECT_THROW(fem::rigidBodyModes(line), std::invalid_argument);
}

TEST(SubdomainSystem, subdomainMatricesSumToTheGlobalMatrix) {
  const mesh::TwoBricksSpec spec{{2, 1, 1}, 3};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto global = fem::assembleGlobal(mesh, kMaterials, {});
  const double scale = global.K.frobeniusNorm();
  for (const auto& part : {mesh::structuredPartition(mesh, spec), mesh::metisPartition(mesh, 7)}) {
    const auto d = mesh::buildDecomposition(mesh, part);
    std::vector<double> sum(global.K.values.size(), 0.0);
    for (const auto& s : d.subdomains) {
      const auto sys = fem::assembleSubdomain(mesh, s, kMaterials, {});
      ASSERT_EQ(sys.K.n, s.numDofs());
      for (LO i = 0; i < sys.K.n; ++i)
        for (LO k = sys.K.rowPtr[i]; k < sys.K.rowPtr[i + 1]; ++k) {
          // Local dof 3a + c <-> global dof 3 nodes[a] + c.
          const LO col = sys.K.colInd[k];
          const LO gi = 3 * s.nodes[i / 3] + i % 3, gj = 3 * s.nodes[col / 3] + col % 3;
          const auto first = global.K.colInd.begin() + global.K.rowPtr[gi];
          const auto last = global.K.colInd.begin() + global.K.rowPtr[gi + 1];
          const auto it = std::lower_bound(first, last, gj);
          ASSERT_TRUE(it != last && *it == gj) << "entry (" << gi << ", " << gj << ") not in the global graph";
          sum[it - global.K.colInd.begin()] += sys.K.values[k];
        }
    }
    for (size_t k = 0; k < sum.size(); ++k) EXPECT_NEAR(sum[k], global.K.values[k], 1e-14 * scale) << "entry " << k;
  }
}

TEST(SubdomainSystem, csrLayoutIsSortedSymmetricAndConsistentWithApply) {
  const mesh::Mesh box = fem::testing::structuredBox(2, 2, 1, 1.0, 0.1, 3);
  const auto sys = fem::assembleGlobal(box, {kSteel}, {});
  const auto& K = sys.K;
  ASSERT_EQ(K.n, 3 * box.numNodes());
  ASSERT_EQ(static_cast<LO>(K.rowPtr.size()), K.n + 1);
  ASSERT_EQ(K.colInd.size(), K.values.size());
  for (LO i = 0; i < K.n; ++i) {
    EXPECT_EQ((K.rowPtr[i + 1] - K.rowPtr[i]) % 3, 0);  // whole 3x3 node blocks
    for (LO k = K.rowPtr[i] + 1; k < K.rowPtr[i + 1]; ++k) EXPECT_LT(K.colInd[k - 1], K.colInd[k]);
    EXPECT_GT(K.at(i, i), 0.0);
  }
  // Graph = node pairs that share an element: nodes 0 and the far corner do not.
  const LO far = box.numNodes() - 1;
  EXPECT_EQ(K.at(0, 3 * far), 0.0);
  const auto A = fem::testing::toDense(K);
  double maxEntry = 0.0;
  for (double v : A) maxEntry = std::max(maxEntry, std::abs(v));
  for (LO i = 0; i < K.n; ++i)
    for (LO j = 0; j < K.n; ++j) {
      EXPECT_LE(std::abs(A[i * K.n + j] - A[j * K.n + i]), 1e-14 * maxEntry);
      EXPECT_EQ(K.at(i, j), A[i * K.n + j]);
    }
  std::vector<double> x(K.n), y(K.n);
  for (LO i = 0; i < K.n; ++i) x[i] = std::sin(1.0 + i);
  K.apply(x.data(), y.data());
  double frob = 0.0;
  for (LO i = 0; i < K.n; ++i) {
    double s = 0.0;
    for (LO j = 0; j < K.n; ++j) s += A[i * K.n + j] * x[j];
    EXPECT_NEAR(y[i], s, 1e-13 * maxEntry * K.n);
  }
  for (double v : A) frob += v * v;
  EXPECT_NEAR(K.frobeniusNorm(), std::sqrt(frob), 1e-14 * std::sqrt(frob));
}

TEST(SubdomainSystem, invertedElementIsAnInputErrorNamingItAndItsBlock) {
  const mesh::TwoBricksSpec spec{{2, 1, 1}, 2};
  const auto mesh = mesh::generateTwoBricks(spec);
  const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  mesh::Subdomain s = d.subdomains.back();  // a steel subdomain (brick 2)
  std::swap(s.localElements.mutableNodes(3)[1], s.localElements.mutableNodes(3)[2]);
  const std::string id = std::to_string(s.elements[3] + 1);
  try {
    fem::assembleSubdomain(mesh, s, kMaterials, {});
    FAIL() << "no error for an inverted element";
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("element " + id + " "), std::string::npos) << what;
    EXPECT_NE(what.find("steel"), std::string::npos) << what;
  }
}

TEST(SubdomainSystem, tractionOnAMissingSideSetIsAnInputErrorNamingIt) {
  const mesh::Mesh box = fem::testing::structuredBox(1, 1, 1, 1.0);
  fem::Loads loads;
  loads.tractions = {{"no_such_face", {1.0, 0.0, 0.0}}};
  try {
    fem::assembleGlobal(box, {kSteel}, loads);
    FAIL() << "no error for a missing side set";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_face"), std::string::npos) << e.what();
  }
  EXPECT_THROW(fem::assembleGlobal(box, {}, {}), std::invalid_argument);  // no material for block 0
}
