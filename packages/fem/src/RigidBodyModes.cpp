#include <cmath>
#include <stdexcept>
#include <string>

#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::fem {

std::vector<double> rigidBodyModes(const std::vector<std::array<double, 3>>& coords) {
  // Kernel of a floating body's stiffness (paper Section 4.1): 3 translations and 3
  // rotations about the centroid (centring keeps the Gram-Schmidt well conditioned).
  const size_t nodes = coords.size(), n = 3 * nodes;
  double c[3] = {0, 0, 0};
  for (const auto& x : coords)
    for (int d = 0; d < 3; ++d) c[d] += x[d] / static_cast<double>(nodes);
  std::vector<double> R(6 * n, 0.0);
  for (size_t k = 0; k < nodes; ++k) {
    const double x = coords[k][0] - c[0], y = coords[k][1] - c[1], z = coords[k][2] - c[2];
    for (int d = 0; d < 3; ++d) R[d * n + 3 * k + d] = 1.0;
    R[3 * n + 3 * k + 1] = -z;  // rotation about x: (0, -z, y)
    R[3 * n + 3 * k + 2] = y;
    R[4 * n + 3 * k + 0] = z;   // about y: (z, 0, -x)
    R[4 * n + 3 * k + 2] = -x;
    R[5 * n + 3 * k + 0] = -y;  // about z: (-y, x, 0)
    R[5 * n + 3 * k + 1] = x;
  }
  // Modified Gram-Schmidt, twice ("twice is enough"): one pass leaves R^T R - I of the
  // order of eps * cond(R), a second one brings it to round-off, which T-FETI relies on
  // (G = R^T B^T and the Moore-Penrose action I - R R^T, ALGORITHMS.md 1).
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j < 6; ++j) {
      double* rj = &R[j * n];
      double before = 0.0;
      for (size_t k = 0; k < n; ++k) before += rj[k] * rj[k];
      for (int i = 0; i < j; ++i) {
        const double* ri = &R[i * n];
        double dot = 0.0;
        for (size_t k = 0; k < n; ++k) dot += ri[k] * rj[k];
        for (size_t k = 0; k < n; ++k) rj[k] -= dot * ri[k];
      }
      double norm = 0.0;
      for (size_t k = 0; k < n; ++k) norm += rj[k] * rj[k];
      // Collinear (or fewer than 3) nodes: a rotation is a combination of the others.
      if (!(norm > 1e-20 * before))
        throw std::invalid_argument("tribos::fem::rigidBodyModes: the " + std::to_string(nodes) +
                                    " nodes are collinear; the 6 rigid body modes are dependent");
      norm = std::sqrt(norm);
      for (size_t k = 0; k < n; ++k) rj[k] /= norm;
    }
  return R;
}

}  // namespace tribos::fem
