#include "tribos/mesh/Mesh.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/mesh/MeshFaces.hpp"
#include "tribos/mesh/ShapeFunctions.hpp"

namespace tribos::mesh {

namespace {
size_t entries(const NodeSet& s) { return s.nodes.size(); }
size_t entries(const SideSet& s) { return s.elements.size(); }
size_t entries(const ElementBlock& b) { return static_cast<size_t>(b.count); }

/// "the mesh" or "the mesh (file.exo)".
std::string theMesh(const std::string& file) { return file.empty() ? "the mesh" : "the mesh (" + file + ")"; }

/// The entity named `name`. A set or block that is used must hold something: an empty one
/// would silently restrain, load or couple nothing.
template <class Set>
const Set& findByName(const std::vector<Set>& sets, const std::string& name, const char* kind,
                      const std::string& file) {
  for (const auto& s : sets) {
    if (s.name != name) continue;
    if (entries(s) == 0)
      throw core::InputError(std::string(kind) + " \"" + name + "\" of " + theMesh(file) + " is empty");
    return s;
  }
  std::ostringstream msg;
  msg << theMesh(file) << " has no " << kind << " named \"" << name << "\"; it has:";
  for (const auto& s : sets) msg << " \"" << s.name << "\"";
  if (sets.empty()) msg << " none";
  throw core::InputError(msg.str());
}
}  // namespace

int Mesh::blockOf(LO element) const {
  for (int b = 0; b < numBlocks(); ++b)
    if (element >= blocks[b].first && element < blocks[b].first + blocks[b].count) return b;
  return -1;
}

int Mesh::blockIndex(const std::string& name) const {
  const auto& block = findByName(blocks, name, "element block", file);
  return static_cast<int>(&block - blocks.data());
}

const NodeSet& Mesh::nodeSet(const std::string& name) const {
  return findByName(nodeSets, name, "node set", file);
}

const SideSet& Mesh::sideSet(const std::string& name) const {
  return findByName(sideSets, name, "side set", file);
}

namespace {
/// The coordinates of an element's nodes, as the shape functions take them.
void elementCoordinates(const Mesh& mesh, LO element, double x[][3]) {
  const ElementNodes nodes = mesh.elementNodes(element);
  for (int k = 0; k < nodes.size(); ++k)
    for (int c = 0; c < 3; ++c) x[k][c] = mesh.coords[nodes[k]][c];
}
}  // namespace

double Mesh::elementVolume(LO element) const {
  if (!elementShape(elementType(element)).linearSimplex) {
    double x[kMaxElementNodes][3];
    elementCoordinates(*this, element, x);
    return elementMeasure(elementType(element), x).volume;
  }
  const auto t = elementNodes(element);
  const auto& a = coords[t[0]];
  double e[3][3];
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c) e[v][c] = coords[t[v + 1]][c] - a[c];
  const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return det / 6.0;
}

std::string Mesh::elementLabel(LO element) const {
  const bool numbered = static_cast<size_t>(element) < elementNumbers.size();
  const int b = blockOf(element);
  return "element " + std::to_string(numbered ? elementNumbers[element] : element + 1LL) +
         (b >= 0 ? " of block \"" + blocks[b].name + "\"" : std::string());
}

double Mesh::longestEdge(LO element) const {
  const auto t = elementNodes(element);
  const int vertices = elementShape(elementType(element)).numVertices;
  double longest = 0.0;
  for (int a = 0; a < vertices; ++a)
    for (int b = a + 1; b < vertices; ++b) {
      double squared = 0.0;
      for (int c = 0; c < 3; ++c) squared += (coords[t[a]][c] - coords[t[b]][c]) * (coords[t[a]][c] - coords[t[b]][c]);
      longest = std::max(longest, squared);
    }
  return std::sqrt(longest);
}

