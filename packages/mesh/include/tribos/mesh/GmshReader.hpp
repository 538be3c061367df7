#pragma once
/// \file GmshReader.hpp
/// Reads a gmsh 4.1 ASCII mesh (the external preprocessor path): linear tetrahedra of each
/// Physical Volume become an element block (a body), triangles of each Physical Surface a
/// side set and a node set. With `splitBodies`, nodes shared by two bodies are duplicated
/// so that each body has its own nodes on their interface (a conforming interface meshed
/// once in gmsh becomes a node-to-node contact pair); a Physical Surface on such an
/// interface yields one side set per body, "<name>_<body>".
#include <string>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

/// Throws core::InputError naming the file and what is wrong (not gmsh 4.1 ASCII, a
/// Physical Volume with elements other than 4-node tetrahedra, a surface triangle that is
/// no face of a tetrahedron). Tetrahedra with negative orientation are reordered.
Mesh readGmsh(const std::string& path, bool splitBodies);

}  // namespace tribos::mesh
