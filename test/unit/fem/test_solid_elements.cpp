// The element types beyond the linear tetrahedron (issue 32): patch tests on distorted
// meshes of every type and of a mixed mesh, the six rigid modes of every element matrix,
// consistent face loads, and the energy-norm convergence rates of a manufactured smooth
// solution (h for hexahedra, prisms and linear tetrahedra, h^2 for quadratic tetrahedra).
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include "FemTestSupport.hpp"
#include "TypedBoxMesh.hpp"
#include "tribos/fem/SolidElements.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Mesh.hpp"

using namespace tribos;
using test::BoxElements;

namespace {
const fem::Material kSteel = fem::Material::fromYoungPoisson(2.1e5, 0.3);

const char* kindName(BoxElements kind) {
  switch (kind) {
    case BoxElements::Tet4: return "tet4";
    case BoxElements::Tet10: return "tet10";
    case BoxElements::Hex8: return "hex8";
    case BoxElements::Wedge6: return "wedge6";
    case BoxElements::HexAndWedge: return "hex8+wedge6";
  }
  return "";
}

constexpr BoxElements kAllKinds[] = {BoxElements::Tet4, BoxElements::Tet10, BoxElements::Hex8, BoxElements::Wedge6,
                                     BoxElements::HexAndWedge};

bool onBoundary(const mesh::Mesh& m, LO n, double size) {
  for (double x : m.coords[n])
    if (x == 0.0 || x == size) return true;
  return false;
}

/// Solves K u = f with u prescribed (`fixed`) where given; returns the whole u. Dense for
/// small systems, Jacobi-preconditioned CG to round-off otherwise.
std::vector<double> solveWithPrescribed(const fem::CsrMatrix& K, const std::vector<double>& f,
                                        const std::vector<char>& fixed, std::vector<double> u) {
  std::vector<LO> free;
  for (LO i = 0; i < K.n; ++i)
    if (!fixed[i]) free.push_back(i);
  std::vector<double> r(f);  // f - K_{.,B} u_B on the free rows
  std::vector<double> uB(K.n, 0.0), KuB(K.n);
  for (LO i = 0; i < K.n; ++i)
    if (fixed[i]) uB[i] = u[i];
  K.apply(uB.data(), KuB.data());
  const size_t m = free.size();
  std::vector<double> b(m);
  for (size_t k = 0; k < m; ++k) b[k] = f[free[k]] - KuB[free[k]];
  std::vector<LO> position(K.n, -1);
  for (size_t k = 0; k < m; ++k) position[free[k]] = static_cast<LO>(k);
  // Jacobi PCG on the free block.
  auto applyFree = [&](const std::vector<double>& x, std::vector<double>& y) {
    for (size_t k = 0; k < m; ++k) {
      const LO i = free[k];
      double sum = 0.0;
      for (LO p = K.rowPtr[i]; p < K.rowPtr[i + 1]; ++p)
        if (position[K.colInd[p]] >= 0) sum += K.values[p] * x[position[K.colInd[p]]];
      y[k] = sum;
    }
  };
  std::vector<double> diag(m), x(m, 0.0), res(b), z(m), p(m), q(m);
  for (size_t k = 0; k < m; ++k) diag[k] = K.at(free[k], free[k]);
  for (size_t k = 0; k < m; ++k) z[k] = res[k] / diag[k];
  p = z;
  double rz = std::inner_product(res.begin(), res.end(), z.begin(), 0.0);
  const double bnorm = std::sqrt(std::inner_product(b.begin(), b.end(), b.begin(), 0.0));
  for (int it = 0; it < 20000 && bnorm > 0.0; ++it) {
    applyFree(p, q);
    const double alpha = rz / std::inner_product(p.begin(), p.end(), q.begin(), 0.0);
    for (size_t k = 0; k < m; ++k) {
      x[k] += alpha * p[k];
      res[k] -= alpha * q[k];
    }
    if (std::sqrt(std::inner_product(res.begin(), res.end(), res.begin(), 0.0)) <= 1e-15 * bnorm) break;
    for (size_t k = 0; k < m; ++k) z[k] = res[k] / diag[k];
    const double rzNew = std::inner_product(res.begin(), res.end(), z.begin(), 0.0);
    for (size_t k = 0; k < m; ++k) p[k] = z[k] + rzNew / rz * p[k];
    rz = rzNew;
  }
  for (size_t k = 0; k < m; ++k) u[free[k]] = x[k];
  return u;
}

void elementCoordinates(const mesh::Mesh& m, LO e, double x[][3]) {
  const auto nodes = m.elementNodes(e);
  for (int k = 0; k < nodes.size(); ++k)
    for (int c = 0; c < 3; ++c) x[k][c] = m.coords[nodes[k]][c];
}
}  // namespace

