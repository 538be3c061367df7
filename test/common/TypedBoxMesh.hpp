#pragma once
// A cube [0, n h]^3 of n^3 cells meshed with one element type (or two), for the element
// tests: 8-node hexahedra; each cell cut into two 6-node prisms along the diagonal of its
// xy face; the 6 Kuhn tetrahedra of each cell (linear, or with straight mid-edge nodes);
// hexahedra in the cells with i < n/2 and prisms in the others (the two meet on whole
// quadrilateral faces, so the mesh is conforming). Interior grid nodes are moved by up to
// jitter * h per component (seeded): the hexahedra are then not parallelepipeds. Mid-edge
// nodes sit at the middle of their edge. One block "cube"; no sets.
#include <algorithm>
#include <array>
#include <map>
#include <random>
#include <utility>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::test {

enum class BoxElements { Tet4, Tet10, Hex8, Wedge6, HexAndWedge };

inline mesh::Mesh typedBox(BoxElements kind, int n, double h, double jitter = 0.0, unsigned seed = 1) {
  using mesh::ElementType;
  mesh::Mesh m;
  auto node = [&](int i, int j, int k) { return static_cast<LO>((k * (n + 1) + j) * (n + 1) + i); };
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-jitter * h, jitter * h);
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        std::array<double, 3> x{i * h, j * h, k * h};
        const bool interior = i > 0 && i < n && j > 0 && j < n && k > 0 && k < n;
        for (int c = 0; c < 3; ++c) {
          const double d = shift(rng);
          if (interior) x[c] += d;
        }
        m.coords.push_back(x);
      }
  std::map<std::pair<LO, LO>, LO> midNode;
  auto middle = [&](LO a, LO b) {
    const auto key = std::minmax(a, b);
    const auto [it, inserted] = midNode.insert({key, m.numNodes()});
    if (inserted) {
      std::array<double, 3> x;
      for (int c = 0; c < 3; ++c) x[c] = (m.coords[a][c] + m.coords[b][c]) / 2;
      m.coords.push_back(x);
    }
    return it->second;
  };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        // Corners in Exodus HEX8 order: the bottom face counter-clockwise, then the top.
        const LO c[8] = {node(i, j, k),         node(i + 1, j, k),         node(i + 1, j + 1, k),
                         node(i, j + 1, k),     node(i, j, k + 1),         node(i + 1, j, k + 1),
                         node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)};
        const bool hex = kind == BoxElements::Hex8 || (kind == BoxElements::HexAndWedge && 2 * i < n);
        if (hex) {
          m.elements.add(ElementType::Hex8, c);
        } else if (kind == BoxElements::Wedge6 || kind == BoxElements::HexAndWedge) {
          m.elements.add(ElementType::Wedge6, {c[0], c[1], c[2], c[4], c[5], c[6]});
          m.elements.add(ElementType::Wedge6, {c[0], c[2], c[3], c[4], c[6], c[7]});
        } else {
          // Kuhn: 0 -> e_a -> e_a + e_b -> (1,1,1); bits x = 1, y = 2, z = 4 index `corner`.
          const LO corner[8] = {c[0], c[1], c[3], c[2], c[4], c[5], c[7], c[6]};
          const int orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
          for (const auto& o : orders) {
            const int first = 1 << o[0], second = first | (1 << o[1]);
            std::array<LO, 4> t{corner[0], corner[first], corner[second], corner[7]};
            mesh::Mesh probe;
            for (LO v : t) probe.coords.push_back(m.coords[v]);
            probe.elements.add(ElementType::Tet4, {0, 1, 2, 3});
            if (probe.elementVolume(0) < 0.0) std::swap(t[2], t[3]);
            if (kind == BoxElements::Tet4) {
              m.elements.add(ElementType::Tet4, t.data());
              continue;
            }
            // Exodus TETRA10 mid-edge order: (0,1) (1,2) (2,0) (0,3) (1,3) (2,3).
            m.elements.add(ElementType::Tet10, {t[0], t[1], t[2], t[3], middle(t[0], t[1]), middle(t[1], t[2]),
                                                middle(t[2], t[0]), middle(t[0], t[3]), middle(t[1], t[3]),
                                                middle(t[2], t[3])});
          }
        }
      }
  m.blocks.push_back({"cube", 1, 0, m.numElements()});
  return m;
}

}  // namespace tribos::test
