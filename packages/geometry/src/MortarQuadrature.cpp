/// \file MortarQuadrature.cpp
/// Quadrature points and dual bases on slave faces (header).
#include "MortarQuadrature.hpp"

#include <algorithm>
#include <cmath>

#include "tribos/geometry/MortarCoupling.hpp"
#include "tribos/mesh/ShapeFunctions.hpp"

namespace tribos::geometry {

namespace {
/// Sub-triangles per slave-triangle edge: 6^2 = 36 sub-triangles, 108 quadrature points.
/// The kinks of the master hat functions inside a slave triangle are then resolved to a
/// sixth of the slave mesh size (the weights change by < 1e-3 from 6 to 12 here).
constexpr int kSubdivisions = 6;

struct CompositePoint {
  std::array<double, 3> lambda;  ///< barycentric coordinates in the slave triangle
  double weight;                 ///< fraction of the triangle's area
};

/// Points and weights of the composite rule on the reference triangle: sub-triangles of a
/// regular kSubdivisions grid, each with the 3-point rule at (2/3, 1/6, 1/6) and permutations.
std::vector<CompositePoint> compositeRule() {
  std::vector<CompositePoint> rule;
  const int n = kSubdivisions;
  const double subWeight = 1.0 / (n * n) / 3.0;
  auto addTriangle = [&](const std::array<std::array<double, 2>, 3>& corner) {
    for (int k = 0; k < 3; ++k) {
      double s = 0.0, t = 0.0;
      for (int c = 0; c < 3; ++c) {
        const double w = c == k ? 2.0 / 3.0 : 1.0 / 6.0;
        s += w * corner[c][0];
        t += w * corner[c][1];
      }
      rule.push_back({{1.0 - s - t, s, t}, subWeight});
    }
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      const double a = double(i) / n, b = double(j) / n, h = 1.0 / n;
      addTriangle({{{a, b}, {a + h, b}, {a, b + h}}});
      if (i + j + 1 < n) addTriangle({{{a + h, b}, {a + h, b + h}, {a, b + h}}});
    }
  return rule;
}

/// The same sub-triangles with the 6-point rule exact for quartics (Dunavant 1985) on each:
/// for 6-node slave triangles, whose dual basis times an affine master field is cubic.
std::vector<CompositePoint> compositeQuarticRule() {
  std::vector<CompositePoint> rule;
  const int n = kSubdivisions;
  auto addTriangle = [&](const std::array<std::array<double, 2>, 3>& corner) {
    for (const TrianglePoint& q : quarticTriangleRule()) {
      double s = 0.0, t = 0.0;
      for (int c = 0; c < 3; ++c) {
        s += q.lambda[c] * corner[c][0];
        t += q.lambda[c] * corner[c][1];
      }
      rule.push_back({{1.0 - s - t, s, t}, q.weight / (n * n)});
    }
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; i + j < n; ++j) {
      const double x = double(i) / n, y = double(j) / n, h = 1.0 / n;
      addTriangle({{{x, y}, {x + h, y}, {x, y + h}}});
      if (i + j + 1 < n) addTriangle({{{x + h, y}, {x + h, y + h}, {x, y + h}}});
    }
  return rule;
}

/// The coefficients A = D M^{-1} of a dual basis psi = A phi from the face's moments D_k =
/// int phi_k and M_kl = int phi_k phi_l (symmetric positive definite: Gauss-Jordan without
/// pivoting): then int psi_i phi_j = delta_ij D_i.
template <int n>
std::array<std::array<double, n>, n> dualCoefficients(const double (&D)[n], const double (&moments)[n][n]) {
  double M[n][2 * n] = {};  // [M | I], reduced to [I | M^{-1}]
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) M[i][j] = moments[i][j];
    M[i][n + i] = 1.0;
  }
  for (int p = 0; p < n; ++p) {
    const double pivot = M[p][p];
    for (int k = 0; k < 2 * n; ++k) M[p][k] /= pivot;
    for (int r = 0; r < n; ++r) {
      if (r == p) continue;
      const double factor = M[r][p];
      for (int k = 0; k < 2 * n; ++k) M[r][k] -= factor * M[p][k];
    }
  }
  std::array<std::array<double, n>, n> A{};
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) A[i][k] = D[i] * M[i][n + k];
  return A;
}

