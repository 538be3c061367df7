#include "SymmetricEigen.hpp"

#include <cmath>

namespace tribos::feti {

std::vector<double> symmetricEigen(std::vector<double>& A, int n, std::vector<double>& vectors) {
  vectors.assign(static_cast<size_t>(n) * n, 0.0);
  for (int i = 0; i < n; ++i) vectors[static_cast<size_t>(i) * n + i] = 1.0;
  const auto at = [&](std::vector<double>& M, int i, int j) -> double& { return M[static_cast<size_t>(i) * n + j]; };
  double frobenius = 0.0;
  for (double v : A) frobenius += v * v;
  for (int sweep = 0; sweep < 100; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += at(A, p, q) * at(A, p, q);
    if (off <= 1e-32 * frobenius) break;  // off-diagonal at round-off: converged (or A = 0)
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        const double apq = at(A, p, q);
        if (apq == 0.0) continue;
        // The rotation (c, s) that zeroes A(p, q): t = tan of its angle, the smaller root.
        const double theta = (at(A, q, q) - at(A, p, p)) / (2.0 * apq);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::hypot(theta, 1.0));
        const double c = 1.0 / std::hypot(t, 1.0), s = t * c;
        for (int k = 0; k < n; ++k) {  // A := A J, V := V J
          const double akp = at(A, k, p), akq = at(A, k, q);
          at(A, k, p) = c * akp - s * akq;
          at(A, k, q) = s * akp + c * akq;
          const double vkp = at(vectors, k, p), vkq = at(vectors, k, q);
          at(vectors, k, p) = c * vkp - s * vkq;
          at(vectors, k, q) = s * vkp + c * vkq;
        }
        for (int k = 0; k < n; ++k) {  // A := J^T A
          const double apk = at(A, p, k), aqk = at(A, q, k);
          at(A, p, k) = c * apk - s * aqk;
          at(A, q, k) = s * apk + c * aqk;
        }
      }
  }
  std::vector<double> values(n);
  for (int i = 0; i < n; ++i) values[i] = at(A, i, i);
  return values;
}


}  // namespace tribos::feti
