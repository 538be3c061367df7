#pragma once
// Helpers shared by the fem unit tests: a small structured box mesh made here (so the
// element tests depend on nothing but Mesh), a Jacobi eigen solver and a dense solver.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace tribos::fem::testing {

/// Box [0, nx h] x [0, ny h] x [0, nz h], every cube cut into the 6 Kuhn tetrahedra around
/// its diagonal (the same cut in every cube, so the mesh is conforming). Interior nodes are
/// moved by up to jitter * h per component (seeded), so that elements are not all alike;
/// the faces stay planar. One block "box"; side sets "xmin", "xmax", "ymin", "ymax",
/// "zmin", "zmax" with their faces.
inline mesh::Mesh structuredBox(int nx, int ny, int nz, double h, double jitter = 0.0, unsigned seed = 1) {
  mesh::Mesh m;
  auto node = [&](int i, int j, int k) { return static_cast<LO>((k * (ny + 1) + j) * (nx + 1) + i); };
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-jitter * h, jitter * h);
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        std::array<double, 3> x{i * h, j * h, k * h};
        const bool interior = i > 0 && i < nx && j > 0 && j < ny && k > 0 && k < nz;
        for (int c = 0; c < 3; ++c) {
          const double d = shift(rng);  // drawn for every node: the field does not depend on nx
          if (interior) x[c] += d;
        }
        m.coords.push_back(x);
      }
  // Kuhn simplices: 0 -> e_a -> e_a + e_b -> (1,1,1) for the 6 orders (a, b, c) of the axes.
  const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& o : orders) {
          int p[3] = {i, j, k};
          std::array<LO, 4> t;
          t[0] = node(p[0], p[1], p[2]);
          for (int s = 0; s < 3; ++s) {
            ++p[o[s]];
            t[s + 1] = node(p[0], p[1], p[2]);
          }
          m.elements.add(mesh::ElementType::Tet4, t.data());
          const LO last = m.numElements() - 1;
          if (m.elementVolume(last) < 0.0) std::swap(m.elements.mutableNodes(last)[2], m.elements.mutableNodes(last)[3]);
        }
  m.blocks.push_back({"box", 1, 0, m.numElements()});
  const double extent[3] = {nx * h, ny * h, nz * h};
  const char* names[3][2] = {{"xmin", "xmax"}, {"ymin", "ymax"}, {"zmin", "zmax"}};
  for (int axis = 0; axis < 3; ++axis)
    for (int end = 0; end < 2; ++end) {
      mesh::SideSet set;
      set.name = names[axis][end];
      set.id = 2 * axis + end + 1;
      const double plane = end == 0 ? 0.0 : extent[axis];
      for (LO e = 0; e < m.numElements(); ++e)
        for (int side = 0; side < 4; ++side) {
          bool on = true;
          for (LO n : m.faceNodes(e, side)) on = on && m.coords[n][axis] == plane;
          if (on) {
            set.elements.push_back(e);
            set.sides.push_back(side);
          }
        }
      m.sideSets.push_back(set);
    }
  return m;
}

/// Dense copy of a CSR matrix (row-major n x n).
inline std::vector<double> toDense(const CsrMatrix& K) {
  std::vector<double> A(static_cast<size_t>(K.n) * K.n, 0.0);
  for (LO i = 0; i < K.n; ++i)
    for (LO k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k) A[static_cast<size_t>(i) * K.n + K.colInd[k]] = K.values[k];
  return A;
}

/// Eigenvalues (ascending) of a symmetric n x n row-major matrix by cyclic Jacobi rotations.
inline std::vector<double> symmetricEigenvalues(std::vector<double> A, int n) {
  auto a = [&](int i, int j) -> double& { return A[static_cast<size_t>(i) * n + j]; };
  double total = 0.0;
  for (double v : A) total += v * v;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0.0;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) off += a(p, q) * a(p, q);
    if (off <= 1e-34 * total) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        if (a(p, q) == 0.0) continue;
        // Rotation in the (p, q) plane that zeroes a(p, q) (Golub & Van Loan, 8.5).
        const double theta = (a(q, q) - a(p, p)) / (2.0 * a(p, q));
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < n; ++k) {
          const double akp = a(k, p), akq = a(k, q);
          a(k, p) = c * akp - s * akq;
          a(k, q) = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) {
          const double apk = a(p, k), aqk = a(q, k);
          a(p, k) = c * apk - s * aqk;
          a(q, k) = s * apk + c * aqk;
        }
      }
  }
  std::vector<double> ev(n);
  for (int i = 0; i < n; ++i) ev[i] = a(i, i);
  std::sort(ev.begin(), ev.end());
  return ev;
}

/// Solves A x = b (row-major n x n) by Gaussian elimination with partial pivoting.
inline std::vector<double> denseSolve(std::vector<double> A, std::vector<double> b) {
  const size_t n = b.size();
  for (size_t p = 0; p < n; ++p) {
    size_t pivot = p;
    for (size_t r = p + 1; r < n; ++r)
      if (std::abs(A[r * n + p]) > std::abs(A[pivot * n + p])) pivot = r;
    if (pivot != p) {
      for (size_t k = 0; k < n; ++k) std::swap(A[p * n + k], A[pivot * n + k]);
      std::swap(b[p], b[pivot]);
    }
    for (size_t r = p + 1; r < n; ++r) {
      const double f = A[r * n + p] / A[p * n + p];
      for (size_t k = p; k < n; ++k) A[r * n + k] -= f * A[p * n + k];
      b[r] -= f * b[p];
    }
  }
  std::vector<double> x(n);
  for (size_t p = n; p-- > 0;) {
    double s = b[p];
    for (size_t k = p + 1; k < n; ++k) s -= A[p * n + k] * x[k];
    x[p] = s / A[p * n + p];
  }
  return x;
}

}  // namespace tribos::fem::testing
