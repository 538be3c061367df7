#pragma once
/// \file SurfaceNormals.hpp
/// The nodes and nodal normals of a surface given as a side set: what the contact search,
/// the mortar integration and the constraint checks ask of a contact surface.
#include <array>
#include <cstdint>
#include <vector>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::geometry {

/// Vertices of the faces of a side set (mid-edge nodes included), ascending, unique.
std::vector<LO> sideSetNodes(const mesh::Mesh& mesh, const mesh::SideSet& set);

/// Per node: the sum over the faces of `set` that contain it (mid-edge nodes included) of
/// their outward unit normals, each weighted by the face's interior angle at the node (pi at a
/// mid-edge node); zero off the set. A 6-node triangle gives the normal and the corner angles of
/// its own quadratic geometry at each node, not its chord triangle's (a face following a sphere:
/// 6.3e-3 rad from the sphere's normal against 0.126, test quadraticFacesGiveTheirOwnNormals).
/// Why angles, not areas: the angle-weighted normal does not depend on how a flat region is
/// cut into faces (a quadrilateral's corner angle is the sum of its triangles' angles there).
/// Area-weighted, a node where a cylinder's flat facets meet leans towards the facet cut into
/// more triangles at it (a 4-node tetrahedral mesh's bore: by up to a sixth of the angle
/// between the facets), and the closing of an interference along the true normal was then
/// measured as a tangential slip of the interference times that lean (1e-4 mm on the
/// shrink fit of test/integration/shrink_fit.xml, where the solution slips nowhere).
std::vector<std::array<double, 3>> summedFaceNormals(const mesh::Mesh& mesh, const mesh::SideSet& set);

/// Per mesh node, the axes along which a displacement condition holds it while it stays free
/// along another (bit c: axis c), as on a symmetry plane; empty: no node is held so.
using HeldAxes = std::vector<std::uint8_t>;

/// The normal of a surface node on symmetry planes: for each axis e_c the node is held along
/// (`heldAxes`, bit c) where the normal is within ~11 degrees of the plane x_c = const, the
/// normal's e_c part is removed. Any condition that holds some components of a node but not
/// all counts (a symmetry plane, a roller, a prescribed axial push): a contact normal within
/// 11 degrees of such a plane is taken to lie in it. The nodal normal there averages the faces on one side of the
/// plane only, so it leans out of the plane; the whole (mirrored) body's normal lies in it.
/// On a faceted cylinder's quarter model (test/integration/shrink_fit.xml) the lean of the bore's
/// node on the plane turned the normal interpolated over the first facet by half a facet
/// angle, and the closing of the interference read as a tangential slip of 1.6e-4 mm there.
std::array<double, 3> inSymmetryPlanes(std::array<double, 3> normal, std::uint8_t heldAxes);

/// The unit vectors of summedFaceNormals; zero where the sum is zero (off the set, or a
/// folded surface).
/// `held` (HeldAxes, optional) turns the normals of nodes on symmetry planes into them
/// (inSymmetryPlanes).
std::vector<std::array<double, 3>> unitNodalNormals(const mesh::Mesh& mesh, const mesh::SideSet& set,
                                                    const HeldAxes& held = {});

/// The largest absolute coordinate (at least 1): the scale of round-off in distances.
double coordinateScale(const mesh::Mesh& mesh);

}  // namespace tribos::geometry
