// Isoparametric element kernels (paper Section 2: Hooke's law, the virtual work of the
// volume and surface loads) by Gauss quadrature.
#include "tribos/fem/SolidElements.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "tribos/fem/ElementKernels.hpp"

namespace tribos::fem {

namespace {
using mesh::ElementType;

/// Cartesian gradients G[k][d] = dN_k/dx_d at a quadrature point; returns det J.
double cartesianGradients(ElementType type, const double (*x)[3], const double xi[3], double N[], double G[][3]) {
  double dN[mesh::kMaxElementNodes][3], J[3][3];
  mesh::shapeFunctions(type, xi, N, dN);
  const double det = mesh::jacobian(type, x, dN, J);
  if (!(det > 0.0)) return det;
  // J^{-1} = adj(J) / det; dN/dx_d = sum_i dN/dxi_i (J^{-1})[i][d].
  double inv[3][3];
  inv[0][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) / det;
  inv[0][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) / det;
  inv[0][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) / det;
  inv[1][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) / det;
  inv[1][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) / det;
  inv[1][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) / det;
  inv[2][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) / det;
  inv[2][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) / det;
  inv[2][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) / det;
  const int n = mesh::elementShape(type).numNodes;
  for (int k = 0; k < n; ++k)
    for (int d = 0; d < 3; ++d) G[k][d] = dN[k][0] * inv[0][d] + dN[k][1] * inv[1][d] + dN[k][2] * inv[2][d];
  return det;
}

void copyTet(const double (*x)[3], double t[4][3]) {
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) t[v][c] = x[v][c];
}
}  // namespace

double solidStiffness(ElementType type, const double (*x)[3], double lambda, double mu, double* Ke) {
  const int n = mesh::elementShape(type).numNodes, dofs = 3 * n;
  if (mesh::elementShape(type).linearSimplex) {  // closed form
    double t[4][3], K[12][12];
    copyTet(x, t);
    const double V = tetStiffness(t, lambda, mu, K);
    if (V > 0.0) std::copy(&K[0][0], &K[0][0] + 144, Ke);
    return V;
  }
  double N[mesh::kMaxElementNodes], G[mesh::kMaxElementNodes][3];
  double volume = 0.0, smallest = 1.0;
  std::fill(Ke, Ke + dofs * dofs, 0.0);
  for (const auto& q : mesh::volumeRule(type)) {
    const double det = cartesianGradients(type, x, q.xi, N, G);
    smallest = std::min(smallest, det);
    if (!(det > 0.0)) continue;
    const double w = q.weight * det;
    volume += w;
    // As tetStiffness: lambda dN_a/dx_i dN_b/dx_j + mu dN_a/dx_j dN_b/dx_i + mu delta_ij grad N_a . grad N_b.
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const double dot = G[a][0] * G[b][0] + G[a][1] * G[b][1] + G[a][2] * G[b][2];
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            Ke[(3 * a + i) * dofs + 3 * b + j] +=
                w * (lambda * G[a][i] * G[b][j] + mu * G[a][j] * G[b][i] + (i == j ? mu * dot : 0.0));
      }
  }
  return smallest > 0.0 ? volume : std::min(smallest, volume);
}

double solidVolumeForce(ElementType type, const double (*x)[3], const double b[3], double* fe) {
  const int n = mesh::elementShape(type).numNodes;
  if (mesh::elementShape(type).linearSimplex) {  // closed form
    double t[4][3], load[12];
    copyTet(x, t);
    const double V = tetVolumeForce(t, b, load);
    std::copy(load, load + 12, fe);
    return V;
  }
  double N[mesh::kMaxElementNodes], dN[mesh::kMaxElementNodes][3], J[3][3], volume = 0.0;
  std::fill(fe, fe + 3 * n, 0.0);
  for (const auto& q : mesh::volumeRule(type)) {
    mesh::shapeFunctions(type, q.xi, N, dN);
    const double w = q.weight * mesh::jacobian(type, x, dN, J);
    volume += w;
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < 3; ++c) fe[3 * k + c] += w * N[k] * b[c];
  }
  return volume;
}