TEST(SolidElements, everyElementMatrixIsSymmetricWithTheSixRigidModesInItsKernel) {
  for (BoxElements kind : kAllKinds) {
    SCOPED_TRACE(kindName(kind));
    const mesh::Mesh m = test::typedBox(kind, 2, 0.5, 0.15);
    for (LO e = 0; e < m.numElements(); ++e) {
      double x[mesh::kMaxElementNodes][3], Ke[fem::kMaxElementDofs * fem::kMaxElementDofs];
      elementCoordinates(m, e, x);
      const int n = m.elementNodes(e).size(), dofs = 3 * n;
      const double volume = fem::solidStiffness(m.elementType(e), x, kSteel.lambda, kSteel.mu, Ke);
      ASSERT_GT(volume, 0.0);
      EXPECT_NEAR(volume, m.elementVolume(e), 1e-14);
      double scale = 0.0;
      for (int i = 0; i < dofs * dofs; ++i) scale = std::max(scale, std::abs(Ke[i]));
      for (int i = 0; i < dofs; ++i)
        for (int j = 0; j < i; ++j) EXPECT_NEAR(Ke[i * dofs + j], Ke[j * dofs + i], 1e-13 * scale);
      // Translations and the rotations about the axes: K_e r = 0.
      for (int mode = 0; mode < 6; ++mode) {
        std::vector<double> r(dofs);
        for (int k = 0; k < n; ++k) {
          const double* p = x[k];
          const double rot[3][3] = {{0, -p[2], p[1]}, {p[2], 0, -p[0]}, {-p[1], p[0], 0}};  // e_a x p
          for (int c = 0; c < 3; ++c) r[3 * k + c] = mode < 3 ? (c == mode ? 1.0 : 0.0) : rot[mode - 3][c];
        }
        for (int i = 0; i < dofs; ++i) {
          double sum = 0.0;
          for (int j = 0; j < dofs; ++j) sum += Ke[i * dofs + j] * r[j];
          EXPECT_NEAR(sum, 0.0, 1e-11 * scale);
        }
      }
    }
  }
}

