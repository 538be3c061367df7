#include "tribos/mesh/TwoBricks.hpp"

#include <algorithm>
#include <cstdlib>
#include <limits>

#include "tribos/core/Errors.hpp"

namespace tribos::mesh {

BrickGrid BrickGrid::parse(const std::string& text, const std::string& parameter) {
  BrickGrid g;
  int* parts[3] = {&g.nx, &g.ny, &g.nz};
  size_t pos = 0;
  for (int d = 0; d < 3; ++d) {
    const size_t end = d < 2 ? text.find('x', pos) : text.size();
    const std::string item = end == std::string::npos ? "" : text.substr(pos, end - pos);
    // Digits only: strtol alone would also accept " 2", "+2" or "2 ", which the strict
    // "<int>x<int>x<int>" syntax rejects. The cap keeps nx*H/h etc. far from int overflow.
    const bool digits = !item.empty() && item.size() <= 6 &&
                        std::all_of(item.begin(), item.end(), [](char c) { return c >= '0' && c <= '9'; });
    const long v = digits ? std::strtol(item.c_str(), nullptr, 10) : 0;
    if (!digits || v < 1 || v > 100000)
      throw core::InputError(parameter + ": \"" + text + "\" is not a subdomain grid \"NXxNYxNZ\" of positive integers");
    *parts[d] = static_cast<int>(v);
    pos = end + 1;
  }
  return g;
}

namespace {
// Cube corners v = (i&1, (i>>1)&1, (i>>2)&1). The 5-tet split keeps one "central" tet whose
// 4 vertices are pairwise joined by face diagonals and cuts off the 4 other corners. The
// even split uses the central set {0,3,5,6}, the odd split {1,2,4,7}; alternating with the
// parity of i+j+k makes the face diagonals of neighbouring cubes coincide (conformity).
constexpr int kEvenSplit[5][4] = {{0, 3, 5, 6}, {1, 0, 3, 5}, {2, 0, 3, 6}, {4, 0, 5, 6}, {7, 3, 5, 6}};
constexpr int kOddSplit[5][4] = {{1, 2, 4, 7}, {0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}};

struct Brick {
  int ex, ey, ez;          // cubes per direction
  double z0;               // bottom of the brick
  LO firstNode;
  LO node(int i, int j, int k) const { return firstNode + i + (ex + 1) * (j + (ey + 1) * k); }
  LO numNodes() const { return (ex + 1) * (ey + 1) * (ez + 1); }
};

double signedVolume(const Mesh& m, const std::array<LO, 4>& t) {
  const auto& a = m.coords[t[0]];
  double e[3][3];
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c) e[v][c] = m.coords[t[v + 1]][c] - a[c];
  return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) - e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
          e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
         6.0;
}
}  // namespace

