#include "tribos/mesh/Mesh.hpp"

#include <algorithm>
#include <sstream>

#include "tribos/core/Errors.hpp"

namespace tribos::mesh {

namespace {
template <class Set>
const Set& findByName(const std::vector<Set>& sets, const std::string& name, const char* kind) {
  for (const auto& s : sets)
    if (s.name == name) return s;
  std::ostringstream msg;
  msg << "the mesh has no " << kind << " named \"" << name << "\"; it has:";
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
  const auto& block = findByName(blocks, name, "element block");
  return static_cast<int>(&block - blocks.data());
}

const NodeSet& Mesh::nodeSet(const std::string& name) const {
  return findByName(nodeSets, name, "node set");
}

const SideSet& Mesh::sideSet(const std::string& name) const {
  return findByName(sideSets, name, "side set");
}

double Mesh::elementVolume(LO element) const {
  const auto& t = tets[element];
  const auto& a = coords[t[0]];
  double e[3][3];
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < 3; ++c) e[v][c] = coords[t[v + 1]][c] - a[c];
  const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                     e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                     e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
  return det / 6.0;
}

std::array<double, 3> Mesh::faceNormal(LO element, int side) const {
  const auto& t = tets[element];
  const auto& face = kTetFaceVertices[side];
  const auto &a = coords[t[face[0]]], &b = coords[t[face[1]]], &c = coords[t[face[2]]];
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
}

void Mesh::validate(const std::string& source) const {
  auto fail = [&](const std::string& what) { throw core::InputError(source + ": " + what); };
  LO next = 0;
  for (const auto& b : blocks) {
    if (b.first != next || b.count < 0)
      fail("element block \"" + b.name + "\" is not contiguous with the previous block");
    next += b.count;
  }
  if (next != numElements()) fail("element blocks do not cover all elements");
  for (LO e = 0; e < numElements(); ++e) {
    for (LO n : tets[e])
      if (n < 0 || n >= numNodes())
        fail("element " + std::to_string(e + 1) + " references node " + std::to_string(n + 1) +
             " out of range 1.." + std::to_string(numNodes()));
    if (!(elementVolume(e) > 0.0))
      fail("element " + std::to_string(e + 1) + " of block \"" + blocks[blockOf(e)].name +
           "\" is inverted or degenerate (volume " + std::to_string(elementVolume(e)) + ")");
  }
  for (const auto& s : nodeSets) {
    for (LO n : s.nodes)
      if (n < 0 || n >= numNodes())
        fail("node set \"" + s.name + "\" references node " + std::to_string(n + 1) + " out of range");
    if (!std::is_sorted(s.nodes.begin(), s.nodes.end()) ||
        std::adjacent_find(s.nodes.begin(), s.nodes.end()) != s.nodes.end())
      fail("node set \"" + s.name + "\" is not sorted and unique");
  }
  for (const auto& s : sideSets) {
    if (s.elements.size() != s.sides.size()) fail("side set \"" + s.name + "\" is malformed");
    for (size_t i = 0; i < s.elements.size(); ++i)
      if (s.elements[i] < 0 || s.elements[i] >= numElements() || s.sides[i] < 0 || s.sides[i] > 3)
        fail("side set \"" + s.name + "\" references element " + std::to_string(s.elements[i] + 1) +
             " side " + std::to_string(s.sides[i] + 1) + " out of range");
  }
}

}  // namespace tribos::mesh
