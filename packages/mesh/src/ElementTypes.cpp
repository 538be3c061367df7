#include "tribos/mesh/ElementTypes.hpp"

#include <algorithm>
#include <stdexcept>

namespace tribos::mesh {

namespace {
// Exodus II side numbering (the Exodus manual's "side set node ordering" tables); the face
// vertices of each are listed so that their right-hand normal points outwards.
// The mirror images: a tetrahedron swaps vertices 2 and 3 (a 10-node one with them the edges
// (1,2) <-> (1,3) and (2,0) <-> (0,3)), a hexahedron and a prism swap their bottom and top.
constexpr ElementShape kShapes[kNumElementTypes] = {
    // "TETRA": meshio 5 maps "TETRA4" to a cell type it does not know (KeyError 'tetra4').
    {"TETRA", "4-node tetrahedron", 4, 4, 4,
     {{3, 3, {0, 1, 3}}, {3, 3, {1, 2, 3}}, {3, 3, {0, 3, 2}}, {3, 3, {0, 2, 1}}},
     {"TETRA", "TETRA4", "TET4", "TET"}, 4, {0, 1, 2, 3}, {0, 1, 3, 2}, true},
    // Mid-edge nodes 4:(0,1) 5:(1,2) 6:(2,0) 7:(0,3) 8:(1,3) 9:(2,3).
    {"TETRA10", "10-node tetrahedron", 10, 4, 4,
     {{3, 6, {0, 1, 3, 4, 8, 7}}, {3, 6, {1, 2, 3, 5, 9, 8}}, {3, 6, {0, 3, 2, 7, 9, 6}}, {3, 6, {0, 2, 1, 6, 5, 4}}},
     {"TETRA", "TETRA10", "TET10"}, 11, {0, 1, 2, 3, 4, 5, 6, 7, 9, 8}, {0, 1, 3, 2, 4, 8, 7, 6, 5, 9}, false},
    {"HEX8", "8-node hexahedron", 8, 8, 6,
     {{4, 4, {0, 1, 5, 4}},
      {4, 4, {1, 2, 6, 5}},
      {4, 4, {2, 3, 7, 6}},
      {4, 4, {0, 4, 7, 3}},
      {4, 4, {0, 3, 2, 1}},
      {4, 4, {4, 5, 6, 7}}},
     {"HEX", "HEX8", "HEXAHEDRON"}, 5, {0, 1, 2, 3, 4, 5, 6, 7}, {4, 5, 6, 7, 0, 1, 2, 3}, false},
    // "WEDGE": meshio 5 does not know "WEDGE6" (KeyError); both are Exodus names of it.
    {"WEDGE", "6-node prism", 6, 6, 5,
     {{4, 4, {0, 1, 4, 3}}, {4, 4, {1, 2, 5, 4}}, {4, 4, {0, 3, 5, 2}}, {3, 3, {0, 2, 1}}, {3, 3, {3, 4, 5}}},
     {"WEDGE", "WEDGE6"}, 6, {0, 1, 2, 3, 4, 5}, {3, 4, 5, 0, 1, 2}, false},
};
}  // namespace

const ElementShape& elementShape(ElementType type) { return kShapes[static_cast<int>(type)]; }

bool elementTypeOfExodus(const std::string& upperCaseTopology, long long nodesPerElement, ElementType& type) {
  for (int t = 0; t < kNumElementTypes; ++t) {
    if (kShapes[t].numNodes != nodesPerElement) continue;
    for (const char* name : kShapes[t].exodusNames)
      if (name != nullptr && upperCaseTopology == name) {
        type = static_cast<ElementType>(t);
        return true;
      }
  }
  return false;
}

bool elementTypeOfGmsh(int gmshType, ElementType& type) {
  for (int t = 0; t < kNumElementTypes; ++t)
    if (kShapes[t].gmshType == gmshType) {
      type = static_cast<ElementType>(t);
      return true;
    }
  return false;
}

void Connectivity::add(ElementType type, const LO* nodes) {
  const int count = elementShape(type).numNodes;
  types_.push_back(type);
  nodes_.insert(nodes_.end(), nodes, nodes + count);
  offsets_.push_back(static_cast<LO>(nodes_.size()));
}

void Connectivity::add(ElementType type, std::initializer_list<LO> nodes) {
  if (static_cast<int>(nodes.size()) != elementShape(type).numNodes)
    throw std::invalid_argument(std::string("tribos::mesh::Connectivity::add: ") + std::to_string(nodes.size()) +
                                " nodes for a " + elementShape(type).description);
  add(type, nodes.begin());
}

void Connectivity::reserve(size_t elements, size_t nodesPerElement) {
  types_.reserve(elements);
  offsets_.reserve(elements + 1);
  nodes_.reserve(elements * nodesPerElement);
}

void Connectivity::release() {
  std::vector<ElementType>().swap(types_);
  std::vector<LO>{0}.swap(offsets_);
  std::vector<LO>().swap(nodes_);
}

bool Connectivity::allLinearTetrahedra() const {
  return std::all_of(types_.begin(), types_.end(), [](ElementType t) { return t == ElementType::Tet4; });
}

FaceNodes faceNodes(const Connectivity& elements, LO e, int side) {
  const FaceShape& face = elementShape(elements.type(e)).faces[side];
  const ElementNodes nodes = elements.nodes(e);
  FaceNodes out{{}, face.numVertices, face.numNodes};
  for (int k = 0; k < face.numNodes; ++k) out.node[k] = nodes[face.nodes[k]];
  return out;
}

}  // namespace tribos::mesh
