#pragma once
/// \file SurfaceNormals.hpp
/// The nodes and nodal normals of a surface given as a side set: what the contact search,
/// the mortar integration and the constraint checks ask of a contact surface.
#include <array>
#include <vector>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::geometry {

/// Vertices of the faces of a side set (mid-edge nodes included), ascending, unique.
std::vector<LO> sideSetNodes(const mesh::Mesh& mesh, const mesh::SideSet& set);

/// Per node: the sum over the faces of `set` that contain it (mid-edge nodes included) of
/// their outward normals (length twice the face area, so the sum is area-weighted); zero off
/// the set.
std::vector<std::array<double, 3>> summedFaceNormals(const mesh::Mesh& mesh, const mesh::SideSet& set);

/// The unit vectors of summedFaceNormals; zero where the sum is zero (off the set, or a
/// folded surface).
std::vector<std::array<double, 3>> unitNodalNormals(const mesh::Mesh& mesh, const mesh::SideSet& set);

/// The largest absolute coordinate (at least 1): the scale of round-off in distances.
double coordinateScale(const mesh::Mesh& mesh);

}  // namespace tribos::geometry
