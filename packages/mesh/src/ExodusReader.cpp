// Reading Exodus II meshes and results (the classic ex_* C API, Debian's exodusii 6.02):
// checks first (a regular file, a header whose counts the file can hold), then coordinates,
// element blocks (4- and 10-node tetrahedra, 8-node hexahedra, 6-node prisms), node and side
// sets, and the variables of every time step. Exodus ids are 1-based; Mesh uses 0-based
// nodes, elements and sides.
#include <exodusII.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <filesystem>
#include <fstream>

#include "ExodusFile.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/InputFiles.hpp"
#include "tribos/mesh/ExodusIO.hpp"

namespace tribos::mesh {

namespace {
using namespace exodus;

/// A 0-based id from the file as LO. Out-of-range ids stay out of range (clamped to
/// [-1, INT_MAX]) so that Mesh::validate reports them; numNodes/numElements <= INT_MAX.
LO toLO(int64_t zeroBased) { return static_cast<LO>(std::clamp<int64_t>(zeroBased, -1, INT_MAX)); }

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

std::vector<std::string> readInfo(int id, const std::string& path) {
  const int64_t count = ex_inquire_int(id, EX_INQ_INFO);
  if (count <= 0) return {};
  requireCount(count, kMaxEntities, path, "info records", "Tribos reads");
  NameArray records(static_cast<size_t>(count), MAX_LINE_LENGTH);
  check(ex_get_info(id, records.data()), path, "reading the info records");
  std::vector<std::string> lines;
  for (int64_t i = 0; i < count; ++i) lines.push_back(records[static_cast<size_t>(i)]);
  return lines;
}

/// Names of the global variables and their values at every step (steps x names).
void readGlobals(int id, const std::string& path, int nameLength, std::vector<TimeStep>& steps) {
  int count = 0;
  check(ex_get_variable_param(id, EX_GLOBAL, &count), path, "counting global variables");
  if (count <= 0) return;
  requireCount(count, kMaxEntities, path, "global variables", "Tribos reads");
  NameArray names(static_cast<size_t>(count), nameLength);
  check(ex_get_variable_names(id, EX_GLOBAL, count, names.data()), path, "reading global variable names");
  std::vector<double> values(static_cast<size_t>(count));
  for (size_t s = 0; s < steps.size(); ++s) {
    check(ex_get_var(id, static_cast<int>(s) + 1, EX_GLOBAL, 1, 0, count, values.data()), path,
          "reading the global variables of time step " + std::to_string(s + 1));
    for (int v = 0; v < count; ++v) steps[s].global.push_back({names[static_cast<size_t>(v)], values[v]});
  }
}

/// The counts of an Exodus header, checked against what the file can hold.
struct Header {
  int64_t numNodes = 0, numElements = 0, numBlocks = 0, numNodeSets = 0, numSideSets = 0;
};

/// Opens `path` for reading: a missing file, a FIFO or device, an unreadable file and a file
/// netCDF cannot open are input errors, each said as such.
int openForReading(const std::string& path) {
  // Checked first because ex_open's answer for a missing file is the same as for a file
  // that is not Exodus.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw core::InputError(path + ": the mesh file does not exist");
  core::requireRegularInputFile(path, "the mesh file");  // a FIFO or a device: never opened
  if (!std::ifstream(path)) throw core::InputError(path + ": cannot open the mesh file (unreadable)");
  ex_opts(0);  // quiet, no abort: errors come back as negative statuses and become InputErrors
  int cpuWordSize = 8, ioWordSize = 0;
  float version = 0.0f;
  const int id = ex_open(path.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version);
  if (id < 0) throw core::InputError(path + ": not an Exodus II file, or a corrupt one (netCDF could not open it)");
  return id;
}

/// One Exodus file being read: its handle, the name length and the header's counts.
class ExodusReader {
 public:
  explicit ExodusReader(const std::string& path) : path_(path), file_(openForReading(path)), id_(file_.id()) {}
  /// The 64-bit API, the name length and the header (3D, counts the file can hold).
  void readHeader();
  void readCoordinates(Mesh& mesh) const;
  /// The element blocks; consecutive blocks of one name join into one body (blockParts).
  void readBlocks(Mesh& mesh);
  void readNodeSets(Mesh& mesh) const;
  void readSideSets(Mesh& mesh) const;
  /// The nodal, element and global variables of every time step, and the info records.
  void readResults(const Mesh& mesh, ExodusData& data) const;

