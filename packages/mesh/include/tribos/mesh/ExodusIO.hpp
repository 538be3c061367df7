#pragma once
/// \file ExodusIO.hpp
/// Exodus II reading and writing of a Mesh with nodal and element variables over time
/// steps (classic ex_* C API of Debian's exodusii 6.02). Files open in ParaView.
#include <string>
#include <vector>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::mesh {

/// One named field: nodal fields have mesh.numNodes() values, element fields
/// mesh.numElements() values (global element order; split per block on write).
struct Field {
  std::string name;
  std::vector<double> values;
};

struct TimeStep {
  double time = 0.0;
  std::vector<Field> nodal;
  std::vector<Field> element;
};

struct ExodusData {
  Mesh mesh;
  std::vector<TimeStep> steps;
};

/// Writes `mesh` (element blocks as TETRA4 with their names and ids, node sets, side sets,
/// all named) and the time steps (every step must carry the same field names). Throws
/// core::InputError naming `path` when the file cannot be created, and std::invalid_argument
/// when field sizes do not match the mesh.
void writeExodus(const std::string& path, const Mesh& mesh, const std::vector<TimeStep>& steps = {});

/// Reads a 3D tetrahedral Exodus II file (TETRA/TETRA4/TET4 blocks; 32- or 64-bit ids)
/// with its node sets, side sets and all nodal / element variables. Errors (missing file,
/// not Exodus, non-tet block, 2D mesh, ids out of range) throw core::InputError naming the
/// file and what is wrong; the result passes Mesh::validate (inverted elements are an
/// error naming the element).
ExodusData readExodus(const std::string& path);

}  // namespace tribos::mesh
