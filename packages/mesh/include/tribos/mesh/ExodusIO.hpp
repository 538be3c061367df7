#pragma once
/// \file ExodusIO.hpp
/// Exodus II reading and writing of a Mesh with nodal and element variables over time
/// steps (classic ex_* C API of Debian's exodusii 6.02). Files open in ParaView.
#include <memory>
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

/// One value per time step for the whole model (an Exodus global variable), e.g. an
/// iteration count or a residual.
struct GlobalValue {
  std::string name;
  double value = 0.0;
};

struct TimeStep {
  double time = 0.0;
  std::vector<Field> nodal;
  std::vector<Field> element;
  std::vector<GlobalValue> global;
};

struct ExodusData {
  Mesh mesh;
  std::vector<TimeStep> steps;
  std::vector<std::string> info;  ///< the info records, one line each
};

/// Writes `mesh` (element blocks with the topology name "TETRA", which ParaView, meshio and
/// the Exodus library all read, with their names and ids; node sets, side sets, all named),
/// the time steps (every step must carry the same field and global names) and `info` as
/// info records (lines longer than 80 characters, the format's limit, are wrapped). Throws
/// core::InputError naming `path` when the file cannot be created, and std::invalid_argument
/// when field sizes do not match the mesh.
void writeExodus(const std::string& path, const Mesh& mesh, const std::vector<TimeStep>& steps = {},
                 const std::vector<std::string>& info = {});

/// An Exodus result written one time step at a time (a load history's steps as they
/// converge, so that no step is held in memory after it is written). The file is created at
/// the first step, whose names declare the variables; each step is on disk when append returns
/// (ex_update), so that a copy taken between steps is a complete file. Every step must carry
/// the first step's names. Errors as writeExodus's, at the step that has them.
class ExodusWriter {
 public:
  ExodusWriter(std::string path, const Mesh& mesh, std::vector<std::string> info = {});
  ~ExodusWriter();
  ExodusWriter(const ExodusWriter&) = delete;
  ExodusWriter& operator=(const ExodusWriter&) = delete;
  void append(const TimeStep& step);
  /// Closes the file (a mesh-only file when no step was appended); reports a failed flush.
  void close();
  int steps() const { return steps_; }
  const std::string& path() const { return path_; }

 private:
  struct Open;
  void create(const TimeStep* first);
  std::string path_;
  const Mesh& mesh_;
  std::vector<std::string> info_;
  std::unique_ptr<Open> open_;
  int steps_ = 0;
  bool closed_ = false;
};

/// Reads a 3D tetrahedral Exodus II file (TETRA/TETRA4/TET4 blocks; 32- or 64-bit ids,
/// ids from 0 as meshio writes them) with its node sets, side sets, all nodal / element /
/// global variables and the info records. Unnamed blocks and sets are named
/// "block_<id>", "nodeset_<id>", "sideset_<id>". Errors (missing file, not Exodus, non-tet
/// block, 2D mesh, ids out of range) throw core::InputError naming the file and what is
/// wrong; the result passes Mesh::validate (inverted elements are an error naming the
/// element).
ExodusData readExodus(const std::string& path);

}  // namespace tribos::mesh
