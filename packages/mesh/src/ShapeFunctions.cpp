#include "tribos/mesh/ShapeFunctions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tribos::mesh {

namespace {
const double kGauss = 1.0 / std::sqrt(3.0);

std::vector<QuadraturePoint> hexRule() {
  std::vector<QuadraturePoint> rule;
  for (double t : {-kGauss, kGauss})
    for (double s : {-kGauss, kGauss})
      for (double r : {-kGauss, kGauss}) rule.push_back({{r, s, t}, 1.0});
  return rule;
}

// The 3-point rule at the triangle's interior points (1/6, 1/6), (2/3, 1/6), (1/6, 2/3):
// exact for quadratics.
const double kTriangle[3][2] = {{1.0 / 6, 1.0 / 6}, {2.0 / 3, 1.0 / 6}, {1.0 / 6, 2.0 / 3}};

std::vector<QuadraturePoint> wedgeRule() {
  std::vector<QuadraturePoint> rule;
  for (double t : {-kGauss, kGauss})
    for (const auto& p : kTriangle) rule.push_back({{p[0], p[1], t}, 1.0 / 6});
  return rule;
}

std::vector<QuadraturePoint> tet10Rule() {
  // The 4-point rule exact for quadratics (a = (5 + 3 sqrt 5) / 20, b = (5 - sqrt 5) / 20).
  const double a = (5.0 + 3.0 * std::sqrt(5.0)) / 20.0, b = (5.0 - std::sqrt(5.0)) / 20.0;
  return {{{b, b, b}, 1.0 / 24}, {{a, b, b}, 1.0 / 24}, {{b, a, b}, 1.0 / 24}, {{b, b, a}, 1.0 / 24}};
}

// Reference vertices, for the corner Jacobians.
const double kTetVertices[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
const double kHexVertices[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
const double kWedgeVertices[6][3] = {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}, {0, 0, 1}, {1, 0, 1}, {0, 1, 1}};

void tet4Functions(const double xi[3], double N[], double dN[][3]) {
  N[0] = 1.0 - xi[0] - xi[1] - xi[2];
  for (int k = 0; k < 3; ++k) N[k + 1] = xi[k];
  for (int d = 0; d < 3; ++d) {
    dN[0][d] = -1.0;
    for (int k = 0; k < 3; ++k) dN[k + 1][d] = k == d ? 1.0 : 0.0;
  }
}

void tet10Functions(const double xi[3], double N[], double dN[][3]) {
  double L[4], dL[4][3];
  tet4Functions(xi, L, dL);
  for (int v = 0; v < 4; ++v) {
    N[v] = L[v] * (2.0 * L[v] - 1.0);
    for (int d = 0; d < 3; ++d) dN[v][d] = (4.0 * L[v] - 1.0) * dL[v][d];
  }
  static const int kEdges[6][2] = {{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  for (int m = 0; m < 6; ++m) {
    const int a = kEdges[m][0], b = kEdges[m][1];
    N[4 + m] = 4.0 * L[a] * L[b];
    for (int d = 0; d < 3; ++d) dN[4 + m][d] = 4.0 * (dL[a][d] * L[b] + L[a] * dL[b][d]);
  }
}

void hex8Functions(const double xi[3], double N[], double dN[][3]) {
  for (int k = 0; k < 8; ++k) {
    const double* s = kHexVertices[k];
    const double f[3] = {(1.0 + s[0] * xi[0]) / 2, (1.0 + s[1] * xi[1]) / 2, (1.0 + s[2] * xi[2]) / 2};
    N[k] = f[0] * f[1] * f[2];
    dN[k][0] = s[0] / 2 * f[1] * f[2];
    dN[k][1] = f[0] * s[1] / 2 * f[2];
    dN[k][2] = f[0] * f[1] * s[2] / 2;
  }
}

void wedge6Functions(const double xi[3], double N[], double dN[][3]) {
  const double L[3] = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
  const double dL[3][2] = {{-1.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}};
  for (int level = 0; level < 2; ++level) {
    const double sign = level == 0 ? -1.0 : 1.0, h = (1.0 + sign * xi[2]) / 2;
    for (int v = 0; v < 3; ++v) {
      const int k = 3 * level + v;
      N[k] = L[v] * h;
      dN[k][0] = dL[v][0] * h;
      dN[k][1] = dL[v][1] * h;
      dN[k][2] = L[v] * sign / 2;
    }
  }
}

double referenceVolume(ElementType type) {
  switch (type) {
    case ElementType::Tet4:
    case ElementType::Tet10: return 1.0 / 6;
    case ElementType::Hex8: return 8.0;
    case ElementType::Wedge6: return 1.0;
  }
  return 1.0;
}
}  // namespace

const std::vector<QuadraturePoint>& volumeRule(ElementType type) {
  static const std::vector<QuadraturePoint> rules[kNumElementTypes] = {
      {{{0.25, 0.25, 0.25}, 1.0 / 6}}, tet10Rule(), hexRule(), wedgeRule()};
  return rules[static_cast<int>(type)];
}

void referenceNode(ElementType type, int k, double xi[3]) {
  const int vertices = elementShape(type).numVertices;
  if (k < vertices) {
    const double* v = type == ElementType::Hex8 ? kHexVertices[k] : type == ElementType::Wedge6 ? kWedgeVertices[k] : kTetVertices[k];
    std::copy(v, v + 3, xi);
    return;
  }
  // The 10-node tetrahedron's mid-edge nodes: edges 0-1, 1-2, 0-2, 0-3, 1-3, 2-3 (Exodus order).
  static const int edge[6][2] = {{0, 1}, {1, 2}, {0, 2}, {0, 3}, {1, 3}, {2, 3}};
  const int* e = edge[k - vertices];
  for (int c = 0; c < 3; ++c) xi[c] = 0.5 * (kTetVertices[e[0]][c] + kTetVertices[e[1]][c]);
}

namespace {
/// The vertex (linear) type of a type's family: the 4-node tetrahedron for the 10-node one.
ElementType vertexType(ElementType type) { return type == ElementType::Tet10 ? ElementType::Tet4 : type; }

/// Solves the dense n x n system A x = b in place (partial pivoting; A well conditioned here).
void solveDense(int n, std::vector<double>& A, std::vector<double>& b) {
  for (int i = 0; i < n; ++i) {
    int p = i;
    for (int r = i + 1; r < n; ++r)
      if (std::abs(A[r * n + i]) > std::abs(A[p * n + i])) p = r;
    for (int c = 0; c < n; ++c) std::swap(A[i * n + c], A[p * n + c]);
    std::swap(b[i], b[p]);
    for (int r = i + 1; r < n; ++r) {
      const double f = A[r * n + i] / A[i * n + i];
      for (int c = i; c < n; ++c) A[r * n + c] -= f * A[i * n + c];
      b[r] -= f * b[i];
    }
  }
  for (int i = n - 1; i >= 0; --i) {
    for (int c = i + 1; c < n; ++c) b[i] -= A[i * n + c] * b[c];
    b[i] /= A[i * n + i];
  }
}

std::vector<double> extrapolationOf(ElementType type) {
  const auto& rule = volumeRule(type);
  const int nodes = elementShape(type).numNodes, points = static_cast<int>(rule.size());
  const ElementType linear = vertexType(type);
  const int nv = elementShape(linear).numVertices;
  std::vector<double> E(static_cast<size_t>(nodes) * points, 1.0 / points);
  if (points < nv) return E;  // one point: the constant
  double N[kMaxElementNodes], dN[kMaxElementNodes][3];
  std::vector<double> A(static_cast<size_t>(points) * nv);  // A[q][v] = N_v(xi_q)
  for (int q = 0; q < points; ++q) {
    shapeFunctions(linear, rule[q].xi, N, dN);
    for (int v = 0; v < nv; ++v) A[q * nv + v] = N[v];
  }
  // Column q of (A^T A)^{-1} A^T: the vertex coefficients of a unit value at point q.
  for (int q = 0; q < points; ++q) {
    std::vector<double> AtA(static_cast<size_t>(nv) * nv, 0.0), rhs(nv);
    for (int i = 0; i < nv; ++i) {
      rhs[i] = A[q * nv + i];
      for (int j = 0; j < nv; ++j)
        for (int r = 0; r < points; ++r) AtA[i * nv + j] += A[r * nv + i] * A[r * nv + j];
    }
    solveDense(nv, AtA, rhs);
    for (int k = 0; k < nodes; ++k) {
      double xi[3];
      referenceNode(type, k, xi);
      shapeFunctions(linear, xi, N, dN);
      double value = 0.0;
      for (int v = 0; v < nv; ++v) value += N[v] * rhs[v];
      E[static_cast<size_t>(k) * points + q] = value;
    }
  }
  return E;
}
}  // namespace

const std::vector<double>& nodalExtrapolation(ElementType type) {
  static const std::vector<double> tables[kNumElementTypes] = {
      extrapolationOf(ElementType::Tet4), extrapolationOf(ElementType::Tet10), extrapolationOf(ElementType::Hex8),
      extrapolationOf(ElementType::Wedge6)};
  return tables[static_cast<int>(type)];
}

void shapeFunctions(ElementType type, const double xi[3], double N[], double dN[][3]) {
  switch (type) {
    case ElementType::Tet4: return tet4Functions(xi, N, dN);
    case ElementType::Tet10: return tet10Functions(xi, N, dN);
    case ElementType::Hex8: return hex8Functions(xi, N, dN);
    case ElementType::Wedge6: return wedge6Functions(xi, N, dN);
  }
}

double jacobian(ElementType type, const double (*x)[3], const double dN[][3], double J[3][3]) {
  const int n = elementShape(type).numNodes;
  for (int d = 0; d < 3; ++d)
    for (int i = 0; i < 3; ++i) {
      double sum = 0.0;
      for (int k = 0; k < n; ++k) sum += x[k][d] * dN[k][i];
      J[d][i] = sum;
    }
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) - J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

ElementMeasure elementMeasure(ElementType type, const double (*x)[3]) {
  double N[kMaxElementNodes], dN[kMaxElementNodes][3], J[3][3];
  ElementMeasure m{0.0, std::numeric_limits<double>::infinity()};
  const double scale = referenceVolume(type);
  for (const auto& q : volumeRule(type)) {
    shapeFunctions(type, q.xi, N, dN);
    const double det = jacobian(type, x, dN, J);
    m.volume += q.weight * det;
    m.smallestScaledJacobian = std::min(m.smallestScaledJacobian, det * scale);
  }
  const int vertices = elementShape(type).numVertices;
  for (int v = 0; v < vertices; ++v) {
    const double* xi = type == ElementType::Hex8     ? kHexVertices[v]
                       : type == ElementType::Wedge6 ? kWedgeVertices[v]
                                                     : kTetVertices[v];
    shapeFunctions(type, xi, N, dN);
    m.smallestScaledJacobian = std::min(m.smallestScaledJacobian, jacobian(type, x, dN, J) * scale);
  }
  return m;
}

FaceType faceType(int numVertices, int numNodes) {
  if (numVertices == 4) return FaceType::Quad4;
  return numNodes == 6 ? FaceType::Tri6 : FaceType::Tri3;
}

const std::vector<QuadraturePoint>& faceRule(FaceType type) {
  static const std::vector<QuadraturePoint> triangle = {{{kTriangle[0][0], kTriangle[0][1], 0.0}, 1.0 / 6},
                                                        {{kTriangle[1][0], kTriangle[1][1], 0.0}, 1.0 / 6},
                                                        {{kTriangle[2][0], kTriangle[2][1], 0.0}, 1.0 / 6}};
  static const std::vector<QuadraturePoint> quad = {{{-kGauss, -kGauss, 0.0}, 1.0},
                                                    {{kGauss, -kGauss, 0.0}, 1.0},
                                                    {{kGauss, kGauss, 0.0}, 1.0},
                                                    {{-kGauss, kGauss, 0.0}, 1.0}};
  return type == FaceType::Quad4 ? quad : triangle;
}

void faceShapeFunctions(FaceType type, const double xi[3], double N[], double dN[][3]) {
  if (type == FaceType::Quad4) {
    static const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (int k = 0; k < 4; ++k) {
      const double a = (1.0 + corner[k][0] * xi[0]) / 2, b = (1.0 + corner[k][1] * xi[1]) / 2;
      N[k] = a * b;
      dN[k][0] = corner[k][0] / 2 * b;
      dN[k][1] = a * corner[k][1] / 2;
      dN[k][2] = 0.0;
    }
    return;
  }
  const double L[3] = {1.0 - xi[0] - xi[1], xi[0], xi[1]};
  const double dL[3][2] = {{-1.0, -1.0}, {1.0, 0.0}, {0.0, 1.0}};
  if (type == FaceType::Tri3) {
    for (int k = 0; k < 3; ++k) {
      N[k] = L[k];
      dN[k][0] = dL[k][0];
      dN[k][1] = dL[k][1];
      dN[k][2] = 0.0;
    }
    return;
  }
  for (int k = 0; k < 3; ++k) {
    N[k] = L[k] * (2.0 * L[k] - 1.0);
    for (int d = 0; d < 2; ++d) dN[k][d] = (4.0 * L[k] - 1.0) * dL[k][d];
    dN[k][2] = 0.0;
  }
  for (int m = 0; m < 3; ++m) {
    const int a = m, b = (m + 1) % 3;
    N[3 + m] = 4.0 * L[a] * L[b];
    for (int d = 0; d < 2; ++d) dN[3 + m][d] = 4.0 * (dL[a][d] * L[b] + L[a] * dL[b][d]);
    dN[3 + m][2] = 0.0;
  }
}

const FaceTypeShape& faceTypeShape(FaceType type) {
  // A quadrilateral is searched as its triangles (0,1,2), (0,2,3), a 6-node triangle as the four
  // its mid-edge nodes cut it into. Indexed by FaceType.
  static constexpr FaceTypeShape kFaceShapes[3] = {
      {"3-node triangle", 3, 3, {{0, 0}, {1, 0}, {0, 1}}, 1, {{0, 1, 2}}, false},
      {"6-node triangle", 3, 6, {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}}, 4,
       {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}}, true},
      {"4-node quadrilateral", 4, 4, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}, 2, {{0, 1, 2}, {0, 2, 3}}, true},
  };
  return kFaceShapes[static_cast<int>(type)];
}

int faceNodeCount(FaceType type) { return faceTypeShape(type).numNodes; }

FaceGeometry faceGeometry(FaceType type, const std::array<double, 3>* x, double xi0, double xi1) {
  FaceGeometry g{};
  double dN[kMaxFaceNodes][3];
  const double xi[3] = {xi0, xi1, 0.0};
  faceShapeFunctions(type, xi, g.N.data(), dN);
  for (int k = 0; k < faceNodeCount(type); ++k)
    for (int d = 0; d < 3; ++d) {
      g.point[d] += g.N[k] * x[k][d];
      g.tangent0[d] += dN[k][0] * x[k][d];
      g.tangent1[d] += dN[k][1] * x[k][d];
    }
  return g;
}

std::array<double, 3> FaceGeometry::normal() const {
  const auto &a = tangent0, &b = tangent1;
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

double FaceGeometry::areaElement() const {
  const auto n = normal();
  return std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

}  // namespace tribos::mesh
