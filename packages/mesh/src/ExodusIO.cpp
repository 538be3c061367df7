// Exodus II I/O with the classic ex_* C API (Debian's exodusii 6.02). Exodus ids are
// 1-based; Mesh uses 0-based nodes/elements and sides 0..3 (Exodus side = side + 1).
#include "tribos/mesh/ExodusIO.hpp"

#include <exodusII.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "tribos/core/Errors.hpp"
#include "tribos/core/InputFiles.hpp"

namespace tribos::mesh {

namespace {
/// Names of at least this length survive a round trip; the library's default (32) would cut
/// descriptive set names such as "contact_upper_brick_bottom_face".
constexpr int kNameLength = 64;
/// netCDF stores names in a dimension of NC_MAX_NAME (256) characters including the NUL.
constexpr int kMaxNameLength = 255;

/// Closes the file on every path out of a reader/writer. The writer closes explicitly via
/// close() so that a failed final flush is reported instead of lost in a destructor.
class ExodusFile {
 public:
  explicit ExodusFile(int id) : id_(id) {}
  ExodusFile(const ExodusFile&) = delete;
  ExodusFile& operator=(const ExodusFile&) = delete;
  ~ExodusFile() {
    if (id_ >= 0) ex_close(id_);
  }
  int id() const { return id_; }
  int close() {
    const int status = ex_close(id_);
    id_ = -1;
    return status;
  }

 private:
  int id_;
};

/// Owns a char*[] for the name APIs (which take non-const char**), each entry `length` + 1
/// characters, zero-filled so unset names read back as empty strings.
class NameArray {
 public:
  NameArray(size_t count, int length)
      : storage_(count, std::string(static_cast<size_t>(length) + 1, '\0')), pointers_(count), length_(length) {
    for (size_t i = 0; i < count; ++i) pointers_[i] = storage_[i].data();
  }
  NameArray(const std::vector<std::string>& names, int length) : NameArray(names.size(), length) {
    for (size_t i = 0; i < names.size(); ++i)
      names[i].copy(pointers_[i], std::min<size_t>(names[i].size(), static_cast<size_t>(length_)));
  }
  char** data() { return pointers_.data(); }
  std::string operator[](size_t i) const { return std::string(pointers_[i]); }

