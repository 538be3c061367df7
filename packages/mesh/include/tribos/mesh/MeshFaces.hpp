#pragma once
/// \file MeshFaces.hpp
/// What a solve needs of the mesh topology, found from the faces that elements share:
/// - a face bounds at most two elements, and those lie on opposite sides of it (else one of
///   them is folded over, inverted in place, or the two overlap);
/// - every body (element block) is one piece: its elements connected through shared faces.
///   A body in several pieces has more rigid motions than the 6 that T-FETI gives each
///   subdomain and each body (METIS cannot cut it into contiguous parts; the restraint check
///   would miss a piece that nothing holds). Pieces that touch only at an edge or a node are
///   separate: such a joint is a hinge, not a solid connection.
#include <string>
#include <vector>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

/// The face-connected pieces of one element block.
struct BlockIslands {
  std::vector<LO> island;        ///< island index of each element of the block (block-local order)
  std::vector<LO> sizes;         ///< elements per island
  std::vector<LO> firstElement;  ///< lowest global element id of each island
  int count() const { return static_cast<int>(sizes.size()); }
};

/// Islands of every block, from one sort of all faces. Expects node ids in range.
std::vector<BlockIslands> blockIslands(const Mesh& mesh);

/// Both checks above, from one sort of the faces. Throws core::InputError naming `source`:
/// the elements and their shared face if a face bounds three or more elements or two
/// elements lie on the same side of it; the face and its element if a quadrilateral face is
/// covered by two triangular faces on its vertices (a non-conforming hexahedron-tetrahedron
/// junction); the block and its number of islands (with their
/// sizes and first elements) if a block is not one piece. Expects node ids in range and
/// positively oriented elements (whose face normals point outwards).
void requireSoundTopology(const Mesh& mesh, const std::string& source);

/// Only the second check: every block one face-connected piece.
void requireConnectedBlocks(const Mesh& mesh, const std::string& source);

}  // namespace tribos::mesh
