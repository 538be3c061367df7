#pragma once
// Structured box meshes for tests: a grid of nx x ny x nz cells, each cut into the 6 Kuhn
// tetrahedra around its main diagonal (the same split in every cell, so neighbouring cells
// share their face diagonals and the mesh is conforming), one element block, and for each
// of the six faces a node set and a side set "<block>_x0", "<block>_x1", "<block>_y0", ...
// (x0 = the face at the lowest x). Two boxes with their own nodes (e.g. two bodies in
// contact) are joined by mergeMeshes.
#include <array>
#include <string>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::test {

/// What fills each cell: the 6 Kuhn tetrahedra (linear, or 10-node with straight mid-edge
/// nodes, numbered after the grid's), one 8-node hexahedron, or two 6-node prisms (the cell
/// cut along the diagonal of its xy face: their triangles lie on the z faces).
enum class CellElements { KuhnTetrahedra, QuadraticKuhnTetrahedra, Hexahedron, TwoPrisms };

/// Node (i, j, k) of the grid is node i + (nx+1) (j + (ny+1) k), at origin + size * (i/nx,
/// j/ny, k/nz) (computed as size * i / n, so binary fractions are exact). Every element is
/// positively oriented. Block id 1, set ids 1..6 in the order x0, x1, y0, y1, z0, z1.
mesh::Mesh boxMesh(std::array<double, 3> origin, std::array<double, 3> size, std::array<int, 3> cells,
                   const std::string& blockName, CellElements fill = CellElements::KuhnTetrahedra);

/// a followed by b: b's nodes renumbered after a's, b's elements after a's; blocks, node
/// sets and side sets concatenated, b's ids shifted past a's so that all ids stay distinct.
/// The bodies share no node (contact surfaces need their own nodes on each side).
mesh::Mesh mergeMeshes(const mesh::Mesh& a, const mesh::Mesh& b);

}  // namespace tribos::test
