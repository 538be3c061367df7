#pragma once
/// \file GmshReader.hpp
/// Reads a gmsh 4.1 ASCII mesh (the external preprocessor path): the volume elements of each
/// Physical Volume (4- and 10-node tetrahedra, 8-node hexahedra, 6-node prisms, mixed) become
/// an element block (a body), the triangles and quadrilaterals of each Physical Surface a
/// side set and a node set. With `splitBodies`, nodes shared by two bodies are duplicated
/// so that each body has its own nodes on their interface (a conforming interface meshed
/// once in gmsh becomes a node-to-node contact pair); a Physical Surface on such an
/// interface yields one side set per body, "<name>_<body>".
///
/// The reader trusts nothing in the file: every count is checked against what the rest of
/// the file can hold before anything is allocated, every number must parse completely,
/// every section must be closed, node tags must exist, coordinates must be finite.
#include <string>
#include <string_view>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

/// Throws core::InputError naming the file, the line and what is wrong (not gmsh 4.1 ASCII,
/// a truncated file or section, a count the file cannot hold, a number that does not parse,
/// an undefined node, a non-finite coordinate, a Physical Volume with elements of another type
/// (20- and 27-node hexahedra, pyramids: the message says how to mesh instead), a degenerate
/// element, a surface element that is no face of a volume element) and, through
/// Mesh::validate, overlapping elements and bodies in several pieces. Elements with negative
/// orientation are reordered (gmsh itself writes positive ones; other writers may use the
/// opposite convention).
Mesh readGmsh(const std::string& path, bool splitBodies);

/// readGmsh on the text of a file; `source` names it in messages (tests and fuzzing).
Mesh parseGmsh(std::string_view text, const std::string& source, bool splitBodies);

}  // namespace tribos::mesh
