#pragma once
/// \file ElementTypes.hpp
/// The solid elements Tribos takes (linear and quadratic tetrahedra, trilinear hexahedra,
/// linear prisms), their faces in Exodus side order, and the connectivity of a mesh of them.
/// Node numbering within an element follows Exodus II (which is gmsh's too, except that
/// gmsh swaps the last two mid-edge nodes of a 10-node tetrahedron; the gmsh reader maps
/// them). Plain C++, no Trilinos.
#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "tribos/core/Types.hpp"

namespace tribos::mesh {

enum class ElementType : std::uint8_t { Tet4 = 0, Tet10 = 1, Hex8 = 2, Wedge6 = 3 };
inline constexpr int kNumElementTypes = 4;
/// Most nodes of any element and of any face (a 10-node tetrahedron; a 6-node triangle).
inline constexpr int kMaxElementNodes = 10;
inline constexpr int kMaxFaceNodes = 6;

/// One face of an element: local node ids, its vertices first in the order whose right-hand
/// normal points out of a positively oriented element, then its mid-edge nodes (6-node
/// triangles: edge v0-v1, v1-v2, v2-v0).
struct FaceShape {
  int numVertices;  ///< 3 (triangle) or 4 (quadrilateral)
  int numNodes;     ///< 3, 4 or 6
  int nodes[kMaxFaceNodes];
};

/// One entry of the element catalogue: everything the readers, writers, checks and faces ask
/// of a type (its shape functions and rules: ShapeFunctions.hpp, by the same ElementType).
struct ElementShape {
  const char* exodusName;  ///< the topology written to Exodus files
  const char* description;  ///< in messages: "8-node hexahedron"
  int numNodes;
  int numVertices;  ///< corner nodes; the rest are mid-edge nodes
  int numFaces;
  FaceShape faces[6];  ///< Exodus side s + 1 = faces[s]
  /// The Exodus topology names read as this type (with numNodes nodes per element), upper case.
  const char* exodusNames[4];
  int gmshType;  ///< gmsh's element type number
  /// gmsh's node order: Exodus node k is gmsh's node gmshNode[k] (they differ on 10-node
  /// tetrahedra, whose last two mid-edge nodes gmsh swaps).
  int gmshNode[kMaxElementNodes];
  /// The mirror image: node k of the reversed element is node mirrorNode[k] (for writers with
  /// the other orientation convention).
  int mirrorNode[kMaxElementNodes];
  /// The linear tetrahedron: a constant Jacobian (its volume alone says whether it is valid)
  /// and closed-form element kernels (fem::tetStiffness and its kin) instead of quadrature.
  bool linearSimplex;
};

/// The shape of every type, indexed by ElementType.
const ElementShape& elementShape(ElementType type);

/// The type whose exodusNames holds `upperCaseTopology` with `nodesPerElement` nodes; false if
/// none does.
bool elementTypeOfExodus(const std::string& upperCaseTopology, long long nodesPerElement, ElementType& type);
/// The type of gmsh element type number `gmshType`; false for other numbers.
bool elementTypeOfGmsh(int gmshType, ElementType& type);

/// The nodes of one element: a view into a Connectivity, valid while that is unchanged.
struct ElementNodes {
  const LO* first;
  int count;
  const LO* begin() const { return first; }
  const LO* end() const { return first + count; }
  LO operator[](int k) const { return first[k]; }
  int size() const { return count; }
};

/// Elements of mixed types in one flat array: element e has the nodes
/// nodes_[offsets_[e] .. offsets_[e + 1]).
class Connectivity {
 public:
  LO size() const { return static_cast<LO>(types_.size()); }
  bool empty() const { return types_.empty(); }
  ElementType type(LO e) const { return types_[e]; }
  ElementNodes nodes(LO e) const { return {nodes_.data() + offsets_[e], offsets_[e + 1] - offsets_[e]}; }
  /// The nodes of element e, to renumber or reorient them in place.
  LO* mutableNodes(LO e) { return nodes_.data() + offsets_[e]; }
  /// Appends an element; `nodes` holds elementShape(type).numNodes ids.
  void add(ElementType type, const LO* nodes);
  void add(ElementType type, std::initializer_list<LO> nodes);
  void reserve(size_t elements, size_t nodesPerElement);
  /// Frees the storage (ranks that no longer need the elements).
  void release();
  /// All node ids, element after element, and where each element starts (size() + 1).
  const std::vector<LO>& flatNodes() const { return nodes_; }
  const std::vector<LO>& offsets() const { return offsets_; }
  const std::vector<ElementType>& types() const { return types_; }
  /// Whether every element is a linear tetrahedron.
  bool allLinearTetrahedra() const;
  bool operator==(const Connectivity& other) const {
    return types_ == other.types_ && offsets_ == other.offsets_ && nodes_ == other.nodes_;
  }

 private:
  std::vector<ElementType> types_;
  std::vector<LO> offsets_{0};
  std::vector<LO> nodes_;
};

/// The nodes of one face of an element: global (or subdomain-local) ids.
struct FaceNodes {
  LO node[kMaxFaceNodes];
  int numVertices;
  int numNodes;
  const LO* begin() const { return node; }
  const LO* end() const { return node + numNodes; }
  /// The corner nodes only: a view into this object, so not of a temporary (that would
  /// dangle in a range-for: name the FaceNodes first).
  ElementNodes vertices() const& { return {node, numVertices}; }
  ElementNodes vertices() const&& = delete;
};

/// Face `side` (0-based; Exodus side - 1) of element e of `elements`.
FaceNodes faceNodes(const Connectivity& elements, LO e, int side);

}  // namespace tribos::mesh
