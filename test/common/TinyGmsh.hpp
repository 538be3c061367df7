#pragma once
// Small gmsh 4.1 ASCII meshes for reader tests, written the way gmsh writes them: unit
// cubes of 6 positive tetrahedra (Kuhn split around the diagonal from (0,0,0) to (1,1,1)) in
// one Physical Volume "cube" (tag 2), the two triangles of the first cube's face z = 0 in
// Physical Surface "bottom" (tag 1). Element tags: the triangles 1 and 2, then the tets from
// 3. Tests corrupt `nodes`, `tets` or the text.
#include <array>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace tribos::test {

struct TinyGmsh {
  std::vector<std::array<double, 3>> nodes;       ///< node tag = index + 1
  std::vector<std::array<long long, 4>> tets;     ///< node tags
  std::vector<std::array<long long, 3>> bottom;   ///< node tags

  /// One unit cube at x = shift (node tags 8 c + 1 .. 8 c + 8 for the c-th cube added).
  TinyGmsh& addCube(double shift = 0.0) {
    const long long first = static_cast<long long>(nodes.size()) + 1;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) nodes.push_back({shift + i, double(j), double(k)});
    // Corners by bits (x = 1, y = 2, z = 4); the tets 0 -> e_a -> e_a + e_b -> 7, the middle
    // two swapped for the odd permutations of the axes so that every tet is positive.
    const int middle[6][2] = {{1, 3}, {2, 6}, {4, 5}, {5, 1}, {3, 2}, {6, 4}};
    for (const auto& m : middle) tets.push_back({first, first + m[0], first + m[1], first + 7});
    if (bottom.empty()) bottom = {{first, first + 1, first + 3}, {first, first + 3, first + 2}};
    return *this;
  }

  std::string text() const {
    std::ostringstream out;
    out.precision(std::numeric_limits<double>::max_digits10);
    const size_t n = nodes.size(), t = tets.size(), b = bottom.size();
    out << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
        << "$PhysicalNames\n2\n2 1 \"bottom\"\n3 2 \"cube\"\n$EndPhysicalNames\n"
        << "$Entities\n0 0 1 1\n1 0 0 0 1 1 0 1 1 0\n1 0 0 0 1 1 1 1 2 0\n$EndEntities\n";
    out << "$Nodes\n1 " << n << " 1 " << n << "\n3 1 0 " << n << "\n";
    for (size_t i = 0; i < n; ++i) out << i + 1 << "\n";
    for (const auto& x : nodes) out << x[0] << " " << x[1] << " " << x[2] << "\n";
    out << "$EndNodes\n$Elements\n2 " << b + t << " 1 " << b + t << "\n2 1 2 " << b << "\n";
    for (size_t i = 0; i < b; ++i) out << i + 1 << " " << bottom[i][0] << " " << bottom[i][1] << " " << bottom[i][2] << "\n";
    out << "3 1 4 " << t << "\n";
    for (size_t i = 0; i < t; ++i)
      out << b + i + 1 << " " << tets[i][0] << " " << tets[i][1] << " " << tets[i][2] << " " << tets[i][3] << "\n";
    out << "$EndElements\n";
    return out.str();
  }
};

}  // namespace tribos::test
