/// \file MortarCoupling.cpp
/// Dual mortar weights by element-based quadrature on the slave surface (header).
#include "tribos/mesh/MortarCoupling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "tribos/mesh/ShapeFunctions.hpp"

namespace tribos::mesh {

namespace {
using Vec3 = std::array<double, 3>;

/// Sub-triangles per slave-triangle edge: 6^2 = 36 sub-triangles, 108 quadrature points.
/// The kinks of the master hat functions inside a slave triangle are then resolved to a
/// sixth of the slave mesh size (the weights change by < 1e-3 from 6 to 12 here).
constexpr int kSubdivisions = 6;

/// Tolerance for "fully covered" (sum_j M_ij = D_i) and for "node-to-node" (w = unit vector).
constexpr double kCoverageTolerance = 1e-9;
constexpr double kNodeToNodeTolerance = 1e-10;

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
  const double a = 0.445948490915965, wa = 0.223381589678011, b = 0.091576213509771, wb = 0.109951743655322;
  const double points[6][3] = {{a, a, 1 - 2 * a}, {a, 1 - 2 * a, a}, {1 - 2 * a, a, a},
                               {b, b, 1 - 2 * b}, {b, 1 - 2 * b, b}, {1 - 2 * b, b, b}};
  std::vector<CompositePoint> rule;
  const int n = kSubdivisions;
  auto addTriangle = [&](const std::array<std::array<double, 2>, 3>& corner) {
    for (int k = 0; k < 6; ++k) {
      double s = 0.0, t = 0.0;
      for (int c = 0; c < 3; ++c) {
        s += points[k][c] * corner[c][0];
        t += points[k][c] * corner[c][1];
      }
      rule.push_back({{1.0 - s - t, s, t}, (k < 3 ? wa : wb) / (n * n)});
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

/// One quadrature point on a slave face: where it is, its weight times the area element, and
/// the slave shape functions phi_v and their duals psi_v at it (vertex order of the face).
struct SlavePoint {
  Vec3 x;
  double omega;
  std::array<double, kMaxFaceNodes> phi, psi;
};

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c);

/// A 3-node triangle: the composite rule, psi_v = 4 phi_v - 1 (Wohlmuth's linear dual basis).
std::vector<SlavePoint> trianglePoints(const std::array<Vec3, 3>& x, const std::vector<CompositePoint>& rule) {
  const double area = triangleArea(x[0], x[1], x[2]);
  std::vector<SlavePoint> points;
  points.reserve(rule.size());
  for (const auto& q : rule) {
    SlavePoint s{{0.0, 0.0, 0.0}, q.weight * area, {}, {}};
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d) s.x[d] += q.lambda[v] * x[v][d];
    for (int v = 0; v < 3; ++v) {
      s.phi[v] = q.lambda[v];
      s.psi[v] = 4.0 * q.lambda[v] - 1.0;
    }
    points.push_back(s);
  }
  return points;
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
void bilinearAt(const std::array<Vec3, kMaxFaceNodes>& x, double xi, double eta, std::array<double, kMaxFaceNodes>& N,
                Vec3& point, double& areaElement) {
  const FaceGeometry g = faceGeometry(FaceType::Quad4, x.data(), xi, eta);
  N = g.N;
  point = g.point;
  areaElement = g.areaElement();
}

/// The dual basis of a 4-node quadrilateral: psi = A phi with A = D M^{-1} (M the face's
/// mass matrix, D its row sums int phi_i), so int psi_i phi_j = delta_ij int phi_i. On a
/// parallelogram this is the bilinear dual basis psi_i = 4 phi_i - 2 (phi_{i+1} + phi_{i-1})
/// + phi_{i+2} (ALGORITHMS.md 12); on other quadrilaterals it follows their Jacobian.
std::array<std::array<double, 4>, 4> quadDualCoefficients(const std::array<Vec3, kMaxFaceNodes>& x) {
  const double g = std::sqrt(3.0 / 5.0), gauss[3] = {-g, 0.0, g}, weight[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double M[4][4] = {}, D[4] = {};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      std::array<double, kMaxFaceNodes> N;
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
void transformedQuadratic(const double N[6], std::array<double, kMaxFaceNodes>& phi) {
  for (int v = 0; v < 3; ++v) phi[v] = N[v] + kTransformAlpha * (N[3 + v] + N[3 + (v + 2) % 3]);
  for (int m = 0; m < 3; ++m) phi[3 + m] = (1.0 - 2.0 * kTransformAlpha) * N[3 + m];
}

/// The quadratic geometry of a 6-node triangle at (r, s): its shape functions, point and area
/// element.
void quadraticTriangleAt(const std::array<Vec3, kMaxFaceNodes>& x, double r, double s, double N[6], Vec3& point,
                         double& areaElement) {
  const FaceGeometry g = faceGeometry(FaceType::Tri6, x.data(), r, s);
  std::copy_n(g.N.begin(), 6, N);
  point = g.point;
  areaElement = g.areaElement();
}

/// The dual basis of a 6-node triangle, biorthogonal to the transformed basis: psi = A phi~
/// with A = D M^{-1}, D_k = int phi~_k, M_kl = int phi~_k phi~_l, by a collapsed 4 x 4 Gauss
/// rule (exact to degree 7 on a flat face).
std::array<std::array<double, 6>, 6> sixNodeDualCoefficients(const std::array<Vec3, kMaxFaceNodes>& x) {
  const double g[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
  const double w[4] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731, 0.1739274225687269};
  double M[6][6] = {}, D[6] = {};
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      double N[6], dA;
      Vec3 point;
      quadraticTriangleAt(x, g[a], g[b] * (1.0 - g[a]), N, point, dA);
      std::array<double, kMaxFaceNodes> phi;
      transformedQuadratic(N, phi);
      const double weight = w[a] * w[b] * (1.0 - g[a]) * dA;
      for (int i = 0; i < 6; ++i) {
        D[i] += weight * phi[i];
        for (int j = 0; j < 6; ++j) M[i][j] += weight * phi[i] * phi[j];
      }
    }
  return dualCoefficients<6>(D, M);
}

/// A 6-node triangle: the composite rule on its reference triangle, mapped by the quadratic
/// geometry; phi holds the transformed basis phi~, psi its dual.
std::vector<SlavePoint> sixNodePoints(const std::array<Vec3, kMaxFaceNodes>& x, const std::vector<CompositePoint>& rule) {
  const auto A = sixNodeDualCoefficients(x);
  std::vector<SlavePoint> points;
  points.reserve(rule.size());
  for (const auto& q : rule) {
    SlavePoint s{};
    double N[6], dA;
    quadraticTriangleAt(x, q.lambda[1], q.lambda[2], N, s.x, dA);
    s.omega = q.weight / 2.0 * dA;  // q.weight: a fraction of the reference triangle (area 1/2)
    transformedQuadratic(N, s.phi);
    for (int v = 0; v < 6; ++v)
      for (int k = 0; k < 6; ++k) s.psi[v] += A[v][k] * s.phi[k];
    points.push_back(s);
  }
  return points;
}

/// A 4-node quadrilateral: kSubdivisions^2 sub-squares with 2 x 2 Gauss points each.
std::vector<SlavePoint> quadPoints(const std::array<Vec3, kMaxFaceNodes>& x) {
  const auto A = quadDualCoefficients(x);
  const int n = kSubdivisions;
  const double h = 2.0 / n, g = h / (2.0 * std::sqrt(3.0)), subWeight = h * h / 4;
  std::vector<SlavePoint> points;
  points.reserve(4 * n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (double dxi : {-g, g})
        for (double deta : {-g, g}) {
          SlavePoint s{};
          double dA;
          bilinearAt(x, -1.0 + (i + 0.5) * h + dxi, -1.0 + (j + 0.5) * h + deta, s.phi, s.x, dA);
          s.omega = subWeight * dA;
          for (int v = 0; v < 4; ++v)
            for (int k = 0; k < 4; ++k) s.psi[v] += A[v][k] * s.phi[k];
          points.push_back(s);
        }
  return points;
}

double triangleArea(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const Vec3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

/// The integrals of one slave node: D_i, M_ij, int psi_i (chi(x) - x), and int psi_i over
/// the covered part (sum_j M_ij); and the range of the pointwise gap (chi(x) - x) . nu_i
/// over its support.
struct NodeIntegrals {
  double D = 0.0, covered = 0.0;
  std::map<LO, double> M;
  Vec3 gapVector{0.0, 0.0, 0.0};
  double gapMin = std::numeric_limits<double>::infinity(), gapMax = -std::numeric_limits<double>::infinity();
};
}  // namespace

MortarRow nodeToSurfaceRow(const ContactPair& pair) {
  MortarRow row;
  row.nodeToSurface = true;
  row.gap = pair.gap;
  std::map<LO, double> sorted;
  for (int v = 0; v < kMaxMasterFaceNodes; ++v)
    if (pair.weights[v] != 0.0) sorted[pair.masterNodes[v]] += pair.weights[v];
  for (const auto& [node, w] : sorted) {
    row.masterNodes.push_back(node);
    row.weights.push_back(w);
  }
  return row;
}

bool projectsOnMasterVertices(const ContactSearchResult& search) {
  for (const auto& pair : search.pairs)
    if (std::count(pair.weights.begin(), pair.weights.end(), 1.0) != 1) return false;
  return !search.pairs.empty();
}

std::vector<MortarRow> dualMortarRows(const Mesh& mesh, const std::string& slaveSideSet, const MasterSurface& master,
                                      const ContactSearchResult& search, double searchDistance) {
  if (projectsOnMasterVertices(search)) {
    // Node-matching interface (header): node-to-node rows, whatever the triangles.
    std::vector<MortarRow> rows;
    for (const auto& pair : search.pairs) rows.push_back(nodeToSurfaceRow(pair));
    return rows;
  }
  std::vector<int> pairOf(mesh.numNodes(), -1);
  for (size_t p = 0; p < search.pairs.size(); ++p) pairOf[search.pairs[p].slaveNode] = static_cast<int>(p);
  std::vector<NodeIntegrals> integrals(search.pairs.size());

  // (1) Quadrature over every slave face touching a paired node.
  const auto rule = compositeRule(), quarticRule = compositeQuarticRule();
  std::map<LO, std::pair<LO, LO>> edgeEnds;  // a 6-node triangle's mid-edge node -> its edge's ends
  const SideSet& set = mesh.sideSet(slaveSideSet);
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const FaceNodes face = mesh.faceNodes(set.elements[f], set.sides[f]);
    const int nodes = face.numNodes;
    bool anyPaired = false;
    for (LO n : face) anyPaired = anyPaired || pairOf[n] >= 0;
    if (!anyPaired) continue;
    std::array<Vec3, kMaxFaceNodes> x{};
    for (int v = 0; v < nodes; ++v) x[v] = mesh.coords[face.node[v]];
    for (int m = 0; nodes == 6 && m < 3; ++m) edgeEnds[face.node[3 + m]] = {face.node[m], face.node[(m + 1) % 3]};
    const auto points = face.numVertices == 4 ? quadPoints(x)
                        : nodes == 6          ? sixNodePoints(x, quarticRule)
                                              : trianglePoints({x[0], x[1], x[2]}, rule);
    for (const SlavePoint& q : points) {
      const Vec3& xq = q.x;
      const double omega = q.omega;
      const auto chi = master.project(xq, searchDistance);
      for (int v = 0; v < nodes; ++v) {
        const int p = pairOf[face.node[v]];
        if (p < 0) continue;
        NodeIntegrals& I = integrals[p];
        I.D += omega * q.phi[v];
        if (chi.face < 0) continue;
        const double psi = q.psi[v];  // the dual basis function of node v
        I.covered += omega * psi;
        for (int j = 0; j < kMaxMasterFaceNodes; ++j)
          if (chi.weights[j] != 0.0) I.M[chi.nodes[j]] += omega * psi * chi.weights[j];
        const Vec3 gap{chi.point[0] - xq[0], chi.point[1] - xq[1], chi.point[2] - xq[2]};
        for (int d = 0; d < 3; ++d) I.gapVector[d] += omega * psi * gap[d];
        const Vec3& nu = search.pairs[p].normal;
        const double along = gap[0] * nu[0] + gap[1] * nu[1] + gap[2] * nu[2];
        I.gapMin = std::min(I.gapMin, along);
        I.gapMax = std::max(I.gapMax, along);
      }
    }
  }

  // (2) Weights per node; node-to-surface where the support is not fully covered, and
  // exactly node-to-node where the mortar weights are (matching meshes).
  std::vector<MortarRow> rows(search.pairs.size());
  for (size_t p = 0; p < rows.size(); ++p) {
    const ContactPair& pair = search.pairs[p];
    const NodeIntegrals& I = integrals[p];
    const MortarRow fallback = nodeToSurfaceRow(pair);
    if (!(I.D > 0.0) || std::abs(I.covered - I.D) > kCoverageTolerance * I.D) {
      rows[p] = fallback;
      continue;
    }
    MortarRow row;
    for (const auto& [masterNode, m] : I.M) {
      row.masterNodes.push_back(masterNode);
      row.weights.push_back(m / I.covered);
    }
    if (fallback.masterNodes.size() == 1) {
      // The node sits on a master vertex: node-to-node if the mortar weights agree.
      double deviation = 0.0;
      for (size_t k = 0; k < row.masterNodes.size(); ++k)
        deviation = std::max(deviation, std::abs(row.weights[k] - (row.masterNodes[k] == fallback.masterNodes[0])));
      if (deviation <= kNodeToNodeTolerance) {
        rows[p] = fallback;
        continue;
      }
    }
    // The dual basis is negative on part of the support: where the gap varies much within it
    // (a master that curves away within one slave element: a fillet of 1.5 slave elements)
    // the weighted gap can leave the range of the gap itself, a weighted overlap where the
    // surfaces are apart (the rounded punch then rose under a downward load). Kept within
    // the range of the pointwise gap over the support: unchanged where it already is
    // (the Hertz scenes, where the gap varies slowly), never an overlap where none is.
    const double weighted =
        (I.gapVector[0] * pair.normal[0] + I.gapVector[1] * pair.normal[1] + I.gapVector[2] * pair.normal[2]) /
        I.covered;
    if (!(I.gapMin <= I.gapMax) || !std::isfinite(weighted)) {  // no finite projection: never a clamp on it
      rows[p] = fallback;
      continue;
    }
    row.gap = std::clamp(weighted, I.gapMin, I.gapMax);
    row.gapLimited = std::abs(row.gap - weighted);
    if (const auto ends = edgeEnds.find(pair.slaveNode); ends != edgeEnds.end()) {
      // The row holds u~_m = (u_m - alpha (u_a + u_b)) / (1 - 2 alpha) (header).
      const double keep = 1.0 - 2.0 * kTransformAlpha;
      row.slaveWeight = 1.0 / keep;
      row.slaveNodes = {ends->second.first, ends->second.second};
      row.slaveWeights = {-kTransformAlpha / keep, -kTransformAlpha / keep};
    }
    rows[p] = std::move(row);
  }
  return rows;
}

}  // namespace tribos::mesh
