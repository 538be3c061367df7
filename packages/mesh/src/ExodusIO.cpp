// Exodus II I/O with the classic ex_* C API (Debian's exodusii 6.02). Exodus ids are
// 1-based; Mesh uses 0-based nodes/elements and sides 0..3 (Exodus side = side + 1).
#include "tribos/mesh/ExodusIO.hpp"

#include <exodusII.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <stdexcept>

#include "tribos/core/Errors.hpp"

namespace tribos::mesh {

namespace {
constexpr int kNameLength = 64;

/// Closes the file on every path out of a reader/writer.
class ExodusFile {
 public:
  explicit ExodusFile(int id) : id_(id) {}
  ~ExodusFile() {
    if (id_ >= 0) ex_close(id_);
  }
  int id() const { return id_; }

 private:
  int id_;
};

/// Owns a char*[] for the name APIs (which take non-const char**).
class NameArray {
 public:
  explicit NameArray(size_t count) : storage_(count, std::string(kNameLength + 1, '\0')), pointers_(count) {
    for (size_t i = 0; i < count; ++i) pointers_[i] = storage_[i].data();
  }
  explicit NameArray(const std::vector<std::string>& names) : NameArray(names.size()) {
    for (size_t i = 0; i < names.size(); ++i) names[i].copy(pointers_[i], std::min<size_t>(names[i].size(), kNameLength));
  }
  char** data() { return pointers_.data(); }
  std::string operator[](size_t i) const { return std::string(pointers_[i]); }

