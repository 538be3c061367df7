#include "tribos/mesh/BoundaryFaces.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "tribos/core/Errors.hpp"

namespace tribos::mesh {

namespace {
/// A face by its sorted node ids, with the (element, side) it came from.
struct FaceUse {
  std::array<LO, 4> nodes;  ///< sorted vertices; a triangle's fourth is -1
  LO element;
  int side;
};

std::vector<FaceUse> allFaces(const Mesh& mesh) {
  std::vector<FaceUse> faces;
  faces.reserve(4 * static_cast<size_t>(mesh.numElements()));
  for (LO e = 0; e < mesh.numElements(); ++e)
    for (int side = 0; side < mesh.numSides(e); ++side) {
      FaceUse f{{-1, -1, -1, -1}, e, side};
      const FaceNodes face = mesh.faceNodes(e, side);
      std::copy_n(face.node, face.numVertices, f.nodes.begin());
      std::sort(f.nodes.begin(), f.nodes.begin() + face.numVertices);
      faces.push_back(f);
    }
  return faces;
}
}  // namespace

SideSet boundaryFaces(const Mesh& mesh) {
  // Sorting by the sorted vertices puts the two uses of an interior face next to each other;
  // a face that occurs once is on the boundary. O(n log n), no hashing.
  auto faces = allFaces(mesh);
  std::sort(faces.begin(), faces.end(), [](const FaceUse& a, const FaceUse& b) { return a.nodes < b.nodes; });
  std::vector<std::pair<LO, int>> boundary;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].nodes == faces[i].nodes) ++j;
    if (j == i + 1) boundary.push_back({faces[i].element, faces[i].side});
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  SideSet out;
  for (const auto& [element, side] : boundary) {
    out.elements.push_back(element);
    out.sides.push_back(side);
  }
  return out;
}

SideSet sideSetFromNodeSet(const Mesh& mesh, const NodeSet& nodes, const std::string& name, int id) {
  std::vector<char> inSet(mesh.numNodes(), 0);
  for (LO n : nodes.nodes)
    if (n >= 0 && n < mesh.numNodes()) inSet[n] = 1;
  const SideSet boundary = boundaryFaces(mesh);
  SideSet out{name, id, {}, {}};
  for (size_t f = 0; f < boundary.elements.size(); ++f) {
    bool all = true;
    for (LO n : mesh.faceNodes(boundary.elements[f], boundary.sides[f])) all = all && inSet[n];
    if (!all) continue;
    out.elements.push_back(boundary.elements[f]);
    out.sides.push_back(boundary.sides[f]);
  }
  return out;
}

namespace {
int findSideSet(const Mesh& mesh, const std::string& name) {
  for (size_t s = 0; s < mesh.sideSets.size(); ++s)
    if (mesh.sideSets[s].name == name) return static_cast<int>(s);
  return -1;
}
}  // namespace

int addSideSetFromNodeSet(Mesh& mesh, const std::string& nodeSet) {
  int id = 0;
  for (const auto& s : mesh.sideSets) id = std::max(id, s.id + 1);
  SideSet faces = sideSetFromNodeSet(mesh, mesh.nodeSet(nodeSet), nodeSet, id);
  core::requireInput(!faces.elements.empty(), "node set \"" + nodeSet +
                                                  "\" contains no boundary face (a face of one element with all "
                                                  "its nodes in the set), so it cannot stand for a surface");
  for (const std::string& name : {nodeSet, nodeSet + "_faces"}) {
    const int existing = findSideSet(mesh, name);
    if (existing < 0) {
      faces.name = name;
      mesh.sideSets.push_back(std::move(faces));
      return static_cast<int>(mesh.sideSets.size()) - 1;
    }
    const auto& other = mesh.sideSets[existing];
    if (other.elements == faces.elements && other.sides == faces.sides) return existing;
  }
  throw core::InputError("node set \"" + nodeSet + "\": the side sets \"" + nodeSet + "\" and \"" + nodeSet +
                         "_faces\" exist with other faces; rename one to use the node set as a surface");
}

int requireSideSet(Mesh& mesh, const std::string& name) {
  if (const int existing = findSideSet(mesh, name); existing >= 0) return existing;
  const bool hasNodeSet = std::any_of(mesh.nodeSets.begin(), mesh.nodeSets.end(),
                                      [&](const NodeSet& n) { return n.name == name; });
  if (!hasNodeSet) {
    try {
      mesh.sideSet(name);  // throws, listing the side sets
    } catch (const core::InputError& e) {
      throw core::InputError(std::string(e.what()) + " (nor a node set of that name to take the faces from)");
    }
  }
  return addSideSetFromNodeSet(mesh, name);
}

}  // namespace tribos::mesh
