#pragma once
/// \file Mesh.hpp
/// The global (user's) mesh: nodes, linear tetrahedra grouped in element blocks (one block
/// = one body), named node sets and side sets. Plain C++ storage, no Trilinos: every layer
/// can include it cheaply.
#include <array>
#include <string>
#include <vector>

#include "tribos/core/Types.hpp"

namespace tribos::mesh {

/// Local vertices of tetrahedron face `side` (0-based; Exodus side = side + 1):
/// 1:(1,2,4) 2:(2,3,4) 3:(1,4,3) 4:(1,3,2). For a positively oriented tet (det > 0) each
/// face ordered this way has its right-hand normal pointing out of the element.
inline constexpr int kTetFaceVertices[4][3] = {{0, 1, 3}, {1, 2, 3}, {0, 3, 2}, {0, 2, 1}};

/// A tetrahedron whose volume is at most this fraction of the cube of its longest edge is
/// degenerate (flat: its nodes are coplanar up to round-off, which is about 1e-16 of that
/// cube): its stiffness would be singular. Slivers of real meshes stay above 1e-6.
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

/// Faces given as (element, side) pairs, side 0..3 as in kTetFaceVertices.
struct SideSet {
  std::string name;
  int id = 0;
  std::vector<LO> elements;
  std::vector<int> sides;
};

struct Mesh {
  std::vector<std::array<double, 3>> coords;  ///< node coordinates
  std::vector<std::array<LO, 4>> tets;        ///< 0-based node ids, positively oriented
  std::vector<ElementBlock> blocks;           ///< cover [0, tets.size()) in order
  std::vector<NodeSet> nodeSets;
  std::vector<SideSet> sideSets;
  std::string file;  ///< the file it was read from, named in messages; empty when generated
  /// The file's own number of each element (gmsh's element tags), named in messages; empty:
  /// elements are numbered by position from 1 (the Exodus numbering).
  std::vector<long long> elementNumbers;

  LO numNodes() const { return static_cast<LO>(coords.size()); }
  LO numElements() const { return static_cast<LO>(tets.size()); }
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
  /// Length of the longest edge of an element.
  double longestEdge(LO element) const;
  /// Outward normal of face `side` of `element`, of length twice the face's area (the cross
  /// product of its edges in kTetFaceVertices order).
  std::array<double, 3> faceNormal(LO element, int side) const;
  /// Checks the invariants above (ids in range, finite coordinates, blocks contiguous and
  /// not empty, sets sorted, positive and not degenerate volumes) and what a solve needs of
  /// the topology (MeshFaces.hpp: no face shared by three elements, no two elements on the
  /// same side of their common face, every body one face-connected piece); throws
  /// core::InputError naming `source` and the bad entity (element and node numbers 1-based).
  void validate(const std::string& source) const;
};

}  // namespace tribos::mesh