// Uniform strain u = A x + b prescribed on the boundary of a distorted mesh (interior nodes
// moved by up to 20 % of h: non-affine hexahedra and prisms) is reproduced at every interior
// node to round-off, with the stress of that strain in every element.
TEST(SolidElements, patchTestOnDistortedMeshesOfEveryTypeAndAMixedOne) {
  const double A[3][3] = {{1e-3, 2e-4, -3e-4}, {-1e-4, 5e-4, 2e-4}, {3e-4, -2e-4, -4e-4}}, b[3] = {1e-3, -2e-3, 5e-4};
  for (BoxElements kind : kAllKinds) {
    SCOPED_TRACE(kindName(kind));
    const double h = 0.5, size = 3 * h;
    const mesh::Mesh m = test::typedBox(kind, 3, h, 0.2);
    m.validate("patch mesh");
    const fem::SubdomainSystem system = fem::assembleGlobal(m, {kSteel}, fem::Loads{});
    std::vector<double> exact(3 * static_cast<size_t>(m.numNodes())), u(exact.size(), 0.0);
    std::vector<char> fixed(exact.size(), 0);
    for (LO n = 0; n < m.numNodes(); ++n)
      for (int i = 0; i < 3; ++i) {
        exact[3 * n + i] = b[i];
        for (int j = 0; j < 3; ++j) exact[3 * n + i] += A[i][j] * m.coords[n][j];
        if (onBoundary(m, n, size)) {
          fixed[3 * n + i] = 1;
          u[3 * n + i] = exact[3 * n + i];
        }
      }
    u = solveWithPrescribed(system.K, std::vector<double>(exact.size(), 0.0), fixed, u);
    double worst = 0.0;
    for (size_t i = 0; i < u.size(); ++i) worst = std::max(worst, std::abs(u[i] - exact[i]));
    EXPECT_LT(worst, 1e-14) << "largest nodal error";
    // The stress of the uniform strain, in every element.
    double eps[6] = {A[0][0], A[1][1], A[2][2], (A[0][1] + A[1][0]) / 2, (A[1][2] + A[2][1]) / 2, (A[0][2] + A[2][0]) / 2};
    const double trace = eps[0] + eps[1] + eps[2];
    for (LO e = 0; e < m.numElements(); ++e) {
      double x[mesh::kMaxElementNodes][3], ue[fem::kMaxElementDofs];
      elementCoordinates(m, e, x);
      const auto nodes = m.elementNodes(e);
      for (int k = 0; k < nodes.size(); ++k)
        for (int c = 0; c < 3; ++c) ue[3 * k + c] = u[3 * nodes[k] + c];
      const auto stress = fem::solidStress(m.elementType(e), x, ue, kSteel.lambda, kSteel.mu);
      for (int k = 0; k < 6; ++k)
        EXPECT_NEAR(stress.sigma[k], 2 * kSteel.mu * eps[k] + (k < 3 ? kSteel.lambda * trace : 0.0), 1e-9);
    }
  }
}

// Nodal stresses extrapolated from the quadrature points (issue 42): the field
// u = (x z, y z, 0) lies in every type's space on an undistorted box (its strain is linear),
// so the stress at each element node must be the exact stress there, not the element's mean.
TEST(SolidElements, stressesAtTheNodesAreExactForALinearStressField) {
  for (BoxElements kind : {BoxElements::Tet10, BoxElements::Hex8, BoxElements::Wedge6, BoxElements::HexAndWedge}) {
    SCOPED_TRACE(kindName(kind));
    const mesh::Mesh m = test::typedBox(kind, 2, 0.5, 0.0);
    double worst = 0.0, spread = 0.0;
    for (LO e = 0; e < m.numElements(); ++e) {
      double x[mesh::kMaxElementNodes][3], ue[fem::kMaxElementDofs];
      elementCoordinates(m, e, x);
      const auto nodes = m.elementNodes(e);
      for (int k = 0; k < nodes.size(); ++k) {
        ue[3 * k] = x[k][0] * x[k][2];
        ue[3 * k + 1] = x[k][1] * x[k][2];
        ue[3 * k + 2] = 0.0;
      }
      const auto stress = fem::solidStress(m.elementType(e), x, ue, kSteel.lambda, kSteel.mu);
      for (int k = 0; k < nodes.size(); ++k) {
        const double eps[6] = {x[k][2], x[k][2], 0.0, 0.0, x[k][1] / 2, x[k][0] / 2};
        const double trace = eps[0] + eps[1] + eps[2];
        for (int c = 0; c < 6; ++c) {
          const double exact = 2 * kSteel.mu * eps[c] + (c < 3 ? kSteel.lambda * trace : 0.0);
          worst = std::max(worst, std::abs(stress.atNodes[k][c] - exact));
          spread = std::max(spread, std::abs(stress.atNodes[k][c] - stress.sigma[c]));
        }
      }
    }
    EXPECT_LT(worst, 1e-9 * kSteel.mu) << "largest error of a nodal stress";
    EXPECT_GT(spread, 0.1 * kSteel.mu) << "the nodal stresses must vary within the elements";
  }
}