 private:
  std::vector<std::string> storage_;
  std::vector<char*> pointers_;
  int length_;
};

/// Counts from the file size allocations: each is checked first against what the rest of
/// the file allows, so that a corrupt header is an input error and not std::bad_alloc.
/// Blocks, sets, variables, steps and info lines beyond this many are not a mesh Tribos reads.
constexpr int64_t kMaxEntities = 1'000'000;
/// A node set may list a node once per face corner it belongs to (other writers do).
constexpr int64_t kMaxNodeRepeats = 64;

void requireCount(int64_t count, int64_t limit, const std::string& path, const std::string& what,
                  const std::string& limitText) {
  if (count < 0 || count > limit)
    throw core::InputError(path + ": the file claims " + std::to_string(count) + " " + what + ", outside 0.." +
                           std::to_string(limit) + " (" + limitText + "): a corrupt file?");
}

void check(int status, const std::string& path, const std::string& what) {
  if (status < 0) throw core::InputError(path + ": Exodus error while " + what + " (status " + std::to_string(status) + ")");
}

std::vector<std::string> fieldNames(const std::vector<Field>& fields) {
  std::vector<std::string> names;
  for (const auto& f : fields) names.push_back(f.name);
  return names;
}

/// Every step must carry the same fields in the same order, because Exodus declares the
/// variable names once for the whole file. Names the first field that differs.
void checkSameFields(const std::vector<Field>& first, const std::vector<Field>& other, size_t step, const char* kind) {
  const size_t common = std::min(first.size(), other.size());
  for (size_t v = 0; v < common; ++v)
    if (first[v].name != other[v].name)
      throw std::invalid_argument("tribos::mesh::writeExodus: time step " + std::to_string(step + 1) + " has " + kind +
                                  " field \"" + other[v].name + "\" where time step 1 has \"" + first[v].name +
                                  "\" (every step must carry the same fields)");
  if (other.size() > common)
    throw std::invalid_argument("tribos::mesh::writeExodus: time step " + std::to_string(step + 1) + " has " + kind +
                                " field \"" + other[common].name + "\" that time step 1 lacks");
  if (first.size() > common)
    throw std::invalid_argument("tribos::mesh::writeExodus: time step " + std::to_string(step + 1) + " lacks " + kind +
                                " field \"" + first[common].name + "\" of time step 1");
}

void checkFieldSizes(const std::vector<Field>& fields, LO expected, const char* kind, const char* entity) {
  for (size_t v = 0; v < fields.size(); ++v) {
    const auto& f = fields[v];
    if (static_cast<LO>(f.values.size()) != expected)
      throw std::invalid_argument("tribos::mesh::writeExodus: " + std::string(kind) + " field \"" + f.name + "\" has " +
                                  std::to_string(f.values.size()) + " values for " + std::to_string(expected) + " " +
                                  entity);
    // Exodus finds variables by name (ParaView shows one of two equal names), so duplicates
    // would silently hide data.
    for (size_t w = 0; w < v; ++w)
      if (fields[w].name == f.name)
        throw std::invalid_argument("tribos::mesh::writeExodus: " + std::string(kind) + " field \"" + f.name +
                                    "\" appears twice");
  }
}

/// The writer reads mesh.tets[b.first .. b.first + b.count) per block and parallel side-set
/// arrays; check those ranges first so a malformed Mesh is an error, not a wild read.
void checkWritableMesh(const Mesh& mesh) {
  LO next = 0;
  for (const auto& b : mesh.blocks) {
    if (b.first != next || b.count < 0 || b.count > mesh.numElements() - b.first)
      throw std::invalid_argument("tribos::mesh::writeExodus: element block \"" + b.name +
                                  "\" does not continue the previous block within the elements");
    next += b.count;
  }
  if (next != mesh.numElements())
    throw std::invalid_argument("tribos::mesh::writeExodus: the element blocks do not cover all elements");
  for (const auto& s : mesh.sideSets)
    if (s.elements.size() != s.sides.size())
      throw std::invalid_argument("tribos::mesh::writeExodus: side set \"" + s.name +
                                  "\" has different numbers of elements and sides");
}

int longestName(const Mesh& mesh, const std::vector<TimeStep>& steps) {
  size_t longest = 0;
  for (const auto& b : mesh.blocks) longest = std::max(longest, b.name.size());
  for (const auto& s : mesh.nodeSets) longest = std::max(longest, s.name.size());
  for (const auto& s : mesh.sideSets) longest = std::max(longest, s.name.size());
  if (!steps.empty()) {
    for (const auto& f : steps.front().nodal) longest = std::max(longest, f.name.size());
    for (const auto& f : steps.front().element) longest = std::max(longest, f.name.size());
    for (const auto& g : steps.front().global) longest = std::max(longest, g.name.size());
  }
  return static_cast<int>(std::min<size_t>(longest, kMaxNameLength));
}

/// A 0-based id from the file as LO. Out-of-range ids stay out of range (clamped to
/// [-1, INT_MAX]) so that Mesh::validate reports them; numNodes/numElements <= INT_MAX.
LO toLO(int64_t zeroBased) { return static_cast<LO>(std::clamp<int64_t>(zeroBased, -1, INT_MAX)); }

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  return s;
}

/// Global variables, like fields, are declared once per file: same names in every step.
void checkSameGlobals(const std::vector<GlobalValue>& first, const std::vector<GlobalValue>& other, size_t step) {
  bool same = first.size() == other.size();
  for (size_t v = 0; same && v < first.size(); ++v) same = first[v].name == other[v].name;
  if (!same)
    throw std::invalid_argument("tribos::mesh::writeExodus: time step " + std::to_string(step + 1) +
                                " has other global variables than time step 1 (every step must carry the same)");
  for (size_t v = 0; v < other.size(); ++v)
    for (size_t w = 0; w < v; ++w)
      if (other[w].name == other[v].name)
        throw std::invalid_argument("tribos::mesh::writeExodus: global variable \"" + other[v].name +
                                    "\" appears twice");
}

/// Info records are lines of at most MAX_LINE_LENGTH (80) characters: longer lines are cut
/// into pieces rather than lost, so a parameter list written as info stays complete.
std::vector<std::string> infoLines(const std::vector<std::string>& info) {
  std::vector<std::string> lines;
  for (const auto& text : info) {
    if (text.empty()) lines.emplace_back();
    for (size_t at = 0; at < text.size(); at += MAX_LINE_LENGTH) lines.push_back(text.substr(at, MAX_LINE_LENGTH));
  }
  return lines;
}

void writeInfo(int id, const std::string& path, const std::vector<std::string>& info) {
  const auto lines = infoLines(info);
  if (lines.empty()) return;
  NameArray records(lines, MAX_LINE_LENGTH);
  check(ex_put_info(id, static_cast<int>(lines.size()), records.data()), path, "writing the info records");
}

void defineGlobals(int id, const std::string& path, const std::vector<GlobalValue>& globals, int nameLength) {
  if (globals.empty()) return;
  std::vector<std::string> names;
  for (const auto& g : globals) names.push_back(g.name);
  const int count = static_cast<int>(names.size());
  check(ex_put_variable_param(id, EX_GLOBAL, count), path, "defining global variables");
  NameArray n(names, nameLength);
  check(ex_put_variable_names(id, EX_GLOBAL, count, n.data()), path, "naming global variables");
}

void writeGlobals(int id, const std::string& path, int step, const std::vector<GlobalValue>& globals) {
  if (globals.empty()) return;
  std::vector<double> values;
  for (const auto& g : globals) values.push_back(g.value);
  // For EX_GLOBAL the library writes all variables of the step at once.
  check(ex_put_var(id, step, EX_GLOBAL, 1, 0, static_cast<int64_t>(values.size()), values.data()), path,
        "writing the global variables of time step " + std::to_string(step));
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
}  // namespace

void writeExodus(const std::string& path, const Mesh& mesh, const std::vector<TimeStep>& steps,
                 const std::vector<std::string>& info) {
  // Validate everything before touching the file, so a bad call does not clobber a good one.
  checkWritableMesh(mesh);
  for (size_t s = 0; s < steps.size(); ++s) {
    checkSameFields(steps.front().nodal, steps[s].nodal, s, "nodal");
    checkSameFields(steps.front().element, steps[s].element, s, "element");
    checkSameGlobals(steps.front().global, steps[s].global, s);
    checkFieldSizes(steps[s].nodal, mesh.numNodes(), "nodal", "nodes");
    checkFieldSizes(steps[s].element, mesh.numElements(), "element", "elements");
  }
  ex_opts(0);  // report errors through return codes (quiet, no abort); 0 is also 6.02's default
  int cpuWordSize = 8, ioWordSize = 8;  // doubles in memory and on disk: coordinates round-trip bitwise
  ExodusFile file(ex_create(path.c_str(), EX_CLOBBER, &cpuWordSize, &ioWordSize));
  if (file.id() < 0) throw core::InputError(path + ": cannot create the Exodus file");
  const int id = file.id();
  const int nameLength = std::max(kNameLength, longestName(mesh, steps));
  check(ex_set_max_name_length(id, nameLength), path, "setting the name length");
  check(ex_put_init(id, "Tribos", 3, mesh.numNodes(), mesh.numElements(), mesh.numBlocks(),
                    static_cast<int64_t>(mesh.nodeSets.size()), static_cast<int64_t>(mesh.sideSets.size())),
        path, "writing the header");
  std::vector<double> x(mesh.numNodes()), y(mesh.numNodes()), z(mesh.numNodes());
  for (LO n = 0; n < mesh.numNodes(); ++n) {
    x[n] = mesh.coords[n][0];
    y[n] = mesh.coords[n][1];
    z[n] = mesh.coords[n][2];
  }
  check(ex_put_coord(id, x.data(), y.data(), z.data()), path, "writing coordinates");
  NameArray coordNames(std::vector<std::string>{"x", "y", "z"}, nameLength);
  check(ex_put_coord_names(id, coordNames.data()), path, "writing coordinate names");
  writeInfo(id, path, info);

  // The file uses 32-bit ids (the default), which LO = int always fits.
  std::vector<std::string> names;
  for (const auto& b : mesh.blocks) {
    // "TETRA": meshio 5 maps "TETRA4" to a cell type it does not know (KeyError 'tetra4').
    check(ex_put_block(id, EX_ELEM_BLOCK, b.id, "TETRA", b.count, 4, 0, 0, 0), path, "writing block " + b.name);
    std::vector<int> conn(4 * static_cast<size_t>(b.count));
    for (LO e = 0; e < b.count; ++e)
      for (int v = 0; v < 4; ++v) conn[4 * static_cast<size_t>(e) + v] = mesh.tets[b.first + e][v] + 1;
    if (b.count > 0)
      check(ex_put_conn(id, EX_ELEM_BLOCK, b.id, conn.data(), nullptr, nullptr), path, "writing block " + b.name);
    names.push_back(b.name);
  }
  if (!names.empty()) {
    NameArray blockNames(names, nameLength);
    check(ex_put_names(id, EX_ELEM_BLOCK, blockNames.data()), path, "writing block names");
  }
  names.clear();
  for (const auto& s : mesh.nodeSets) {
    check(ex_put_set_param(id, EX_NODE_SET, s.id, static_cast<int64_t>(s.nodes.size()), 0), path, "writing node set " + s.name);
    std::vector<int> list(s.nodes.begin(), s.nodes.end());
    for (int& n : list) ++n;
    if (!list.empty()) check(ex_put_set(id, EX_NODE_SET, s.id, list.data(), nullptr), path, "writing node set " + s.name);
    names.push_back(s.name);
  }
  if (!names.empty()) {
    NameArray setNames(names, nameLength);
    check(ex_put_names(id, EX_NODE_SET, setNames.data()), path, "writing node set names");
  }
  names.clear();
  for (const auto& s : mesh.sideSets) {
    check(ex_put_set_param(id, EX_SIDE_SET, s.id, static_cast<int64_t>(s.elements.size()), 0), path,
          "writing side set " + s.name);
    std::vector<int> elements(s.elements.size()), sides(s.sides.size());
    for (size_t i = 0; i < elements.size(); ++i) {
      elements[i] = s.elements[i] + 1;
      sides[i] = s.sides[i] + 1;
    }
    if (!elements.empty())
      check(ex_put_set(id, EX_SIDE_SET, s.id, elements.data(), sides.data()), path, "writing side set " + s.name);
    names.push_back(s.name);
  }
  if (!names.empty()) {
    NameArray setNames(names, nameLength);
    check(ex_put_names(id, EX_SIDE_SET, setNames.data()), path, "writing side set names");
  }

  if (!steps.empty()) {
    defineGlobals(id, path, steps.front().global, nameLength);
    const auto nodalNames = fieldNames(steps.front().nodal), elementNames = fieldNames(steps.front().element);
    const int numNodal = static_cast<int>(nodalNames.size()), numElemVars = static_cast<int>(elementNames.size());
    if (numNodal > 0) {
      check(ex_put_variable_param(id, EX_NODAL, numNodal), path, "defining nodal variables");
      NameArray n(nodalNames, nameLength);
      check(ex_put_variable_names(id, EX_NODAL, numNodal, n.data()), path, "naming nodal variables");
    }
    if (numElemVars > 0 && mesh.numBlocks() > 0) {
      check(ex_put_variable_param(id, EX_ELEM_BLOCK, numElemVars), path, "defining element variables");
      NameArray n(elementNames, nameLength);
      check(ex_put_variable_names(id, EX_ELEM_BLOCK, numElemVars, n.data()), path, "naming element variables");
      // Every variable exists on every block. Declaring that up front defines all of them in
      // one go instead of one netCDF redefinition per (variable, block) at the first ex_put_var.
      std::vector<int> truth(static_cast<size_t>(mesh.numBlocks()) * numElemVars, 1);
      check(ex_put_truth_table(id, EX_ELEM_BLOCK, mesh.numBlocks(), numElemVars, truth.data()), path,
            "writing the element variable truth table");
    }
    for (size_t s = 0; s < steps.size(); ++s) {
      const int step = static_cast<int>(s) + 1;
      const double time = steps[s].time;
      check(ex_put_time(id, step, &time), path, "writing time");
      writeGlobals(id, path, step, steps[s].global);
      for (size_t v = 0; v < steps[s].nodal.size(); ++v)
        check(ex_put_var(id, step, EX_NODAL, static_cast<int>(v) + 1, 1, mesh.numNodes(), steps[s].nodal[v].values.data()),
              path, "writing nodal variable " + steps[s].nodal[v].name);
      for (size_t v = 0; v < steps[s].element.size(); ++v)
        for (const auto& b : mesh.blocks)
          if (b.count > 0)
            check(ex_put_var(id, step, EX_ELEM_BLOCK, static_cast<int>(v) + 1, b.id, b.count,
                             steps[s].element[v].values.data() + b.first),
                  path, "writing element variable " + steps[s].element[v].name);
    }
  }
  check(file.close(), path, "closing the file");
}

ExodusData readExodus(const std::string& path) {
  // Checked first because ex_open's answer for a missing file is the same as for a file
  // that is not Exodus.
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw core::InputError(path + ": the mesh file does not exist");
  core::requireRegularInputFile(path, "the mesh file");  // a FIFO or a device: never opened
  if (!std::ifstream(path)) throw core::InputError(path + ": cannot open the mesh file (unreadable)");
  ex_opts(0);  // quiet, no abort: errors come back as negative statuses and become InputErrors
  int cpuWordSize = 8, ioWordSize = 0;
  float version = 0.0f;
  ExodusFile file(ex_open(path.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version));
  if (file.id() < 0) throw core::InputError(path + ": not an Exodus II file, or a corrupt one (netCDF could not open it)");
  const int id = file.id();
  // With the 64-bit API, one code path reads files written with 32- or 64-bit ids.
  check(ex_set_int64_status(id, EX_ALL_INT64_API) < 0 ? -1 : 0, path, "selecting the 64-bit API");
  const int64_t usedNameLength = ex_inquire_int(id, EX_INQ_DB_MAX_USED_NAME_LENGTH);
  const int nameLength =
      static_cast<int>(std::clamp<int64_t>(usedNameLength, kNameLength, kMaxNameLength));
  check(ex_set_max_name_length(id, nameLength), path, "setting the name length");
  char title[MAX_LINE_LENGTH + 1] = {0};
  int64_t dim = 0, numNodes = 0, numElements = 0, numBlocks = 0, numNodeSets = 0, numSideSets = 0;
  check(ex_get_init(id, title, &dim, &numNodes, &numElements, &numBlocks, &numNodeSets, &numSideSets), path,
        "reading the header");
  if (dim != 3) throw core::InputError(path + ": the mesh is " + std::to_string(dim) + "D; Tribos needs a 3D mesh");
  if (numElements <= 0 || numBlocks <= 0) throw core::InputError(path + ": the mesh has no elements");
  if (numNodes < 4) throw core::InputError(path + ": the mesh has " + std::to_string(numNodes) + " nodes");
  if (numNodes > INT_MAX || numElements > INT_MAX)
    throw core::InputError(path + ": the mesh has more nodes or elements than Tribos can index");
  // A file stores its coordinates and connectivity; compressed (netCDF-4) it may hold more
  // values than bytes, but not a thousand times more: a bound for corrupt headers.
  const auto fileBytes = std::filesystem::file_size(path, ec);
  const int64_t fileValues = ec ? INT64_MAX : 1000 * static_cast<int64_t>(fileBytes);
  requireCount(numNodes, fileValues, path, "nodes", "more than a file of this size can hold");
  requireCount(numElements, fileValues, path, "elements", "more than a file of this size can hold");
  // Every other count is checked against these before it sizes an allocation.
  requireCount(numBlocks, numElements, path, "element blocks", "elements");
  requireCount(numNodeSets, kMaxEntities, path, "node sets", "Tribos reads");
  requireCount(numSideSets, kMaxEntities, path, "side sets", "Tribos reads");

  ExodusData data;
  Mesh& mesh = data.mesh;
  std::vector<double> x(numNodes), y(numNodes), z(numNodes);
  if (numNodes > 0) check(ex_get_coord(id, x.data(), y.data(), z.data()), path, "reading coordinates");
  mesh.coords.resize(numNodes);
  for (int64_t n = 0; n < numNodes; ++n) mesh.coords[n] = {x[n], y[n], z[n]};

  auto readIds = [&](ex_entity_type type, int64_t count, const char* kind) {
    std::vector<int64_t> ids(count);
    if (count > 0) check(ex_get_ids(id, type, ids.data()), path, std::string("reading ") + kind + " ids");
    // meshio numbers blocks and sets from 0; Exodus itself only asks for distinct ids.
    for (int64_t i : ids)
      if (i < 0 || i > INT_MAX)
        throw core::InputError(path + ": " + kind + " id " + std::to_string(i) + " is not in 0.." + std::to_string(INT_MAX));
    return ids;
  };
  // Files from other tools often carry no names; fall back to "<kind>_<id>" so that every
  // entity can still be referred to by name in a scene file.
  auto readNames = [&](ex_entity_type type, const std::vector<int64_t>& ids, const char* fallback) {
    NameArray names(ids.size(), nameLength);
    if (!ids.empty()) check(ex_get_names(id, type, names.data()), path, std::string("reading ") + fallback + " names");
    std::vector<std::string> out(ids.size());
    for (size_t i = 0; i < ids.size(); ++i) {
      out[i] = names[i];
      if (out[i].empty()) out[i] = std::string(fallback) + "_" + std::to_string(ids[i]);
    }
    return out;
  };

  const auto blockIds = readIds(EX_ELEM_BLOCK, numBlocks, "element block");
  const auto blockNames = readNames(EX_ELEM_BLOCK, blockIds, "block");
  for (int64_t b = 0; b < numBlocks; ++b) {
    ex_block block{};
    block.id = blockIds[b];
    block.type = EX_ELEM_BLOCK;
    check(ex_get_block_param(id, &block), path, "reading element block " + blockNames[b]);
    const std::string blockText = "element block \"" + blockNames[b] + "\" (id " + std::to_string(blockIds[b]) + ")";
    if (block.num_entry == 0) throw core::InputError(path + ": " + blockText + " has no elements");
    const std::string topology = upper(block.topology);
    if (!(topology == "TETRA" || topology == "TETRA4" || topology == "TET4" || topology == "TET") ||
        block.num_nodes_per_entry != 4)
      throw core::InputError(path + ": element block \"" + blockNames[b] + "\" (id " + std::to_string(blockIds[b]) +
                             ") has topology " + block.topology + " with " + std::to_string(block.num_nodes_per_entry) +
                             " nodes per element; Tribos needs linear tetrahedra (TETRA, 4 nodes)");
    requireCount(block.num_entry, numElements - static_cast<int64_t>(mesh.tets.size()), path,
                 "elements in " + blockText, "elements the header leaves for it");
    std::vector<int64_t> conn(4 * static_cast<size_t>(block.num_entry));
    if (block.num_entry > 0)
      check(ex_get_conn(id, EX_ELEM_BLOCK, blockIds[b], conn.data(), nullptr, nullptr), path,
            "reading element block " + blockNames[b]);
    ElementBlock eb{blockNames[b], static_cast<int>(blockIds[b]), static_cast<LO>(mesh.tets.size()),
                    static_cast<LO>(block.num_entry)};
    for (int64_t e = 0; e < block.num_entry; ++e) {
      std::array<LO, 4> tet;
      for (int v = 0; v < 4; ++v) {
        const int64_t node = conn[4 * e + v];
        if (node < 1 || node > numNodes)
          throw core::InputError(path + ": element " + std::to_string(eb.first + e + 1) + " of block \"" + eb.name +
                                 "\" references node " + std::to_string(node) + " out of range 1.." +
                                 std::to_string(numNodes) +
                                 (node == 0 ? " (0 is what netCDF reads where data is missing: a truncated file?)" : ""));
        tet[v] = static_cast<LO>(node - 1);
      }
      mesh.tets.push_back(tet);
    }
    mesh.blocks.push_back(eb);
  }
  if (static_cast<int64_t>(mesh.tets.size()) != numElements)
    throw core::InputError(path + ": the element blocks hold " + std::to_string(mesh.tets.size()) +
                           " elements but the header says " + std::to_string(numElements));

  // Ids from the file are range-checked by mesh.validate below, which names the bad id.
  const auto nodeSetIds = readIds(EX_NODE_SET, numNodeSets, "node set");
  const auto nodeSetNames = readNames(EX_NODE_SET, nodeSetIds, "nodeset");
  for (int64_t s = 0; s < numNodeSets; ++s) {
    int64_t count = 0, factors = 0;
    check(ex_get_set_param(id, EX_NODE_SET, nodeSetIds[s], &count, &factors), path, "reading node set " + nodeSetNames[s]);
    // Other writers repeat nodes (one entry per face corner), so allow each node many times.
    requireCount(count, kMaxNodeRepeats * numNodes, path, "entries in node set \"" + nodeSetNames[s] + "\"",
                 "the nodes allow");
    std::vector<int64_t> list(count);
    if (count > 0)
      check(ex_get_set(id, EX_NODE_SET, nodeSetIds[s], list.data(), nullptr), path, "reading node set " + nodeSetNames[s]);
    NodeSet ns{nodeSetNames[s], static_cast<int>(nodeSetIds[s]), {}};
    for (int64_t n : list) ns.nodes.push_back(toLO(n - 1));
    // Other tools write node sets in face order with repeats; Mesh wants them sorted, unique.
    std::sort(ns.nodes.begin(), ns.nodes.end());
    ns.nodes.erase(std::unique(ns.nodes.begin(), ns.nodes.end()), ns.nodes.end());
    mesh.nodeSets.push_back(std::move(ns));
  }
  const auto sideSetIds = readIds(EX_SIDE_SET, numSideSets, "side set");
  const auto sideSetNames = readNames(EX_SIDE_SET, sideSetIds, "sideset");
  for (int64_t s = 0; s < numSideSets; ++s) {
    int64_t count = 0, factors = 0;
    check(ex_get_set_param(id, EX_SIDE_SET, sideSetIds[s], &count, &factors), path, "reading side set " + sideSetNames[s]);
    requireCount(count, 4 * numElements, path, "faces in side set \"" + sideSetNames[s] + "\"", "the elements have");
    std::vector<int64_t> elements(count), sides(count);
    if (count > 0)
      check(ex_get_set(id, EX_SIDE_SET, sideSetIds[s], elements.data(), sides.data()), path,
            "reading side set " + sideSetNames[s]);
    SideSet ss{sideSetNames[s], static_cast<int>(sideSetIds[s]), {}, {}};
    for (int64_t i = 0; i < count; ++i) {
      ss.elements.push_back(toLO(elements[i] - 1));
      ss.sides.push_back(toLO(sides[i] - 1));
    }
    mesh.sideSets.push_back(std::move(ss));
  }
  mesh.file = path;
  mesh.validate(path);

  // Variables over time steps.
  const int64_t numSteps = ex_inquire_int(id, EX_INQ_TIME);
  if (numSteps < 0) check(-1, path, "counting time steps");
  requireCount(numSteps, kMaxEntities, path, "time steps", "Tribos reads");
  int numNodal = 0, numElemVars = 0;
  check(ex_get_variable_param(id, EX_NODAL, &numNodal), path, "counting nodal variables");
  check(ex_get_variable_param(id, EX_ELEM_BLOCK, &numElemVars), path, "counting element variables");
  requireCount(numNodal, kMaxEntities, path, "nodal variables", "Tribos reads");
  requireCount(numElemVars, kMaxEntities, path, "element variables", "Tribos reads");
  NameArray nodalNames(numNodal, nameLength), elemNames(numElemVars, nameLength);
  if (numNodal > 0)
    check(ex_get_variable_names(id, EX_NODAL, numNodal, nodalNames.data()), path, "reading nodal variable names");
  if (numElemVars > 0)
    check(ex_get_variable_names(id, EX_ELEM_BLOCK, numElemVars, elemNames.data()), path,
          "reading element variable names");
  // truth[b * numElemVars + v] != 0 when variable v is stored on block b; other writers may
  // leave a variable off some blocks, which then read as zeros.
  std::vector<int> truth(static_cast<size_t>(numBlocks) * numElemVars, 1);
  if (numElemVars > 0)
    check(ex_get_truth_table(id, EX_ELEM_BLOCK, static_cast<int>(numBlocks), numElemVars, truth.data()), path,
          "reading the element variable truth table");
  std::vector<double> times(numSteps);
  if (numSteps > 0) check(ex_get_all_times(id, times.data()), path, "reading times");
  for (int64_t s = 0; s < numSteps; ++s) {
    TimeStep step;
    step.time = times[s];
    const int stepIndex = static_cast<int>(s + 1);
    for (int v = 0; v < numNodal; ++v) {
      Field f{nodalNames[v], std::vector<double>(numNodes)};
      if (numNodes > 0)
        check(ex_get_var(id, stepIndex, EX_NODAL, v + 1, 1, numNodes, f.values.data()), path,
              "reading nodal variable " + f.name + " at time step " + std::to_string(stepIndex));
      step.nodal.push_back(std::move(f));
    }
    for (int v = 0; v < numElemVars; ++v) {
      Field f{elemNames[v], std::vector<double>(numElements, 0.0)};
      for (int64_t b = 0; b < numBlocks; ++b) {
        const auto& eb = mesh.blocks[b];
        if (eb.count > 0 && truth[b * numElemVars + v])
          check(ex_get_var(id, stepIndex, EX_ELEM_BLOCK, v + 1, eb.id, eb.count, f.values.data() + eb.first), path,
                "reading element variable " + f.name + " on block " + eb.name + " at time step " +
                    std::to_string(stepIndex));
      }
      step.element.push_back(std::move(f));
    }
    data.steps.push_back(std::move(step));
  }
  readGlobals(id, path, nameLength, data.steps);
  data.info = readInfo(id, path);
  return data;
}

}  // namespace tribos::mesh
