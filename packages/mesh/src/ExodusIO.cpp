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
#include "ExodusFile.hpp"

namespace tribos::mesh {

namespace {
using namespace exodus;

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

/// The writer reads the elements [b.first .. b.first + b.count) per block and parallel side-set
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

}  // namespace

namespace {
// Validate everything before touching the file, so a bad call does not clobber a good one.
/// One step checked against the first (names) and the mesh (sizes).
void checkStep(const Mesh& mesh, const TimeStep& first, const TimeStep& step, size_t index) {
  checkSameFields(first.nodal, step.nodal, index, "nodal");
  checkSameFields(first.element, step.element, index, "element");
  checkSameGlobals(first.global, step.global, index);
  checkFieldSizes(step.nodal, mesh.numNodes(), "nodal", "nodes");
  checkFieldSizes(step.element, mesh.numElements(), "element", "elements");
}

void checkWritable(const Mesh& mesh, const std::vector<TimeStep>& steps) {
  checkWritableMesh(mesh);
  for (size_t s = 0; s < steps.size(); ++s) checkStep(mesh, steps.front(), steps[s], s);
}

void writeCoordinates(int id, const std::string& path, const Mesh& mesh, int nameLength) {
  std::vector<double> x(mesh.numNodes()), y(mesh.numNodes()), z(mesh.numNodes());
  for (LO n = 0; n < mesh.numNodes(); ++n) {
    x[n] = mesh.coords[n][0];
    y[n] = mesh.coords[n][1];
    z[n] = mesh.coords[n][2];
  }
  check(ex_put_coord(id, x.data(), y.data(), z.data()), path, "writing coordinates");
  NameArray coordNames(std::vector<std::string>{"x", "y", "z"}, nameLength);
  check(ex_put_coord_names(id, coordNames.data()), path, "writing coordinate names");
}

void writeNames(int id, const std::string& path, ex_entity_type type, const std::vector<std::string>& names,
                int nameLength, const char* what) {
  if (names.empty()) return;
  NameArray array(names, nameLength);
  check(ex_put_names(id, type, array.data()), path, std::string("writing ") + what + " names");
}

// The file uses 32-bit ids (the default), which LO = int always fits.
void writeBlocks(int id, const std::string& path, const Mesh& mesh, const std::vector<BlockPart>& parts,
                 int nameLength) {
  std::vector<std::string> names;
  for (const auto& part : parts) {
    const ElementShape& shape = elementShape(part.type);
    const std::string& name = mesh.blocks[part.body].name;
    check(ex_put_block(id, EX_ELEM_BLOCK, part.id, shape.exodusName, part.count, shape.numNodes, 0, 0, 0), path,
          "writing block " + name);
    std::vector<int> conn;
    conn.reserve(static_cast<size_t>(part.count) * shape.numNodes);
    for (LO e = part.first; e < part.first + part.count; ++e)
      for (LO n : mesh.elementNodes(e)) conn.push_back(n + 1);
    if (part.count > 0)
      check(ex_put_conn(id, EX_ELEM_BLOCK, part.id, conn.data(), nullptr, nullptr), path, "writing block " + name);
    names.push_back(name);
  }
  writeNames(id, path, EX_ELEM_BLOCK, names, nameLength, "block");
}

void writeSets(int id, const std::string& path, const Mesh& mesh, int nameLength) {
  std::vector<std::string> names;
  for (const auto& s : mesh.nodeSets) {
    check(ex_put_set_param(id, EX_NODE_SET, s.id, static_cast<int64_t>(s.nodes.size()), 0), path, "writing node set " + s.name);
    std::vector<int> list(s.nodes.begin(), s.nodes.end());
    for (int& n : list) ++n;
    if (!list.empty()) check(ex_put_set(id, EX_NODE_SET, s.id, list.data(), nullptr), path, "writing node set " + s.name);
    names.push_back(s.name);
  }
  writeNames(id, path, EX_NODE_SET, names, nameLength, "node set");
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
  writeNames(id, path, EX_SIDE_SET, names, nameLength, "side set");
}

/// The variables, declared once for the file from the first step's names.
void defineVariables(int id, const std::string& path, const std::vector<BlockPart>& parts, const TimeStep& first,
                     int nameLength) {
  defineGlobals(id, path, first.global, nameLength);
  const auto nodalNames = fieldNames(first.nodal), elementNames = fieldNames(first.element);
  const int numNodal = static_cast<int>(nodalNames.size()), numElemVars = static_cast<int>(elementNames.size());
  if (numNodal > 0) {
    check(ex_put_variable_param(id, EX_NODAL, numNodal), path, "defining nodal variables");
    NameArray n(nodalNames, nameLength);
    check(ex_put_variable_names(id, EX_NODAL, numNodal, n.data()), path, "naming nodal variables");
  }
  const int numParts = static_cast<int>(parts.size());
  if (numElemVars > 0 && numParts > 0) {
    check(ex_put_variable_param(id, EX_ELEM_BLOCK, numElemVars), path, "defining element variables");
    NameArray n(elementNames, nameLength);
    check(ex_put_variable_names(id, EX_ELEM_BLOCK, numElemVars, n.data()), path, "naming element variables");
    // Every variable exists on every block. Declaring that up front defines all of them in
    // one go instead of one netCDF redefinition per (variable, block) at the first ex_put_var.
    std::vector<int> truth(static_cast<size_t>(numParts) * numElemVars, 1);
    check(ex_put_truth_table(id, EX_ELEM_BLOCK, numParts, numElemVars, truth.data()), path,
          "writing the element variable truth table");
  }
}

/// The values of time step `step` (1-based).
void writeStep(int id, const std::string& path, const Mesh& mesh, const std::vector<BlockPart>& parts, int step,
               const TimeStep& values) {
  check(ex_put_time(id, step, &values.time), path, "writing time");
  writeGlobals(id, path, step, values.global);
  for (size_t v = 0; v < values.nodal.size(); ++v)
    check(ex_put_var(id, step, EX_NODAL, static_cast<int>(v) + 1, 1, mesh.numNodes(), values.nodal[v].values.data()),
          path, "writing nodal variable " + values.nodal[v].name);
  for (size_t v = 0; v < values.element.size(); ++v)
    for (const auto& part : parts)
      if (part.count > 0)
        check(ex_put_var(id, step, EX_ELEM_BLOCK, static_cast<int>(v) + 1, part.id, part.count,
                         values.element[v].values.data() + part.first),
              path, "writing element variable " + values.element[v].name);
}

}  // namespace

struct ExodusWriter::Open {
  explicit Open(int id, std::vector<exodus::BlockPart> p) : file(id), parts(std::move(p)) {}
  exodus::ExodusFile file;
  std::vector<exodus::BlockPart> parts;
  TimeStep first;  ///< the first step's names (its values dropped)
};

ExodusWriter::ExodusWriter(std::string path, const Mesh& mesh, std::vector<std::string> info)
    : path_(std::move(path)), mesh_(mesh), info_(std::move(info)) {
  checkWritableMesh(mesh_);
}

ExodusWriter::~ExodusWriter() = default;

/// Creates the file: the header, coordinates, info, blocks and sets, and the variables of
/// `first` (none: a mesh-only file).
void ExodusWriter::create(const TimeStep* first) {
  ex_opts(0);  // report errors through return codes (quiet, no abort); 0 is also 6.02's default
  int cpuWordSize = 8, ioWordSize = 8;  // doubles in memory and on disk: coordinates round-trip bitwise
  const int id = ex_create(path_.c_str(), EX_CLOBBER, &cpuWordSize, &ioWordSize);
  if (id < 0) throw core::InputError(path_ + ": cannot create the Exodus file");
  open_ = std::make_unique<Open>(id, blockParts(mesh_));
  const std::vector<TimeStep> names = first ? std::vector<TimeStep>{*first} : std::vector<TimeStep>{};
  const int nameLength = std::max(kNameLength, longestName(mesh_, names));
  check(ex_set_max_name_length(id, nameLength), path_, "setting the name length");
  check(ex_put_init(id, "Tribos", 3, mesh_.numNodes(), mesh_.numElements(), static_cast<int64_t>(open_->parts.size()),
                    static_cast<int64_t>(mesh_.nodeSets.size()), static_cast<int64_t>(mesh_.sideSets.size())),
        path_, "writing the header");
  writeCoordinates(id, path_, mesh_, nameLength);
  writeInfo(id, path_, info_);
  writeBlocks(id, path_, mesh_, open_->parts, nameLength);
  writeSets(id, path_, mesh_, nameLength);
  if (!first) return;
  defineVariables(id, path_, open_->parts, *first, nameLength);
  for (const auto& f : first->nodal) open_->first.nodal.push_back({f.name, {}});
  for (const auto& f : first->element) open_->first.element.push_back({f.name, {}});
  open_->first.global = first->global;
}

void ExodusWriter::append(const TimeStep& step) {
  if (closed_) throw std::logic_error("tribos::mesh::ExodusWriter::append after close (" + path_ + ")");
  checkStep(mesh_, open_ ? open_->first : step, step, static_cast<size_t>(steps_));
  if (!open_) create(&step);
  ++steps_;
  writeStep(open_->file.id(), path_, mesh_, open_->parts, steps_, step);
  check(ex_update(open_->file.id()), path_, "flushing time step " + std::to_string(steps_));
}

void ExodusWriter::close() {
  if (closed_) return;
  if (!open_) create(nullptr);
  closed_ = true;
  check(open_->file.close(), path_, "closing the file");
}

void writeExodus(const std::string& path, const Mesh& mesh, const std::vector<TimeStep>& steps,
                 const std::vector<std::string>& info) {
  checkWritable(mesh, steps);  // everything before touching the file: a bad call does not clobber a good one
  ExodusWriter writer(path, mesh, info);
  for (const auto& step : steps) writer.append(step);
  writer.close();
}

}  // namespace tribos::mesh