/// Bilinear shape functions, the point and the area element of quadrilateral x at (xi, eta).
void bilinearAt(const std::array<Vec3, mesh::kMaxFaceNodes>& x, double xi, double eta, std::array<double, mesh::kMaxFaceNodes>& N,
                Vec3& point, double& areaElement) {
  const mesh::FaceGeometry g = mesh::faceGeometry(mesh::FaceType::Quad4, x.data(), xi, eta);
  N = g.N;
  point = g.point;
  areaElement = g.areaElement();
}

/// The dual basis of a 4-node quadrilateral: psi = A phi with A = D M^{-1} (M the face's
/// mass matrix, D its row sums int phi_i), so int psi_i phi_j = delta_ij int phi_i. On a
/// parallelogram this is the bilinear dual basis psi_i = 4 phi_i - 2 (phi_{i+1} + phi_{i-1})
/// + phi_{i+2} (ALGORITHMS.md 12); on other quadrilaterals it follows their Jacobian.
std::array<std::array<double, 4>, 4> quadDualCoefficients(const std::array<Vec3, mesh::kMaxFaceNodes>& x) {
  const double g = std::sqrt(3.0 / 5.0), gauss[3] = {-g, 0.0, g}, weight[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double M[4][4] = {}, D[4] = {};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      std::array<double, mesh::kMaxFaceNodes> N;
      Vec3 point;
      double dA;
      bilinearAt(x, gauss[a], gauss[b], N, point, dA);
      for (int i = 0; i < 4; ++i) {
        D[i] += weight[a] * weight[b] * dA * N[i];
        for (int j = 0; j < 4; ++j) M[i][j] += weight[a] * weight[b] * dA * N[i] * N[j];
      }
    }
  return dualCoefficients<4>(D, M);
}

/// The basis transformation of a 6-node triangle (Popp, Wohlmuth, Gee & Wall 2012): the
/// vertex functions take alpha of each neighbouring mid-edge function, phi~_v = phi_v + alpha
/// (phi_m + phi_m'), phi~_m = (1 - 2 alpha) phi_m. Its integrals are positive (2 alpha / 3 and
/// (1 - 2 alpha) / 3 of the area on a flat face, where the vertex functions' own are 0), so
/// a dual basis biorthogonal to it exists with positive D; the span and the partition of unity
/// are kept. The slave displacement's coefficients in this basis are u~_v = u_v and u~_m =
/// (u_m - alpha (u_a + u_b)) / (1 - 2 alpha) (a, b the ends of m's edge): a mid-edge node's
/// row couples it with them (MortarRow::slaveNodes).
constexpr double kTransformAlpha = kQuadraticTransformAlpha;
/// Mid-edge node 3 + m lies on the edge (m, m + 1 mod 3).
void transformedQuadratic(const double N[6], std::array<double, mesh::kMaxFaceNodes>& phi) {
  for (int v = 0; v < 3; ++v) phi[v] = N[v] + kTransformAlpha * (N[3 + v] + N[3 + (v + 2) % 3]);
  for (int m = 0; m < 3; ++m) phi[3 + m] = (1.0 - 2.0 * kTransformAlpha) * N[3 + m];
}

/// The quadratic geometry of a 6-node triangle at (r, s): its shape functions, point and area
/// element.
void quadraticTriangleAt(const std::array<Vec3, mesh::kMaxFaceNodes>& x, double r, double s, double N[6], Vec3& point,
                         double& areaElement) {
  const mesh::FaceGeometry g = mesh::faceGeometry(mesh::FaceType::Tri6, x.data(), r, s);
  std::copy_n(g.N.begin(), 6, N);
  point = g.point;
  areaElement = g.areaElement();
}

