#include "BoxMesh.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

namespace tribos::test {

namespace {
// Kuhn split: the 6 tets 0 -> e_a -> e_a + e_b -> (1,1,1) for the permutations (a, b, c) of
// the axes, corners numbered by bits (x = 1, y = 2, z = 4).
constexpr int kAxisOrders[6][2] = {{0, 1}, {0, 2}, {1, 0}, {1, 2}, {2, 0}, {2, 1}};

double signedVolume(const mesh::Mesh& m, const std::array<LO, 4>& t) {
  const auto& a = m.coords[t[0]];
  double e[3][3];
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c) e[v][c] = m.coords[t[v + 1]][c] - a[c];
  return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
          e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}

int maxId(const std::vector<mesh::ElementBlock>& v) {
  int m = 0;
  for (const auto& x : v) m = std::max(m, x.id);
  return m;
}
template <class Set>
int maxSetId(const std::vector<Set>& v) {
  int m = 0;
  for (const auto& x : v) m = std::max(m, x.id);
  return m;
}
}  // namespace

mesh::Mesh boxMesh(std::array<double, 3> origin, std::array<double, 3> size, std::array<int, 3> cells,
                   const std::string& blockName, CellElements fill) {
  for (int d = 0; d < 3; ++d)
    if (cells[d] < 1 || !(size[d] > 0.0)) throw std::invalid_argument("boxMesh: cells >= 1 and size > 0 needed");
  const int nx = cells[0], ny = cells[1], nz = cells[2];
  auto node = [&](int i, int j, int k) { return static_cast<LO>(i + (nx + 1) * (j + (ny + 1) * k)); };
  mesh::Mesh m;
  std::map<std::pair<LO, LO>, LO> midNode;  // edge (ascending ends) -> its mid-edge node
  std::vector<std::pair<LO, LO>> midEnds;   // mid-edge node - grid nodes -> its edge's ends
  auto middle = [&](LO a, LO b) {
    const auto [it, inserted] = midNode.insert({std::minmax(a, b), m.numNodes()});
    if (inserted) {
      std::array<double, 3> x;
      for (int c = 0; c < 3; ++c) x[c] = (m.coords[a][c] + m.coords[b][c]) / 2;
      m.coords.push_back(x);
      midEnds.push_back({a, b});
    }
    return it->second;
  };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        m.coords.push_back({origin[0] + size[0] * i / nx, origin[1] + size[1] * j / ny, origin[2] + size[2] * k / nz});
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        LO corner[8];
        for (int v = 0; v < 8; ++v) corner[v] = node(i + (v & 1), j + ((v >> 1) & 1), k + ((v >> 2) & 1));
        // Exodus order: the bottom face counter-clockwise, then the top one.
        const LO hex[8] = {corner[0], corner[1], corner[3], corner[2], corner[4], corner[5], corner[7], corner[6]};
        if (fill == CellElements::Hexahedron) {
          m.elements.add(mesh::ElementType::Hex8, hex);
          continue;
        }
        if (fill == CellElements::TwoPrisms) {
          m.elements.add(mesh::ElementType::Wedge6, {hex[0], hex[1], hex[2], hex[4], hex[5], hex[6]});
          m.elements.add(mesh::ElementType::Wedge6, {hex[0], hex[2], hex[3], hex[4], hex[6], hex[7]});
          continue;
        }
        for (const auto& order : kAxisOrders) {
          const int first = 1 << order[0], second = first | (1 << order[1]);
          std::array<LO, 4> tet{corner[0], corner[first], corner[second], corner[7]};
          if (signedVolume(m, tet) < 0.0) std::swap(tet[2], tet[3]);
          if (fill == CellElements::QuadraticKuhnTetrahedra) {  // Exodus mid-edge order
            m.elements.add(mesh::ElementType::Tet10,
                           {tet[0], tet[1], tet[2], tet[3], middle(tet[0], tet[1]), middle(tet[1], tet[2]),
                            middle(tet[2], tet[0]), middle(tet[0], tet[3]), middle(tet[1], tet[3]),
                            middle(tet[2], tet[3])});
            continue;
          }
          m.elements.add(mesh::ElementType::Tet4, tet.data());
        }
      }
  m.blocks.push_back({blockName, 1, 0, m.numElements()});

  // Faces: a node is on face (axis, upper) when its grid index along axis is 0 or n
  // (integer test, no floating-point comparison); a mid-edge node when both ends of its edge are.
  const LO gridNodes = (nx + 1) * (ny + 1) * (nz + 1);
  auto onPlane = [&](LO n, int axis, int plane) {
    auto index = [&](LO g) {
      const int idx[3] = {g % (nx + 1), (g / (nx + 1)) % (ny + 1), g / ((nx + 1) * (ny + 1))};
      return idx[axis];
    };
    if (n < gridNodes) return index(n) == plane;
    const auto& ends = midEnds[n - gridNodes];
    return index(ends.first) == plane && index(ends.second) == plane;
  };
  int id = 1;
  for (int axis = 0; axis < 3; ++axis)
    for (int upper = 0; upper < 2; ++upper, ++id) {
      const std::string name = blockName + "_" + "xyz"[axis] + (upper ? "1" : "0");
      const int plane = upper ? cells[axis] : 0;
      mesh::NodeSet ns{name, id, {}};
      mesh::SideSet ss{name, id, {}, {}};
      for (LO n = 0; n < m.numNodes(); ++n)
        if (onPlane(n, axis, plane)) ns.nodes.push_back(n);
      for (LO e = 0; e < m.numElements(); ++e)
        for (int side = 0; side < m.numSides(e); ++side) {
          bool all = true;
          for (LO n : m.faceNodes(e, side)) all = all && onPlane(n, axis, plane);
          if (!all) continue;
          ss.elements.push_back(e);
          ss.sides.push_back(side);
        }
      m.nodeSets.push_back(std::move(ns));
      m.sideSets.push_back(std::move(ss));
    }
  return m;
}

mesh::Mesh mergeMeshes(const mesh::Mesh& a, const mesh::Mesh& b) {
  mesh::Mesh m = a;
  const LO nodeShift = a.numNodes(), elementShift = a.numElements();
  const int blockShift = maxId(a.blocks), nodeSetShift = maxSetId(a.nodeSets), sideSetShift = maxSetId(a.sideSets);
  m.coords.insert(m.coords.end(), b.coords.begin(), b.coords.end());
  for (LO e = 0; e < b.numElements(); ++e) {
    LO nodes[mesh::kMaxElementNodes];
    int count = 0;
    for (LO n : b.elementNodes(e)) nodes[count++] = n + nodeShift;
    m.elements.add(b.elementType(e), nodes);
  }
  for (auto block : b.blocks) {
    block.first += elementShift;
    block.id += blockShift;
    m.blocks.push_back(block);
  }
  for (auto set : b.nodeSets) {
    for (LO& n : set.nodes) n += nodeShift;
    set.id += nodeSetShift;
    m.nodeSets.push_back(std::move(set));
  }
  for (auto set : b.sideSets) {
    for (LO& e : set.elements) e += elementShift;
    set.id += sideSetShift;
    m.sideSets.push_back(std::move(set));
  }
  return m;
}

}  // namespace tribos::test