std::array<double, 3> Mesh::faceNormal(LO element, int side) const {
  const FaceNodes face = faceNodes(element, side);
  const auto& a = coords[face.node[0]];
  const auto& b = coords[face.node[1]];
  const auto& c = coords[face.node[2]];
  double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  if (face.numVertices == 4) {  // the diagonals: (c - a) x (d - b)
    const auto& d = coords[face.node[3]];
    for (int k = 0; k < 3; ++k) {
      e1[k] = c[k] - a[k];
      e2[k] = d[k] - b[k];
    }
  }
  return {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
}

namespace {
using Fail = std::function<void(const std::string&)>;

void requireContiguousBlocks(const Mesh& mesh, const Fail& fail) {
  LO next = 0;
  for (const auto& b : mesh.blocks) {
    if (b.first != next || b.count < 0 || b.count > mesh.numElements() - next)
      fail("element block \"" + b.name + "\" is not contiguous with the previous block");
    if (b.count == 0) fail("element block \"" + b.name + "\" (id " + std::to_string(b.id) + ") has no elements");
    next += b.count;
  }
  if (next != mesh.numElements()) fail("element blocks do not cover all elements");
}

void requireFiniteCoordinates(const Mesh& mesh, const Fail& fail) {
  for (LO n = 0; n < mesh.numNodes(); ++n)
    for (double x : mesh.coords[n])
      if (!std::isfinite(x)) fail("node " + std::to_string(n + 1) + " has a coordinate that is not finite: " +
                                  core::formatPoint(mesh.coords[n]));
}

void requireValidElements(const Mesh& mesh, const Fail& fail) {
  for (LO e = 0; e < mesh.numElements(); ++e) {
    for (LO n : mesh.elementNodes(e))
      if (n < 0 || n >= mesh.numNodes())
        fail(mesh.elementLabel(e) + " references node " + std::to_string(n + 1) + " out of range 1.." +
             std::to_string(mesh.numNodes()));
    const double volume = mesh.elementVolume(e), edge = mesh.longestEdge(e);
    const double tiny = kDegenerateVolumeRatio * edge * edge * edge;
    if (std::abs(volume) <= tiny)
      fail(mesh.elementLabel(e) + " is degenerate (volume " + core::formatNumber(volume) + " for a longest edge of " +
           core::formatNumber(edge) + ")");
    if (volume < 0.0) fail(mesh.elementLabel(e) + " is inverted (volume " + core::formatNumber(volume) + ")");
    if (elementShape(mesh.elementType(e)).linearSimplex) continue;  // its Jacobian is constant: the volume says it all
    double x[kMaxElementNodes][3];
    elementCoordinates(mesh, e, x);
    const double smallest = elementMeasure(mesh.elementType(e), x).smallestScaledJacobian;
    if (smallest <= tiny)
      fail(mesh.elementLabel(e) + " (type " + elementShape(mesh.elementType(e)).exodusName +
           ") is inverted or distorted at a corner: its Jacobian there is " + core::formatNumber(smallest) +
           " of the reference element's (nonpositive; volume " + core::formatNumber(volume) + ")");
  }
}

void requireValidSets(const Mesh& mesh, const Fail& fail) {
  for (const auto& s : mesh.nodeSets) {
    for (LO n : s.nodes)
      if (n < 0 || n >= mesh.numNodes())
        fail("node set \"" + s.name + "\" references node " + std::to_string(n + 1) + " out of range");
    if (!std::is_sorted(s.nodes.begin(), s.nodes.end()) ||
        std::adjacent_find(s.nodes.begin(), s.nodes.end()) != s.nodes.end())
      fail("node set \"" + s.name + "\" is not sorted and unique");
  }
  for (const auto& s : mesh.sideSets) {
    if (s.elements.size() != s.sides.size()) fail("side set \"" + s.name + "\" is malformed");
    for (size_t i = 0; i < s.elements.size(); ++i)
      if (s.elements[i] < 0 || s.elements[i] >= mesh.numElements() || s.sides[i] < 0 ||
          s.sides[i] >= mesh.numSides(s.elements[i]))
        fail("side set \"" + s.name + "\" references element " + std::to_string(s.elements[i] + 1) + " side " +
             std::to_string(s.sides[i] + 1) + " out of range");
  }
}
}  // namespace

void Mesh::validate(const std::string& source) const {
  const Fail fail = [&](const std::string& what) { throw core::InputError(source + ": " + what); };
  // In this order: each check relies on the ones before (ids in range, then volumes, then
  // face normals that point outwards).
  requireContiguousBlocks(*this, fail);
  requireFiniteCoordinates(*this, fail);
  requireValidElements(*this, fail);
  requireValidSets(*this, fail);
  requireSoundTopology(*this, source);
}

}  // namespace tribos::mesh
