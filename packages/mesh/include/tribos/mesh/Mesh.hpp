#pragma once
/// \file Mesh.hpp
/// The global (user's) mesh: nodes, elements (ElementTypes.hpp: tetrahedra, hexahedra,
/// prisms) grouped in element blocks (one block = one body), named node sets and side sets. Plain C++ storage, no Trilinos: every layer
/// can include it cheaply.
#include <array>
#include <string>
#include <vector>

#include "tribos/core/Types.hpp"
#include "tribos/mesh/ElementTypes.hpp"

namespace tribos::mesh {

/// An element whose volume (or whose Jacobian at a corner or quadrature point, scaled to
/// the reference element's volume) is at most this fraction of the cube of its longest edge
/// is degenerate (flat: its nodes are coplanar up to round-off, which is about 1e-16 of
/// that cube): its stiffness would be singular. Slivers of real meshes stay above 1e-6.
inline constexpr double kDegenerateVolumeRatio = 1e-12;

/// Element block = body. Elements of a block are contiguous: [first, first + count).
struct ElementBlock {
  std::string name;
  int id = 0;       ///< Exodus block id (>= 0; meshio numbers blocks from 0)
  LO first = 0;     ///< first element of the block
  LO count = 0;     ///< number of elements
};

struct NodeSet {
  std::string name;
  int id = 0;                ///< Exodus set id (>= 0)
  std::vector<LO> nodes;     ///< 0-based global node ids, ascending, unique
};

/// Faces given as (element, side) pairs, side 0-based as in ElementShape::faces.
struct SideSet {
  std::string name;
  int id = 0;
  std::vector<LO> elements;
  std::vector<int> sides;
};

struct Mesh {
  std::vector<std::array<double, 3>> coords;  ///< node coordinates
  Connectivity elements;                      ///< 0-based node ids, positively oriented
  std::vector<ElementBlock> blocks;           ///< cover [0, numElements()) in order
  std::vector<NodeSet> nodeSets;
  std::vector<SideSet> sideSets;
  std::string file;  ///< the file it was read from, named in messages; empty when generated
  /// The file's own number of each element (gmsh's element tags), named in messages; empty:
  /// elements are numbered by position from 1 (the Exodus numbering).
  std::vector<long long> elementNumbers;

  LO numNodes() const { return static_cast<LO>(coords.size()); }
  LO numElements() const { return elements.size(); }
  ElementType elementType(LO element) const { return elements.type(element); }
  ElementNodes elementNodes(LO element) const { return elements.nodes(element); }
  /// Face `side` of `element` (ElementShape::faces order).
  FaceNodes faceNodes(LO element, int side) const { return mesh::faceNodes(elements, element, side); }
  int numSides(LO element) const { return elementShape(elements.type(element)).numFaces; }
  int numBlocks() const { return static_cast<int>(blocks.size()); }
  /// Index into `blocks` of the block that holds `element`.
  int blockOf(LO element) const;
  /// Index of the block named `name`; throws core::InputError listing the block names.
  int blockIndex(const std::string& name) const;
  /// The set named `name`; throws core::InputError naming it (and the mesh file) and listing
  /// the sets there are, or saying that it is empty: a set that is used must hold something.
  const NodeSet& nodeSet(const std::string& name) const;
  const SideSet& sideSet(const std::string& name) const;
  /// "element 12 of block \"steel\"" (with the file's element number, see elementNumbers).
  std::string elementLabel(LO element) const;
  /// Signed volume of an element (positive for a valid element).
  double elementVolume(LO element) const;
  /// Length of the longest edge of an element (between any two of its vertices).
  double longestEdge(LO element) const;
  /// Outward normal of face `side` of `element`, of length twice the face's area: the cross
  /// product of a triangle's edges from its first vertex, of a quadrilateral's diagonals (its
  /// mean normal; twice its area when flat). Mid-edge nodes are not used.
  std::array<double, 3> faceNormal(LO element, int side) const;
  /// Checks the invariants above (ids in range, finite coordinates, blocks contiguous and
  /// not empty, sets sorted, positive and not degenerate volumes) and what a solve needs of
  /// the topology (MeshFaces.hpp: no face shared by three elements, no two elements on the
  /// same side of their common face, every body one face-connected piece); throws
  /// core::InputError naming `source` and the bad entity (element and node numbers 1-based).
  void validate(const std::string& source) const;
};

}  // namespace tribos::mesh
