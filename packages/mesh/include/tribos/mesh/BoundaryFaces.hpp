#pragma once
/// \file BoundaryFaces.hpp
/// Boundary faces of a mesh and side sets made from node sets. Tools such as meshio write
/// node sets only, while tractions and contact surfaces need faces: the faces on the
/// boundary (faces of exactly one tetrahedron) whose three nodes all lie in a node set
/// stand for that set's surface.
#include <string>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

/// Every boundary face of `mesh` (a face that belongs to exactly one tetrahedron), as
/// (element, side) pairs in ascending element, then side order. The name is empty, id 0.
SideSet boundaryFaces(const Mesh& mesh);

/// The boundary faces whose three nodes all lie in `nodes`, named `name` with id `id`.
/// A face on a body interface whose bodies share nodes is not a boundary face; bodies with
/// their own nodes on an interface (tribos-msh2exo --split-bodies) keep a face on each side.
SideSet sideSetFromNodeSet(const Mesh& mesh, const NodeSet& nodes, const std::string& name, int id);

/// Adds the side set of node set `nodeSet`'s boundary faces to the mesh (next free id) and
/// returns its index. It is named after the node set; when a different side set already has
/// that name, "<name>_faces". An identical side set of that name is reused (two loads on
/// one node set). Throws core::InputError naming the set when there is no such node set or
/// it covers no boundary face.
int addSideSetFromNodeSet(Mesh& mesh, const std::string& nodeSet);

/// The index of the side set named `name`; when the mesh has none but has a node set of that
/// name, the side set made from it (addSideSetFromNodeSet). Throws core::InputError naming
/// `name` and listing the side sets when neither exists.
int requireSideSet(Mesh& mesh, const std::string& name);

}  // namespace tribos::mesh