 private:
  std::vector<std::string> storage_;
  std::vector<char*> pointers_;
};

void check(int status, const std::string& path, const std::string& what) {
  if (status < 0) throw core::InputError(path + ": Exodus error while " + what + " (status " + std::to_string(status) + ")");
}

std::vector<std::string> fieldNames(const std::vector<Field>& fields) {
  std::vector<std::string> names;
  for (const auto& f : fields) names.push_back(f.name);
  return names;
}
}  // namespace

void writeExodus(const std::string& path, const Mesh& mesh, const std::vector<TimeStep>& steps) {
  for (const auto& step : steps) {
    if (fieldNames(step.nodal) != fieldNames(steps.front().nodal) ||
        fieldNames(step.element) != fieldNames(steps.front().element))
      throw std::invalid_argument("tribos::mesh::writeExodus: every time step must carry the same fields");
    for (const auto& f : step.nodal)
      if (static_cast<LO>(f.values.size()) != mesh.numNodes())
        throw std::invalid_argument("tribos::mesh::writeExodus: nodal field \"" + f.name + "\" has " +
                                    std::to_string(f.values.size()) + " values for " + std::to_string(mesh.numNodes()) + " nodes");
    for (const auto& f : step.element)
      if (static_cast<LO>(f.values.size()) != mesh.numElements())
        throw std::invalid_argument("tribos::mesh::writeExodus: element field \"" + f.name + "\" has " +
                                    std::to_string(f.values.size()) + " values for " + std::to_string(mesh.numElements()) +
                                    " elements");
  }
  ex_opts(0);  // report errors through return codes, never abort the process
  int cpuWordSize = 8, ioWordSize = 8;
  const ExodusFile file(ex_create(path.c_str(), EX_CLOBBER, &cpuWordSize, &ioWordSize));
  if (file.id() < 0) throw core::InputError(path + ": cannot create the Exodus file");
  const int id = file.id();
  ex_set_max_name_length(id, kNameLength);
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
  NameArray coordNames(std::vector<std::string>{"x", "y", "z"});
  check(ex_put_coord_names(id, coordNames.data()), path, "writing coordinate names");

  std::vector<std::string> names;
  for (const auto& b : mesh.blocks) {
    check(ex_put_block(id, EX_ELEM_BLOCK, b.id, "TETRA4", b.count, 4, 0, 0, 0), path, "writing block " + b.name);
    std::vector<int> conn(4 * static_cast<size_t>(b.count));
    for (LO e = 0; e < b.count; ++e)
      for (int v = 0; v < 4; ++v) conn[4 * e + v] = mesh.tets[b.first + e][v] + 1;
    check(ex_put_conn(id, EX_ELEM_BLOCK, b.id, conn.data(), nullptr, nullptr), path, "writing block " + b.name);
    names.push_back(b.name);
  }
  if (!names.empty()) {
    NameArray blockNames(names);
    check(ex_put_names(id, EX_ELEM_BLOCK, blockNames.data()), path, "writing block names");
  }
  names.clear();
  for (const auto& s : mesh.nodeSets) {
    check(ex_put_set_param(id, EX_NODE_SET, s.id, static_cast<int64_t>(s.nodes.size()), 0), path, "writing node set " + s.name);
    std::vector<int> list(s.nodes.begin(), s.nodes.end());
    for (int& n : list) ++n;
    check(ex_put_set(id, EX_NODE_SET, s.id, list.data(), nullptr), path, "writing node set " + s.name);
    names.push_back(s.name);
  }
  if (!names.empty()) {
    NameArray setNames(names);
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
    check(ex_put_set(id, EX_SIDE_SET, s.id, elements.data(), sides.data()), path, "writing side set " + s.name);
    names.push_back(s.name);
  }
  if (!names.empty()) {
    NameArray setNames(names);
    check(ex_put_names(id, EX_SIDE_SET, setNames.data()), path, "writing side set names");
  }

  if (steps.empty()) return;
  const auto nodalNames = fieldNames(steps.front().nodal), elementNames = fieldNames(steps.front().element);
  if (!nodalNames.empty()) {
    check(ex_put_variable_param(id, EX_NODAL, static_cast<int>(nodalNames.size())), path, "defining nodal variables");
    NameArray n(nodalNames);
    check(ex_put_variable_names(id, EX_NODAL, static_cast<int>(nodalNames.size()), n.data()), path, "naming nodal variables");
  }
  if (!elementNames.empty()) {
    check(ex_put_variable_param(id, EX_ELEM_BLOCK, static_cast<int>(elementNames.size())), path,
          "defining element variables");
    NameArray n(elementNames);
    check(ex_put_variable_names(id, EX_ELEM_BLOCK, static_cast<int>(elementNames.size()), n.data()), path,
          "naming element variables");
  }
  for (size_t s = 0; s < steps.size(); ++s) {
    const int step = static_cast<int>(s) + 1;
    const double time = steps[s].time;
    check(ex_put_time(id, step, &time), path, "writing time");
    for (size_t v = 0; v < steps[s].nodal.size(); ++v)
      check(ex_put_var(id, step, EX_NODAL, static_cast<int>(v) + 1, 1, mesh.numNodes(), steps[s].nodal[v].values.data()),
            path, "writing nodal variable " + steps[s].nodal[v].name);
    for (size_t v = 0; v < steps[s].element.size(); ++v)
      for (const auto& b : mesh.blocks)
        check(ex_put_var(id, step, EX_ELEM_BLOCK, static_cast<int>(v) + 1, b.id, b.count,
                         steps[s].element[v].values.data() + b.first),
              path, "writing element variable " + steps[s].element[v].name);
  }
}

ExodusData readExodus(const std::string& path) {
  if (!std::ifstream(path)) throw core::InputError(path + ": cannot open the mesh file (missing or unreadable)");
  ex_opts(0);
  int cpuWordSize = 8, ioWordSize = 0;
  float version = 0.0f;
  const ExodusFile file(ex_open(path.c_str(), EX_READ, &cpuWordSize, &ioWordSize, &version));
  if (file.id() < 0) throw core::InputError(path + ": not an Exodus II file");
  const int id = file.id();
  ex_set_int64_status(id, EX_ALL_INT64_API);
  ex_set_max_name_length(id, kNameLength);
  char title[MAX_LINE_LENGTH + 1] = {0};
  int64_t dim = 0, numNodes = 0, numElements = 0, numBlocks = 0, numNodeSets = 0, numSideSets = 0;
  check(ex_get_init(id, title, &dim, &numNodes, &numElements, &numBlocks, &numNodeSets, &numSideSets), path,
        "reading the header");
  if (dim != 3) throw core::InputError(path + ": the mesh is " + std::to_string(dim) + "D; Tribos needs a 3D mesh");
  if (numElements <= 0 || numBlocks <= 0) throw core::InputError(path + ": the mesh has no elements");

  ExodusData data;
  Mesh& mesh = data.mesh;
  std::vector<double> x(numNodes), y(numNodes), z(numNodes);
  check(ex_get_coord(id, x.data(), y.data(), z.data()), path, "reading coordinates");
  mesh.coords.resize(numNodes);
  for (int64_t n = 0; n < numNodes; ++n) mesh.coords[n] = {x[n], y[n], z[n]};

  auto readNames = [&](ex_entity_type type, int64_t count, const char* fallback, const std::vector<int64_t>& ids) {
    NameArray names(static_cast<size_t>(count));
    std::vector<std::string> out(count);
    if (count > 0) check(ex_get_names(id, type, names.data()), path, "reading names");
    for (int64_t i = 0; i < count; ++i) {
      out[i] = names[i];
      if (out[i].empty()) out[i] = std::string(fallback) + "_" + std::to_string(ids[i]);
    }
    return out;
  };
  auto readIds = [&](ex_entity_type type, int64_t count) {
    std::vector<int64_t> ids(count);
    if (count > 0) check(ex_get_ids(id, type, ids.data()), path, "reading ids");
    return ids;
  };

  const auto blockIds = readIds(EX_ELEM_BLOCK, numBlocks);
  const auto blockNames = readNames(EX_ELEM_BLOCK, numBlocks, "block", blockIds);
  for (int64_t b = 0; b < numBlocks; ++b) {
    ex_block block{};
    block.id = blockIds[b];
    block.type = EX_ELEM_BLOCK;
    check(ex_get_block_param(id, &block), path, "reading element block " + blockNames[b]);
    std::string topology = block.topology;
    std::transform(topology.begin(), topology.end(), topology.begin(), [](unsigned char c) { return std::toupper(c); });
    if (!(topology == "TETRA" || topology == "TETRA4" || topology == "TET4" || topology == "TET") ||
        block.num_nodes_per_entry != 4)
      throw core::InputError(path + ": element block \"" + blockNames[b] + "\" (id " + std::to_string(blockIds[b]) +
                             ") has topology " + block.topology + " with " + std::to_string(block.num_nodes_per_entry) +
                             " nodes; Tribos needs linear tetrahedra (TETRA4)");
    std::vector<int64_t> conn(4 * static_cast<size_t>(block.num_entry));
    if (block.num_entry > 0) check(ex_get_conn(id, EX_ELEM_BLOCK, blockIds[b], conn.data(), nullptr, nullptr), path,
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
                                 std::to_string(numNodes));
        tet[v] = static_cast<LO>(node - 1);
      }
      mesh.tets.push_back(tet);
    }
    mesh.blocks.push_back(eb);
  }

  const auto nodeSetIds = readIds(EX_NODE_SET, numNodeSets);
  const auto nodeSetNames = readNames(EX_NODE_SET, numNodeSets, "nodeset", nodeSetIds);
  for (int64_t s = 0; s < numNodeSets; ++s) {
    int64_t count = 0, factors = 0;
    check(ex_get_set_param(id, EX_NODE_SET, nodeSetIds[s], &count, &factors), path, "reading node set " + nodeSetNames[s]);
    std::vector<int64_t> list(count);
    if (count > 0) check(ex_get_set(id, EX_NODE_SET, nodeSetIds[s], list.data(), nullptr), path, "reading node set");
    NodeSet ns{nodeSetNames[s], static_cast<int>(nodeSetIds[s]), {}};
    for (int64_t n : list) ns.nodes.push_back(static_cast<LO>(n - 1));
    std::sort(ns.nodes.begin(), ns.nodes.end());
    ns.nodes.erase(std::unique(ns.nodes.begin(), ns.nodes.end()), ns.nodes.end());
    mesh.nodeSets.push_back(std::move(ns));
  }
  const auto sideSetIds = readIds(EX_SIDE_SET, numSideSets);
  const auto sideSetNames = readNames(EX_SIDE_SET, numSideSets, "sideset", sideSetIds);
  for (int64_t s = 0; s < numSideSets; ++s) {
    int64_t count = 0, factors = 0;
    check(ex_get_set_param(id, EX_SIDE_SET, sideSetIds[s], &count, &factors), path, "reading side set " + sideSetNames[s]);
    std::vector<int64_t> elements(count), sides(count);
    if (count > 0) check(ex_get_set(id, EX_SIDE_SET, sideSetIds[s], elements.data(), sides.data()), path, "reading side set");
    SideSet ss{sideSetNames[s], static_cast<int>(sideSetIds[s]), {}, {}};
    for (int64_t i = 0; i < count; ++i) {
      ss.elements.push_back(static_cast<LO>(elements[i] - 1));
      ss.sides.push_back(static_cast<int>(sides[i] - 1));
    }
    mesh.sideSets.push_back(std::move(ss));
  }
  mesh.validate(path);

  // Variables over time steps.
  const int64_t numSteps = ex_inquire_int(id, EX_INQ_TIME);
  int numNodal = 0, numElemVars = 0;
  ex_get_variable_param(id, EX_NODAL, &numNodal);
  ex_get_variable_param(id, EX_ELEM_BLOCK, &numElemVars);
  NameArray nodalNames(numNodal), elemNames(numElemVars);
  if (numNodal > 0) check(ex_get_variable_names(id, EX_NODAL, numNodal, nodalNames.data()), path, "reading variable names");
  if (numElemVars > 0)
    check(ex_get_variable_names(id, EX_ELEM_BLOCK, numElemVars, elemNames.data()), path, "reading variable names");
  std::vector<double> times(numSteps);
  if (numSteps > 0) check(ex_get_all_times(id, times.data()), path, "reading times");
  for (int64_t s = 0; s < numSteps; ++s) {
    TimeStep step;
    step.time = times[s];
    for (int v = 0; v < numNodal; ++v) {
      Field f{nodalNames[v], std::vector<double>(numNodes)};
      check(ex_get_var(id, static_cast<int>(s + 1), EX_NODAL, v + 1, 1, numNodes, f.values.data()), path,
            "reading nodal variable " + f.name);
      step.nodal.push_back(std::move(f));
    }
    for (int v = 0; v < numElemVars; ++v) {
      Field f{elemNames[v], std::vector<double>(numElements, 0.0)};
      for (const auto& b : mesh.blocks)
        if (b.count > 0)  // a block without the variable keeps zeros
          ex_get_var(id, static_cast<int>(s + 1), EX_ELEM_BLOCK, v + 1, b.id, b.count, f.values.data() + b.first);
      step.element.push_back(std::move(f));
    }
    data.steps.push_back(std::move(step));
  }
  return data;
}

}  // namespace tribos::mesh