 private:
  std::vector<int64_t> readIds(ex_entity_type type, int64_t count, const char* kind) const;
  std::vector<std::string> readNames(ex_entity_type type, const std::vector<int64_t>& ids, const char* fallback) const;
  void readBlock(int64_t blockId, const std::string& name, Mesh& mesh);
  TimeStep readStep(int stepIndex, double time, const Mesh& mesh, const NameArray& nodalNames, int numNodal,
                    const NameArray& elemNames, int numElemVars, const std::vector<int>& truth) const;

  std::string path_;
  ExodusFile file_;
  int id_;
  int nameLength_ = kNameLength;
  Header h_;
  std::vector<BlockPart> parts_;  ///< the file's element blocks, in file order
};

/// The element type of an Exodus topology name with `nodes` nodes per element; throws
/// naming the block, with what to convert to where Tribos has no such element.
ElementType elementTypeOf(const std::string& topology, int64_t nodes, const std::string& path,
                          const std::string& blockText) {
  const std::string name = upper(topology);
  ElementType type;
  if (elementTypeOfExodus(name, nodes, type)) return type;
  const auto is = [&](std::initializer_list<const char*> names) {
    return std::any_of(names.begin(), names.end(), [&](const char* n) { return name == n; });
  };
  std::string advice;
  if (is({"HEX", "HEX20", "HEX27", "HEXAHEDRON"}))
    advice = " (for 20- or 27-node hexahedra, convert to 8-node ones, e.g. in gmsh with Mesh.ElementOrder = 1, or "
             "mesh with 10-node tetrahedra)";
  throw core::InputError(path + ": " + blockText + " has topology " + topology + " with " + std::to_string(nodes) +
                         " nodes per element" + advice +
                         "; Tribos takes TETRA (4 nodes), TETRA10, HEX8 and WEDGE6 element blocks");
}

void ExodusReader::readHeader() {
  // With the 64-bit API, one code path reads files written with 32- or 64-bit ids.
  check(ex_set_int64_status(id_, EX_ALL_INT64_API) < 0 ? -1 : 0, path_, "selecting the 64-bit API");
  const int64_t usedNameLength = ex_inquire_int(id_, EX_INQ_DB_MAX_USED_NAME_LENGTH);
  nameLength_ = static_cast<int>(std::clamp<int64_t>(usedNameLength, kNameLength, kMaxNameLength));
  check(ex_set_max_name_length(id_, nameLength_), path_, "setting the name length");
  char title[MAX_LINE_LENGTH + 1] = {0};
  int64_t dim = 0;
  check(ex_get_init(id_, title, &dim, &h_.numNodes, &h_.numElements, &h_.numBlocks, &h_.numNodeSets, &h_.numSideSets),
        path_, "reading the header");
  if (dim != 3) throw core::InputError(path_ + ": the mesh is " + std::to_string(dim) + "D; Tribos needs a 3D mesh");
  if (h_.numElements <= 0 || h_.numBlocks <= 0) throw core::InputError(path_ + ": the mesh has no elements");
  if (h_.numNodes < 4) throw core::InputError(path_ + ": the mesh has " + std::to_string(h_.numNodes) + " nodes");
  if (h_.numNodes > INT_MAX || h_.numElements > INT_MAX)
    throw core::InputError(path_ + ": the mesh has more nodes or elements than Tribos can index");
  // A file stores its coordinates and connectivity; compressed (netCDF-4) it may hold more
  // values than bytes, but not a thousand times more: a bound for corrupt headers.
  std::error_code ec;
  const auto fileBytes = std::filesystem::file_size(path_, ec);
  const int64_t fileValues = ec ? INT64_MAX : 1000 * static_cast<int64_t>(fileBytes);
  requireCount(h_.numNodes, fileValues, path_, "nodes", "more than a file of this size can hold");
  requireCount(h_.numElements, fileValues, path_, "elements", "more than a file of this size can hold");
  // Every other count is checked against these before it sizes an allocation.
  requireCount(h_.numBlocks, h_.numElements, path_, "element blocks", "elements");
  requireCount(h_.numNodeSets, kMaxEntities, path_, "node sets", "Tribos reads");
  requireCount(h_.numSideSets, kMaxEntities, path_, "side sets", "Tribos reads");
}

void ExodusReader::readCoordinates(Mesh& mesh) const {
  const int64_t numNodes = h_.numNodes;
  std::vector<double> x(numNodes), y(numNodes), z(numNodes);
  if (numNodes > 0) check(ex_get_coord(id_, x.data(), y.data(), z.data()), path_, "reading coordinates");
  mesh.coords.resize(numNodes);
  for (int64_t n = 0; n < numNodes; ++n) mesh.coords[n] = {x[n], y[n], z[n]};
}

std::vector<int64_t> ExodusReader::readIds(ex_entity_type type, int64_t count, const char* kind) const {
  std::vector<int64_t> ids(count);
  if (count > 0) check(ex_get_ids(id_, type, ids.data()), path_, std::string("reading ") + kind + " ids");
  // meshio numbers blocks and sets from 0; Exodus itself only asks for distinct ids.
  for (int64_t i : ids)
    if (i < 0 || i > INT_MAX)
      throw core::InputError(path_ + ": " + kind + " id " + std::to_string(i) + " is not in 0.." + std::to_string(INT_MAX));
  return ids;
}

// Files from other tools often carry no names; fall back to "<kind>_<id>" so that every
// entity can still be referred to by name in a scene file.
std::vector<std::string> ExodusReader::readNames(ex_entity_type type, const std::vector<int64_t>& ids,
                                                 const char* fallback) const {
  NameArray names(ids.size(), nameLength_);
  if (!ids.empty()) check(ex_get_names(id_, type, names.data()), path_, std::string("reading ") + fallback + " names");
  std::vector<std::string> out(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) {
    out[i] = names[i];
    if (out[i].empty()) out[i] = std::string(fallback) + "_" + std::to_string(ids[i]);
  }
  return out;
}

void ExodusReader::readBlocks(Mesh& mesh) {
  const auto blockIds = readIds(EX_ELEM_BLOCK, h_.numBlocks, "element block");
  const auto blockNames = readNames(EX_ELEM_BLOCK, blockIds, "block");
  for (int64_t b = 0; b < h_.numBlocks; ++b) {
    const bool continuesBody = b > 0 && blockNames[b] == blockNames[b - 1];
    if (!continuesBody) mesh.blocks.push_back({blockNames[b], static_cast<int>(blockIds[b]), mesh.numElements(), 0});
    readBlock(blockIds[b], blockNames[b], mesh);
    parts_.back().body = mesh.numBlocks() - 1;
    mesh.blocks.back().count += parts_.back().count;
  }
  if (static_cast<int64_t>(mesh.numElements()) != h_.numElements)
    throw core::InputError(path_ + ": the element blocks hold " + std::to_string(mesh.numElements()) +
                           " elements but the header says " + std::to_string(h_.numElements));
}

void ExodusReader::readBlock(int64_t blockId, const std::string& name, Mesh& mesh) {
  ex_block block{};
  block.id = blockId;
  block.type = EX_ELEM_BLOCK;
  check(ex_get_block_param(id_, &block), path_, "reading element block " + name);
  const std::string blockText = "element block \"" + name + "\" (id " + std::to_string(blockId) + ")";
  if (block.num_entry == 0) throw core::InputError(path_ + ": " + blockText + " has no elements");
  const ElementType type = elementTypeOf(block.topology, block.num_nodes_per_entry, path_, blockText);
  const int perElement = elementShape(type).numNodes;
  requireCount(block.num_entry, h_.numElements - static_cast<int64_t>(mesh.numElements()), path_,
               "elements in " + blockText, "elements the header leaves for it");
  std::vector<int64_t> conn(perElement * static_cast<size_t>(block.num_entry));
  if (block.num_entry > 0)
    check(ex_get_conn(id_, EX_ELEM_BLOCK, blockId, conn.data(), nullptr, nullptr), path_, "reading element block " + name);
  const BlockPart part{static_cast<int>(blockId), 0, type, mesh.numElements(), static_cast<LO>(block.num_entry)};
  for (int64_t e = 0; e < block.num_entry; ++e) {
    LO nodes[kMaxElementNodes];
    for (int v = 0; v < perElement; ++v) {
      const int64_t node = conn[perElement * e + v];
      if (node < 1 || node > h_.numNodes)
        throw core::InputError(path_ + ": element " + std::to_string(part.first + e + 1) + " of block \"" + name +
                               "\" references node " + std::to_string(node) + " out of range 1.." +
                               std::to_string(h_.numNodes) +
                               (node == 0 ? " (0 is what netCDF reads where data is missing: a truncated file?)" : ""));
      nodes[v] = static_cast<LO>(node - 1);
    }
    mesh.elements.add(type, nodes);
  }
  parts_.push_back(part);
}

// Ids from the file are range-checked by mesh.validate, which names the bad id.
void ExodusReader::readNodeSets(Mesh& mesh) const {
  const auto ids = readIds(EX_NODE_SET, h_.numNodeSets, "node set");
  const auto names = readNames(EX_NODE_SET, ids, "nodeset");
  for (int64_t s = 0; s < h_.numNodeSets; ++s) {
    int64_t count = 0, factors = 0;
    check(ex_get_set_param(id_, EX_NODE_SET, ids[s], &count, &factors), path_, "reading node set " + names[s]);
    // Other writers repeat nodes (one entry per face corner), so allow each node many times.
    requireCount(count, kMaxNodeRepeats * h_.numNodes, path_, "entries in node set \"" + names[s] + "\"",
                 "the nodes allow");
    std::vector<int64_t> list(count);
    if (count > 0) check(ex_get_set(id_, EX_NODE_SET, ids[s], list.data(), nullptr), path_, "reading node set " + names[s]);
    NodeSet ns{names[s], static_cast<int>(ids[s]), {}};
    for (int64_t n : list) ns.nodes.push_back(toLO(n - 1));
    // Other tools write node sets in face order with repeats; Mesh wants them sorted, unique.
    std::sort(ns.nodes.begin(), ns.nodes.end());
    ns.nodes.erase(std::unique(ns.nodes.begin(), ns.nodes.end()), ns.nodes.end());
    mesh.nodeSets.push_back(std::move(ns));
  }
}

void ExodusReader::readSideSets(Mesh& mesh) const {
  const auto ids = readIds(EX_SIDE_SET, h_.numSideSets, "side set");
  const auto names = readNames(EX_SIDE_SET, ids, "sideset");
  for (int64_t s = 0; s < h_.numSideSets; ++s) {
    int64_t count = 0, factors = 0;
    check(ex_get_set_param(id_, EX_SIDE_SET, ids[s], &count, &factors), path_, "reading side set " + names[s]);
    requireCount(count, 6 * h_.numElements, path_, "faces in side set \"" + names[s] + "\"",
                 "at most 6 per element");
    std::vector<int64_t> elements(count), sides(count);
    if (count > 0)
      check(ex_get_set(id_, EX_SIDE_SET, ids[s], elements.data(), sides.data()), path_, "reading side set " + names[s]);
    SideSet ss{names[s], static_cast<int>(ids[s]), {}, {}};
    for (int64_t i = 0; i < count; ++i) {
      ss.elements.push_back(toLO(elements[i] - 1));
      ss.sides.push_back(toLO(sides[i] - 1));
    }
    mesh.sideSets.push_back(std::move(ss));
  }
}

void ExodusReader::readResults(const Mesh& mesh, ExodusData& data) const {
  const int64_t numSteps = ex_inquire_int(id_, EX_INQ_TIME);
  if (numSteps < 0) check(-1, path_, "counting time steps");
  requireCount(numSteps, kMaxEntities, path_, "time steps", "Tribos reads");
  int numNodal = 0, numElemVars = 0;
  check(ex_get_variable_param(id_, EX_NODAL, &numNodal), path_, "counting nodal variables");
  check(ex_get_variable_param(id_, EX_ELEM_BLOCK, &numElemVars), path_, "counting element variables");
  requireCount(numNodal, kMaxEntities, path_, "nodal variables", "Tribos reads");
  requireCount(numElemVars, kMaxEntities, path_, "element variables", "Tribos reads");
  NameArray nodalNames(numNodal, nameLength_), elemNames(numElemVars, nameLength_);
  if (numNodal > 0)
    check(ex_get_variable_names(id_, EX_NODAL, numNodal, nodalNames.data()), path_, "reading nodal variable names");
  if (numElemVars > 0)
    check(ex_get_variable_names(id_, EX_ELEM_BLOCK, numElemVars, elemNames.data()), path_,
          "reading element variable names");
  // truth[b * numElemVars + v] != 0 when variable v is stored on block b; other writers may
  // leave a variable off some blocks, which then read as zeros.
  std::vector<int> truth(static_cast<size_t>(h_.numBlocks) * numElemVars, 1);
  if (numElemVars > 0)
    check(ex_get_truth_table(id_, EX_ELEM_BLOCK, static_cast<int>(h_.numBlocks), numElemVars, truth.data()), path_,
          "reading the element variable truth table");
  std::vector<double> times(numSteps);
  if (numSteps > 0) check(ex_get_all_times(id_, times.data()), path_, "reading times");
  for (int64_t s = 0; s < numSteps; ++s)
    data.steps.push_back(readStep(static_cast<int>(s + 1), times[s], mesh, nodalNames, numNodal, elemNames,
                                  numElemVars, truth));
  readGlobals(id_, path_, nameLength_, data.steps);
  data.info = readInfo(id_, path_);
}

TimeStep ExodusReader::readStep(int stepIndex, double time, const Mesh& mesh, const NameArray& nodalNames,
                                int numNodal, const NameArray& elemNames, int numElemVars,
                                const std::vector<int>& truth) const {
  TimeStep step;
  step.time = time;
  for (int v = 0; v < numNodal; ++v) {
    Field f{nodalNames[v], std::vector<double>(h_.numNodes)};
    if (h_.numNodes > 0)
      check(ex_get_var(id_, stepIndex, EX_NODAL, v + 1, 1, h_.numNodes, f.values.data()), path_,
            "reading nodal variable " + f.name + " at time step " + std::to_string(stepIndex));
    step.nodal.push_back(std::move(f));
  }
  for (int v = 0; v < numElemVars; ++v) {
    Field f{elemNames[v], std::vector<double>(h_.numElements, 0.0)};
    for (int64_t b = 0; b < h_.numBlocks; ++b) {
      const auto& part = parts_[b];
      if (part.count > 0 && truth[b * numElemVars + v])
        check(ex_get_var(id_, stepIndex, EX_ELEM_BLOCK, v + 1, part.id, part.count, f.values.data() + part.first),
              path_,
              "reading element variable " + f.name + " on block " + mesh.blocks[part.body].name + " at time step " +
                  std::to_string(stepIndex));
    }
    step.element.push_back(std::move(f));
  }
  return step;
}
}  // namespace

namespace {
// Debian's Exodus library (6.02) leaves a coordinate array unread, all zero, when it is the
// file's first netCDF variable (valid netCDF; ncgen and scipy write files so). Every node in one
// plane is no 3D mesh either way: said as what it is, not as a degenerate element (issue 44).
// After the blocks, whose check names a truncated file (also read as zeros) first.
void requireNoZeroCoordinateArray(const Mesh& mesh, const std::string& path) {
  for (int axis = 0; axis < 3; ++axis)
    if (std::all_of(mesh.coords.begin(), mesh.coords.end(), [&](const auto& x) { return x[axis] == 0.0; }))
      throw core::InputError(path + ": every node has " + "xyz"[axis] + " = 0: a flat mesh, or coordinates this " +
                             "Exodus library could not read (it misreads a coordinate array stored as the file's " +
                             "first netCDF variable); rewrite the file with tribos-msh2exo or meshio");
}
}  // namespace

ExodusData readExodus(const std::string& path) {
  ExodusReader reader(path);
  reader.readHeader();
  ExodusData data;
  Mesh& mesh = data.mesh;
  reader.readCoordinates(mesh);
  reader.readBlocks(mesh);
  requireNoZeroCoordinateArray(mesh, path);
  reader.readNodeSets(mesh);
  reader.readSideSets(mesh);
  mesh.file = path;
  mesh.validate(path);
  reader.readResults(mesh, data);
  return data;
}

}  // namespace tribos::mesh