/// The dual basis of a 6-node triangle, biorthogonal to the transformed basis: psi = A phi~
/// with A = D M^{-1}, D_k = int phi~_k, M_kl = int phi~_k phi~_l, by a collapsed 4 x 4 Gauss
/// rule (exact to degree 7 on a flat face).
std::array<std::array<double, 6>, 6> sixNodeDualCoefficients(const std::array<Vec3, mesh::kMaxFaceNodes>& x) {
  const double g[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
  const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
  double M[6][6] = {}, D[6] = {};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      double N[6], dA;
      Vec3 point;
      quadraticTriangleAt(x, g[a], g[b] * (1.0 - g[a]), N, point, dA);
      std::array<double, mesh::kMaxFaceNodes> phi;
      transformedQuadratic(N, phi);
      const double weight = w[a] * w[b] * (1.0 - g[a]) * dA;
      for (int i = 0; i < 6; ++i) {
        D[i] += weight * phi[i];
        for (int j = 0; j < 6; ++j) M[i][j] += weight * phi[i] * phi[j];
      }
    }
  return dualCoefficients<6>(D, M);
}

}  // namespace

const std::array<TrianglePoint, 6>& quarticTriangleRule() {
  static constexpr double a = 0.445948490915965, wa = 0.223381589678011, b = 0.091576213509771,
                          wb = 0.109951743655322;
  static const std::array<TrianglePoint, 6> rule = {{{{a, a, 1 - 2 * a}, wa},
                                                     {{a, 1 - 2 * a, a}, wa},
                                                     {{1 - 2 * a, a, a}, wa},
                                                     {{b, b, 1 - 2 * b}, wb},
                                                     {{b, 1 - 2 * b, b}, wb},
                                                     {{1 - 2 * b, b, b}, wb}}};
  return rule;
}

SlaveBasis::SlaveBasis(const mesh::FaceNodes& face, const FaceCoordinates& x)
    : type_(mesh::faceType(face.numVertices, face.numNodes)), x_(x) {
  if (type_ == mesh::FaceType::Tri3) {
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) dual_[i][k] = (i == k ? 4.0 : 0.0) - 1.0;
    return;
  }
  if (type_ == mesh::FaceType::Quad4) {
    const auto A = quadDualCoefficients(x);
    for (int i = 0; i < 4; ++i) std::copy(A[i].begin(), A[i].end(), dual_[i].begin());
    return;
  }
  const auto A = sixNodeDualCoefficients(x);
  for (int i = 0; i < 6; ++i) std::copy(A[i].begin(), A[i].end(), dual_[i].begin());
}

SlavePoint SlaveBasis::at(double xi0, double xi1, double referenceWeight) const {
  const mesh::FaceGeometry g = mesh::faceGeometry(type_, x_.data(), xi0, xi1);
  SlavePoint s{};
  s.xi = {xi0, xi1};
  s.x = g.point;
  s.omega = referenceWeight * g.areaElement();
  const int n = mesh::faceNodeCount(type_);
  if (type_ == mesh::FaceType::Tri6)
    transformedQuadratic(g.N.data(), s.phi);
  else
    std::copy_n(g.N.begin(), n, s.phi.begin());
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < n; ++k) s.psi[v] += dual_[v][k] * s.phi[k];
  return s;
}

std::vector<SlavePoint> slaveFacePoints(const mesh::FaceNodes& face, const FaceCoordinates& x) {
  static const auto rule = compositeRule(), quarticRule = compositeQuarticRule();
  const SlaveBasis basis(face, x);
  std::vector<SlavePoint> points;
  if (basis.type() == mesh::FaceType::Quad4) {
    // kSubdivisions^2 sub-squares of the reference square with 2 x 2 Gauss points each.
    const int n = kSubdivisions;
    const double h = 2.0 / n, g = h / (2.0 * std::sqrt(3.0));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (double dxi : {-g, g})
          for (double deta : {-g, g})
            points.push_back(basis.at(-1.0 + (i + 0.5) * h + dxi, -1.0 + (j + 0.5) * h + deta, h * h / 4));
    return points;
  }
  // The reference triangle has area 1/2; the rules' weights are fractions of it.
  for (const auto& q : basis.type() == mesh::FaceType::Tri6 ? quarticRule : rule)
    points.push_back(basis.at(q.lambda[1], q.lambda[2], q.weight / 2.0));
  return points;
}

}  // namespace tribos::geometry