namespace {
/// The checks of the spec: H/h >= 1, cubic subdomains, ids that fit LO, gap >= 0.
void checkTwoBricksSpec(const TwoBricksSpec& spec) {
  const BrickGrid& g = spec.subdomainsPerBrick;
  const int m = spec.hOverH;
  core::requireInput(m >= 1, "Mesh/H Over h: must be >= 1, got " + std::to_string(m));
  // Cubic subdomains: 20/nx == 10/ny == 10/nz.
  core::requireInput(g.ny >= 1 && g.nx == 2 * g.ny && g.ny == g.nz,
                     "Mesh/Subdomains Per Brick: the subdomains of the (20 x 10 x 10) bricks must be cubes, i.e. "
                     "NX = 2 NY = 2 NZ (e.g. 2x1x1, 4x2x2), got " +
                         std::to_string(g.nx) + "x" + std::to_string(g.ny) + "x" + std::to_string(g.nz));
  // Element and node ids are LO (int): refuse grids whose 2 * 5 (nx m)(ny m)(nz m) tets
  // would overflow it (memory would run out long before, but fail with a clear message).
  // (In double: the factors may be as large as 1e5 each.)
  const double cubes = static_cast<double>(g.nx) * m * g.ny * m * g.nz * m;
  core::requireInput(10.0 * cubes <= std::numeric_limits<LO>::max(),
                     "Mesh/Subdomains Per Brick and Mesh/H Over h: " + std::to_string(g.nx) + "x" +
                         std::to_string(g.ny) + "x" + std::to_string(g.nz) + " subdomains with H/h = " +
                         std::to_string(m) + " give more tetrahedra than a 32-bit index can count");
  core::requireInput(spec.gap >= 0.0, "Mesh/Initial Gap: must be >= 0, got " + std::to_string(spec.gap));
}

/// The tetrahedra of one brick as one element block: five per cube, the split alternating
/// with the parity of the cube (conforming face diagonals), positively oriented.
void addBrickElements(Mesh& mesh, const Brick& br, const char* name, int id) {
  ElementBlock block{name, id, mesh.numElements(), 0};
  for (int k = 0; k < br.ez; ++k)
    for (int j = 0; j < br.ey; ++j)
      for (int i = 0; i < br.ex; ++i) {
        LO corner[8];
        for (int v = 0; v < 8; ++v) corner[v] = br.node(i + (v & 1), j + ((v >> 1) & 1), k + ((v >> 2) & 1));
        const auto& split = (i + j + k) % 2 == 0 ? kEvenSplit : kOddSplit;
        for (const auto& t : split) {
          std::array<LO, 4> tet{corner[t[0]], corner[t[1]], corner[t[2]], corner[t[3]]};
          if (signedVolume(mesh, tet) < 0.0) std::swap(tet[2], tet[3]);
          mesh.elements.add(ElementType::Tet4, tet.data());
        }
      }
  block.count = mesh.numElements() - block.first;
  mesh.blocks.push_back(block);
}

/// A boundary part: (name, brick, axis, plane at the upper or lower end of the axis).
struct BoundaryPart {
  const char* name;
  int brick, axis;
  bool upper;
};

/// The node set and side set of a part: the faces of its brick whose 3 vertices lie on the
/// plane (tested on grid indices, not on floating-point coordinates).
void addBoundaryPart(Mesh& mesh, const Brick (&bricks)[2], const BoundaryPart& part, int id) {
  auto onPlane = [&](LO node) {
    const Brick& br = bricks[part.brick];
    const LO local = node - br.firstNode;
    if (local < 0 || local >= br.numNodes()) return false;
    const int idx[3] = {local % (br.ex + 1), (local / (br.ex + 1)) % (br.ey + 1), local / ((br.ex + 1) * (br.ey + 1))};
    const int extent[3] = {br.ex, br.ey, br.ez};
    return idx[part.axis] == (part.upper ? extent[part.axis] : 0);
  };
  NodeSet ns{part.name, id, {}};
  SideSet ss{part.name, id, {}, {}};
  const ElementBlock& block = mesh.blocks[part.brick];
  for (LO e = block.first; e < block.first + block.count; ++e)
    for (int side = 0; side < 4; ++side) {
      const FaceNodes face = mesh.faceNodes(e, side);
      bool all = true;
      for (LO n : face) all = all && onPlane(n);
      if (!all) continue;
      ss.elements.push_back(e);
      ss.sides.push_back(side);
      ns.nodes.insert(ns.nodes.end(), face.begin(), face.end());
    }
  std::sort(ns.nodes.begin(), ns.nodes.end());
  ns.nodes.erase(std::unique(ns.nodes.begin(), ns.nodes.end()), ns.nodes.end());
  mesh.nodeSets.push_back(std::move(ns));
  mesh.sideSets.push_back(std::move(ss));
}
}  // namespace

Mesh generateTwoBricks(const TwoBricksSpec& spec) {
  checkTwoBricksSpec(spec);
  const BrickGrid& g = spec.subdomainsPerBrick;
  const int m = spec.hOverH;
  const double h = 20.0 / (g.nx * m);
  Mesh mesh;
  Brick bricks[2];
  for (int b = 0; b < 2; ++b) {
    bricks[b] = {g.nx * m, g.ny * m, g.nz * m, b == 0 ? 0.0 : 10.0 + spec.gap, b == 0 ? 0 : bricks[0].numNodes()};
    const Brick& br = bricks[b];
    for (int k = 0; k <= br.ez; ++k)
      for (int j = 0; j <= br.ey; ++j)
        for (int i = 0; i <= br.ex; ++i) mesh.coords.push_back({i * h, j * h, br.z0 + k * h});
  }
  const char* names[2] = {"aluminium", "steel"};
  for (int b = 0; b < 2; ++b) addBrickElements(mesh, bricks[b], names[b], b + 1);
  const BoundaryPart parts[6] = {{"dirichlet_aluminium", 0, 0, false}, {"dirichlet_steel", 1, 0, false},
                                 {"contact_aluminium", 0, 2, true},    {"contact_steel", 1, 2, false},
                                 {"load_end", 1, 0, true},             {"load_top", 1, 2, true}};
  for (int p = 0; p < 6; ++p) addBoundaryPart(mesh, bricks, parts[p], p + 1);
  mesh.validate("two-bricks generator");
  return mesh;
}

std::vector<int> structuredPartition(const Mesh& mesh, const TwoBricksSpec& spec) {
  const BrickGrid& g = spec.subdomainsPerBrick;
  const int m = spec.hOverH;
  const int ex = g.nx * m, ey = g.ny * m, ez = g.nz * m;
  const LO perBrick = 5 * ex * ey * ez;
  if (mesh.numElements() != 2 * perBrick)
    throw core::InputError("structured partition: the mesh is not the two-brick mesh of this grid");
  std::vector<int> part(mesh.numElements());
  for (LO e = 0; e < mesh.numElements(); ++e) {
    const int brick = e / perBrick;
    const LO cube = (e % perBrick) / 5;  // elements are generated cube by cube, x fastest
    const int i = cube % ex, j = (cube / ex) % ey, k = cube / (ex * ey);
    part[e] = brick * g.count() + (i / m) + g.nx * ((j / m) + g.ny * (k / m));
  }
  return part;
}

}  // namespace tribos::mesh