TEST(SolidElements, faceLoadsSumToTheResultantAndSplitAsTheShapeFunctions) {
  const double p[3] = {1.0, -2.0, 3.0};
  // A flat 6-node triangle: corner weights 0, mid-edge weights area / 3.
  const double tri6[6][3] = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}, {1, 0, 0}, {1, 0.5, 0}, {0, 0.5, 0}};
  double fe[18];
  EXPECT_NEAR(fem::faceLoad(mesh::FaceType::Tri6, tri6, p, 0.0, fe), 1.0, 1e-15);
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fe[3 * k + c], k < 3 ? 0.0 : p[c] / 3, 1e-15);
  // A flat trapezoid: the resultant of traction and pressure, and each vertex's share.
  const double quad[4][3] = {{0, 0, 0}, {2, 0, 0}, {1.5, 1, 0}, {0.5, 1, 0}};
  double fq[12];
  const double area = fem::faceLoad(mesh::FaceType::Quad4, quad, p, 4.0, fq);
  EXPECT_NEAR(area, 1.5, 1e-15);
  for (int c = 0; c < 3; ++c) {
    const double sum = fq[c] + fq[3 + c] + fq[6 + c] + fq[9 + c];
    EXPECT_NEAR(sum, p[c] * 1.5 - (c == 2 ? 4.0 * 1.5 : 0.0), 1e-14);  // normal +z: pressure pushes along -z
  }
  // int N_0 over the trapezoid: the wide side's vertex takes more than the narrow side's.
  EXPECT_NEAR(fq[0], 5.0 / 12 * p[0], 1e-14);
  EXPECT_NEAR(fq[9], 1.0 / 3 * p[0], 1e-14);
}

