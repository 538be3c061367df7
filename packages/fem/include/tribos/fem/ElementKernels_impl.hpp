#pragma once
// Inline implementations of ElementKernels.hpp (P1 tetrahedron, paper Section 2/3).

namespace tribos::fem {

namespace detail {
/// Gradients of the 4 barycentric shape functions (grad[a][i] = dN_a/dx_i); returns the
/// signed volume. For x = x0 + J xi with J = [x1-x0, x2-x0, x3-x0], N_a = xi_a (a = 1..3),
/// so grad N_a is row a of J^{-1} and grad N_0 = -(sum of the others).
KOKKOS_INLINE_FUNCTION double shapeGradients(const double x[4][3], double grad[4][3]) {
  double J[3][3];
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) J[i][a] = x[a + 1][i] - x[0][i];
  const double det = J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
                     J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
                     J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
  if (!(det > 0.0)) return det / 6.0;
  const double inv = 1.0 / det;
  // Rows of J^{-1} (adjugate / det).
  grad[1][0] = (J[1][1] * J[2][2] - J[1][2] * J[2][1]) * inv;
  grad[1][1] = (J[0][2] * J[2][1] - J[0][1] * J[2][2]) * inv;
  grad[1][2] = (J[0][1] * J[1][2] - J[0][2] * J[1][1]) * inv;
  grad[2][0] = (J[1][2] * J[2][0] - J[1][0] * J[2][2]) * inv;
  grad[2][1] = (J[0][0] * J[2][2] - J[0][2] * J[2][0]) * inv;
  grad[2][2] = (J[0][2] * J[1][0] - J[0][0] * J[1][2]) * inv;
  grad[3][0] = (J[1][0] * J[2][1] - J[1][1] * J[2][0]) * inv;
  grad[3][1] = (J[0][1] * J[2][0] - J[0][0] * J[2][1]) * inv;
  grad[3][2] = (J[0][0] * J[1][1] - J[0][1] * J[1][0]) * inv;
  for (int i = 0; i < 3; ++i) grad[0][i] = -(grad[1][i] + grad[2][i] + grad[3][i]);
  return det / 6.0;
}
}  // namespace detail

KOKKOS_INLINE_FUNCTION double tetStiffness(const double x[4][3], double lambda, double mu, double Ke[12][12]) {
  double grad[4][3];
  const double V = detail::shapeGradients(x, grad);
  if (!(V > 0.0)) return V;
  // a(u, v) = int lambda div u div v + 2 mu eps(u):eps(v) with u = N_b e_j, v = N_a e_i:
  // V (lambda dN_a/dx_i dN_b/dx_j + mu dN_a/dx_j dN_b/dx_i + mu delta_ij grad N_a . grad N_b).
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const double dot = grad[a][0] * grad[b][0] + grad[a][1] * grad[b][1] + grad[a][2] * grad[b][2];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          Ke[3 * a + i][3 * b + j] =
              V * (lambda * grad[a][i] * grad[b][j] + mu * grad[a][j] * grad[b][i] + (i == j ? mu * dot : 0.0));
    }
  return V;
}

KOKKOS_INLINE_FUNCTION double triangleTraction(const double x[3][3], const double p[3], double fe[9]) {
  const double e1[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
  const double e2[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  const double area = 0.5 * Kokkos::Experimental::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  // Constant p against linear shape functions: each vertex gets area/3 * p.
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c) fe[3 * v + c] = area / 3.0 * p[c];
  return area;
}

KOKKOS_INLINE_FUNCTION double tetVolumeForce(const double x[4][3], const double b[3], double fe[12]) {
  double grad[4][3];
  const double V = detail::shapeGradients(x, grad);
  for (int v = 0; v < 4; ++v)
    for (int c = 0; c < 3; ++c) fe[3 * v + c] = V / 4.0 * b[c];
  return V;
}

KOKKOS_INLINE_FUNCTION double tetStress(const double x[4][3], const double u[12], double lambda, double mu,
                                        double eps[6], double sigma[6]) {
  double grad[4][3];
  const double V = detail::shapeGradients(x, grad);
  if (!(V > 0.0)) return V;
  // du_i/dx_j = sum_a u_ai dN_a/dx_j, constant over the element.
  double du[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) du[i][j] += u[3 * a + i] * grad[a][j];
  constexpr int row[6] = {0, 1, 2, 0, 1, 0}, col[6] = {0, 1, 2, 1, 2, 2};
  for (int k = 0; k < 6; ++k) eps[k] = 0.5 * (du[row[k]][col[k]] + du[col[k]][row[k]]);
  const double trace = eps[0] + eps[1] + eps[2];
  for (int k = 0; k < 6; ++k) sigma[k] = 2.0 * mu * eps[k] + (k < 3 ? lambda * trace : 0.0);
  return V;
}

KOKKOS_INLINE_FUNCTION double vonMisesStress(const double s[6]) {
  // 3 J2 = ((s11 - s22)^2 + (s22 - s33)^2 + (s33 - s11)^2) / 2 + 3 (s12^2 + s23^2 + s13^2).
  const double a = s[0] - s[1], b = s[1] - s[2], c = s[2] - s[0];
  const double threeJ2 = 0.5 * (a * a + b * b + c * c) + 3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
  return Kokkos::Experimental::sqrt(threeJ2);
}

KOKKOS_INLINE_FUNCTION double strainEnergyDensity(const double eps[6], const double sigma[6]) {
  // The off-diagonal components appear twice in the double contraction.
  return 0.5 * (eps[0] * sigma[0] + eps[1] * sigma[1] + eps[2] * sigma[2]) +
         (eps[3] * sigma[3] + eps[4] * sigma[4] + eps[5] * sigma[5]);
}

}  // namespace tribos::fem
