#pragma once
// Test helpers: random SPD matrices with the sparsity of 3D elasticity and random vectors (the
// factorisation and coarse-solve tests).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::test {

/// A random SPD matrix with the graph of 3D elasticity on an m^3 grid: 3 dofs per node,
/// 27-point node stencil, random symmetric off-diagonal values in [-1, 1] and a diagonal
/// that dominates strictly (so SPD by Gershgorin) with a margin `shift`.
inline fem::CsrMatrix randomSpd(int m, double shift, unsigned seed) {
  const int dofs = 3 * m * m * m;
  auto symmetricValue = [seed](int i, int j) {
    // Same value for (i, j) and (j, i): a splitmix64 hash of the unordered pair, in [-1, 1].
    std::uint64_t z = (static_cast<std::uint64_t>(seed) << 42) ^ (static_cast<std::uint64_t>(std::min(i, j)) << 21) ^
                      static_cast<std::uint64_t>(std::max(i, j));
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return 2.0 * static_cast<double>(z >> 11) / 9007199254740992.0 - 1.0;
  };
  fem::CsrMatrix A;
  A.n = dofs;
  A.rowPtr.push_back(0);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i)
        for (int c = 0; c < 3; ++c) {
          const int row = 3 * (i + m * (j + m * k)) + c;
          std::vector<int> cols;
          for (int dk = -1; dk <= 1; ++dk)
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di) {
                const int a = i + di, b = j + dj, e = k + dk;
                if (a < 0 || b < 0 || e < 0 || a >= m || b >= m || e >= m) continue;
                for (int d = 0; d < 3; ++d) cols.push_back(3 * (a + m * (b + m * e)) + d);
              }
          std::sort(cols.begin(), cols.end());
          double offSum = 0.0;
          const size_t diagAt = A.colInd.size() + (std::find(cols.begin(), cols.end(), row) - cols.begin());
          for (int col : cols) {
            const double v = col == row ? 0.0 : symmetricValue(row, col);
            offSum += std::abs(v);
            A.colInd.push_back(col);
            A.values.push_back(v);
          }
          A.values[diagAt] = offSum + shift;
          A.rowPtr.push_back(static_cast<LO>(A.colInd.size()));
        }
  return A;
}

/// n values uniform in [-1, 1] from a seeded Mersenne twister.
inline std::vector<double> randomVector(size_t n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  std::vector<double> v(n);
  for (double& x : v) x = dist(gen);
  return v;
}

}  // namespace tribos::test