namespace {
// The manufactured solution u_c = sin(x + y + z) for every component c: div sigma =
// -3 (lambda + 2 mu) sin(s) in every component, so the body force is 3 (lambda + 2 mu) sin(s).
double manufactured(const double x[3]) { return std::sin(x[0] + x[1] + x[2]); }

/// A rule of 4 x 4 x 4 Gauss points on the element (collapsed for tetrahedra and prisms),
/// exact well beyond the elements' degree: the error norm is integrated, not sampled.
std::vector<mesh::QuadraturePoint> fineRule(mesh::ElementType type) {
  const double g[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
  const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
  std::vector<mesh::QuadraturePoint> rule;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int c = 0; c < 4; ++c) {
        const double weight = w[a] * w[b] * w[c];
        switch (type) {
          case mesh::ElementType::Hex8:
            rule.push_back({{2 * g[a] - 1, 2 * g[b] - 1, 2 * g[c] - 1}, 8 * weight});
            break;
          case mesh::ElementType::Wedge6:  // (r, s) = (u, v (1 - u)) on the triangle
            rule.push_back({{g[a], g[b] * (1 - g[a]), 2 * g[c] - 1}, 2 * weight * (1 - g[a])});
            break;
          default:  // (r, s, t) = (u, v (1 - u), w (1 - u)(1 - v))
            rule.push_back({{g[a], g[b] * (1 - g[a]), g[c] * (1 - g[a]) * (1 - g[b])},
                            weight * (1 - g[a]) * (1 - g[a]) * (1 - g[b])});
        }
      }
  return rule;
}

/// The energy norm of the error of the finite element solution on an n^3 mesh of the unit cube.
double energyError(BoxElements kind, int n) {
  const mesh::Mesh m = test::typedBox(kind, n, 1.0 / n, 0.0);
  const fem::SubdomainSystem system = fem::assembleGlobal(m, {kSteel}, fem::Loads{});
  const double lambda = kSteel.lambda, mu = kSteel.mu, force = 3 * (lambda + 2 * mu);
  std::vector<double> f(3 * static_cast<size_t>(m.numNodes()), 0.0), u(f.size(), 0.0);
  double N[mesh::kMaxElementNodes], dN[mesh::kMaxElementNodes][3], J[3][3];
  for (LO e = 0; e < m.numElements(); ++e) {
    double x[mesh::kMaxElementNodes][3];
    elementCoordinates(m, e, x);
    const auto nodes = m.elementNodes(e);
    for (const auto& q : fineRule(m.elementType(e))) {
      mesh::shapeFunctions(m.elementType(e), q.xi, N, dN);
      const double w = q.weight * mesh::jacobian(m.elementType(e), x, dN, J);
      double xq[3] = {0, 0, 0};
      for (int k = 0; k < nodes.size(); ++k)
        for (int c = 0; c < 3; ++c) xq[c] += N[k] * x[k][c];
      for (int k = 0; k < nodes.size(); ++k)
        for (int c = 0; c < 3; ++c) f[3 * nodes[k] + c] += w * N[k] * force * manufactured(xq);
    }
  }
  std::vector<char> fixed(f.size(), 0);
  for (LO node = 0; node < m.numNodes(); ++node)
    if (onBoundary(m, node, 1.0))
      for (int c = 0; c < 3; ++c) {
        fixed[3 * node + c] = 1;
        u[3 * node + c] = manufactured(m.coords[node].data());
      }
  u = solveWithPrescribed(system.K, f, fixed, u);
  // sum over elements of int (eps_h - eps) : C : (eps_h - eps).
  double error = 0.0;
  for (LO e = 0; e < m.numElements(); ++e) {
    double x[mesh::kMaxElementNodes][3];
    elementCoordinates(m, e, x);
    const auto nodes = m.elementNodes(e);
    for (const auto& q : fineRule(m.elementType(e))) {
      mesh::shapeFunctions(m.elementType(e), q.xi, N, dN);
      const double det = mesh::jacobian(m.elementType(e), x, dN, J);
      const double inv[3][3] = {{(J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det, (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det,
                                 (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det},
                                {(J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det, (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det,
                                 (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det},
                                {(J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det, (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det,
                                 (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det}};
      double xq[3] = {0, 0, 0}, du[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      for (int k = 0; k < nodes.size(); ++k) {
        double G[3];
        for (int d = 0; d < 3; ++d) G[d] = dN[k][0] * inv[0][d] + dN[k][1] * inv[1][d] + dN[k][2] * inv[2][d];
        for (int c = 0; c < 3; ++c) {
          xq[c] += N[k] * x[k][c];
          for (int d = 0; d < 3; ++d) du[c][d] += u[3 * nodes[k] + c] * G[d];
        }
      }
      const double exact = std::cos(xq[0] + xq[1] + xq[2]);  // every du_c/dx_d
      double eps[3][3], trace = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) eps[i][j] = (du[i][j] + du[j][i]) / 2 - exact;
      for (int i = 0; i < 3; ++i) trace += eps[i][i];
      double density = lambda * trace * trace;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) density += 2 * mu * eps[i][j] * eps[i][j];
      error += q.weight * det * density;
    }
  }
  return std::sqrt(error);
}
}  // namespace

// Energy-norm rates between n = 4 and n = 8 (and 2 -> 4, printed): h for the linear
// elements, h^2 for the quadratic tetrahedron.
TEST(SolidElements, energyNormConvergesAtTheElementsRates) {
  struct Expected {
    BoxElements kind;
    double rate;
  };
  for (const Expected& x : {Expected{BoxElements::Hex8, 1.0}, Expected{BoxElements::Wedge6, 1.0},
                            Expected{BoxElements::Tet4, 1.0}, Expected{BoxElements::Tet10, 2.0}}) {
    SCOPED_TRACE(kindName(x.kind));
    const double e2 = energyError(x.kind, 2), e4 = energyError(x.kind, 4), e8 = energyError(x.kind, 8);
    const double rate = std::log2(e4 / e8);
    std::printf("%-6s energy error n=2 %.4e n=4 %.4e n=8 %.4e  rates %.3f %.3f\n", kindName(x.kind), e2, e4, e8,
                std::log2(e2 / e4), rate);
    EXPECT_NEAR(rate, x.rate, 0.12);
  }
}