ElementStress solidStress(ElementType type, const double (*x)[3], const double* u, double lambda, double mu) {
  ElementStress out;
  if (mesh::elementShape(type).linearSimplex) {  // closed form
    double t[4][3];
    copyTet(x, t);
    out.volume = tetStress(t, u, lambda, mu, out.eps, out.sigma);
    if (out.volume > 0.0) out.strainEnergy = out.volume * strainEnergyDensity(out.eps, out.sigma);
    for (auto& node : out.atNodes) std::copy(out.sigma, out.sigma + 6, node);
    return out;
  }
  const int n = mesh::elementShape(type).numNodes;
  const auto& rule = mesh::volumeRule(type);
  double N[mesh::kMaxElementNodes], G[mesh::kMaxElementNodes][3];
  constexpr size_t kMaxPoints = 8;  // the hexahedron's 2 x 2 x 2
  std::array<std::array<double, 6>, kMaxPoints> atPoints{};
  size_t points = 0;
  for (const auto& q : rule) {
    const double det = cartesianGradients(type, x, q.xi, N, G);
    if (!(det > 0.0)) return ElementStress{det};
    double du[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) du[i][j] += u[3 * k + i] * G[k][j];
    constexpr int row[6] = {0, 1, 2, 0, 1, 0}, col[6] = {0, 1, 2, 1, 2, 2};
    double eps[6], sigma[6];
    for (int k = 0; k < 6; ++k) eps[k] = 0.5 * (du[row[k]][col[k]] + du[col[k]][row[k]]);
    const double trace = eps[0] + eps[1] + eps[2];
    for (int k = 0; k < 6; ++k) sigma[k] = 2.0 * mu * eps[k] + (k < 3 ? lambda * trace : 0.0);
    const double w = q.weight * det;
    if (points < kMaxPoints) atPoints[points++] = {sigma[0], sigma[1], sigma[2], sigma[3], sigma[4], sigma[5]};
    out.volume += w;
    out.strainEnergy += w * strainEnergyDensity(eps, sigma);
    for (int k = 0; k < 6; ++k) {
      out.eps[k] += w * eps[k];
      out.sigma[k] += w * sigma[k];
    }
  }
  for (int k = 0; k < 6; ++k) {
    out.eps[k] /= out.volume;
    out.sigma[k] /= out.volume;
  }
  const std::vector<double>& E = mesh::nodalExtrapolation(type);
  for (int k = 0; k < n; ++k)
    for (size_t q = 0; q < points; ++q)
      for (int c = 0; c < 6; ++c) out.atNodes[k][c] += E[k * points + q] * atPoints[q][c];
  return out;
}

double faceLoad(mesh::FaceType type, const double (*x)[3], const double p[3], double pressure, double* fe) {
  const int n = mesh::faceNodeCount(type);
  std::array<double, 3> nodes[mesh::kMaxFaceNodes];
  for (int k = 0; k < n; ++k) nodes[k] = {x[k][0], x[k][1], x[k][2]};
  double area = 0.0;
  std::fill(fe, fe + 3 * n, 0.0);
  for (const auto& q : mesh::faceRule(type)) {
    const mesh::FaceGeometry g = mesh::faceGeometry(type, nodes, q.xi[0], q.xi[1]);
    // The outward normal times the area element (the face's vertex order).
    const auto a = g.normal();
    const double dA = g.areaElement();
    area += q.weight * dA;
    for (int k = 0; k < n; ++k)
      for (int c = 0; c < 3; ++c) fe[3 * k + c] += q.weight * g.N[k] * (p[c] * dA - pressure * a[c]);
  }
  return area;
}

}  // namespace tribos::fem
