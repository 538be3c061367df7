#include "tribos/mesh/GmshReader.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "tribos/core/Errors.hpp"

namespace tribos::mesh {

namespace {
struct Triangle {
  std::array<long long, 3> nodes;
  int physical;
};
struct Tet {
  std::array<long long, 4> nodes;
  int physical;
};
}  // namespace

Mesh readGmsh(const std::string& path, bool splitBodies) {
  std::ifstream in(path);
  if (!in) throw core::InputError(path + ": cannot open the gmsh file");
  auto fail = [&](const std::string& what) -> void { throw core::InputError(path + ": " + what); };

  std::map<std::pair<int, int>, std::string> physicalName;       // (dim, tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> entityPhysical;  // (dim, entity) -> physical tags
  std::map<long long, std::array<double, 3>> nodes;
  std::vector<Tet> tets;
  std::vector<Triangle> triangles;
  std::string section;
  bool sawFormat = false;
  while (in >> section) {
    if (section == "$MeshFormat") {
      double version = 0;
      int binary = 1, size = 0;
      in >> version >> binary >> size;
      if (version < 4.0 || version >= 5.0 || binary != 0)
        fail("only gmsh 4.x ASCII meshes are read (gmsh -format msh41); this file is version " +
             std::to_string(version) + (binary ? " binary" : ""));
      sawFormat = true;
    } else if (section == "$PhysicalNames") {
      int count = 0;
      in >> count;
      for (int i = 0; i < count; ++i) {
        int dim = 0, tag = 0;
        std::string name;
        in >> dim >> tag;
        std::getline(in, name);
        const auto first = name.find('"'), last = name.rfind('"');
        physicalName[{dim, tag}] = first == std::string::npos ? name : name.substr(first + 1, last - first - 1);
      }
    } else if (section == "$Entities") {
      long long counts[4];
      in >> counts[0] >> counts[1] >> counts[2] >> counts[3];
      for (int dim = 0; dim < 4; ++dim)
        for (long long e = 0; e < counts[dim]; ++e) {
          int tag = 0;
          double box[6];
          in >> tag;
          for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) in >> box[k];
          int numPhysical = 0;
          in >> numPhysical;
          std::vector<int> phys(numPhysical);
          for (int& p : phys) in >> p;
          entityPhysical[{dim, tag}] = phys;
          if (dim > 0) {
            int numBounding = 0;
            in >> numBounding;
            for (int k = 0; k < numBounding; ++k) {
              long long skip;
              in >> skip;
            }
          }
        }
    } else if (section == "$Nodes") {
      long long blocks = 0, count = 0, minTag = 0, maxTag = 0;
      in >> blocks >> count >> minTag >> maxTag;
      for (long long b = 0; b < blocks; ++b) {
        int dim = 0, entity = 0, parametric = 0;
        long long inBlock = 0;
        in >> dim >> entity >> parametric >> inBlock;
        if (parametric) fail("parametric node coordinates are not supported");
        std::vector<long long> tags(inBlock);
        for (auto& t : tags) in >> t;
        for (auto t : tags) {
          std::array<double, 3> x;
          in >> x[0] >> x[1] >> x[2];
          nodes[t] = x;
        }
      }
    } else if (section == "$Elements") {
      long long blocks = 0, count = 0, minTag = 0, maxTag = 0;
      in >> blocks >> count >> minTag >> maxTag;
      for (long long b = 0; b < blocks; ++b) {
        int dim = 0, entity = 0, type = 0;
        long long inBlock = 0;
        in >> dim >> entity >> type >> inBlock;
        const auto& phys = entityPhysical[{dim, entity}];
        const int physical = phys.empty() ? 0 : phys.front();
        const int perElement = type == 4 ? 4 : type == 2 ? 3 : type == 1 ? 2 : type == 15 ? 1 : -1;
        if (dim == 3 && type != 4)
          fail("volume entity " + std::to_string(entity) + " has elements of gmsh type " + std::to_string(type) +
               "; Tribos needs 4-node tetrahedra (type 4)");
        if (perElement < 0) fail("unsupported gmsh element type " + std::to_string(type));
        for (long long e = 0; e < inBlock; ++e) {
          long long tag;
          in >> tag;
          std::array<long long, 4> v{};
          for (int k = 0; k < perElement; ++k) in >> v[k];
          if (type == 4) tets.push_back({v, physical});
          if (type == 2) triangles.push_back({{v[0], v[1], v[2]}, physical});
        }
      }
    }
  }
  if (!sawFormat) fail("not a gmsh mesh ($MeshFormat missing)");
  if (tets.empty()) fail("no tetrahedra (mesh in 3D with a Physical Volume)");

  // Bodies in the order of their physical tags; elements sorted by body (contiguous blocks).
  std::set<int> bodyTags;
  for (const auto& t : tets) bodyTags.insert(t.physical);
  std::vector<int> bodies(bodyTags.begin(), bodyTags.end());
  std::stable_sort(tets.begin(), tets.end(), [](const Tet& a, const Tet& b) { return a.physical < b.physical; });

  // Node numbering per (gmsh node, body): one node unless split and shared.
  Mesh mesh;
  std::map<std::pair<long long, int>, LO> nodeId;
  std::map<long long, LO> sharedId;
  auto idOf = [&](long long gmshNode, int body) -> LO {
    const auto it = nodes.find(gmshNode);
    if (it == nodes.end()) fail("element references node " + std::to_string(gmshNode) + " that does not exist");
    if (!splitBodies) {
      auto [pos, inserted] = sharedId.insert({gmshNode, static_cast<LO>(mesh.coords.size())});
      if (inserted) mesh.coords.push_back(it->second);
      return pos->second;
    }
    auto [pos, inserted] = nodeId.insert({{gmshNode, body}, static_cast<LO>(mesh.coords.size())});
    if (inserted) mesh.coords.push_back(it->second);
    return pos->second;
  };
  std::map<std::array<LO, 3>, std::vector<std::pair<LO, int>>> faces;  // sorted gmsh nodes -> (element, side)
  std::map<int, int> blockOfBody;
  for (size_t e = 0; e < tets.size(); ++e) {
    const int body = tets[e].physical;
    if (!blockOfBody.count(body)) {
      const auto name = physicalName.count({3, body}) ? physicalName[{3, body}] : "volume_" + std::to_string(body);
      blockOfBody[body] = static_cast<int>(mesh.blocks.size());
      mesh.blocks.push_back({name, body > 0 ? body : static_cast<int>(mesh.blocks.size()) + 1, static_cast<LO>(e), 0});
    }
    mesh.blocks[blockOfBody[body]].count++;
    std::array<LO, 4> t;
    for (int v = 0; v < 4; ++v) t[v] = idOf(tets[e].nodes[v], body);
    mesh.tets.push_back(t);
    if (mesh.elementVolume(static_cast<LO>(e)) < 0.0) {
      std::swap(mesh.tets.back()[2], mesh.tets.back()[3]);
      std::swap(tets[e].nodes[2], tets[e].nodes[3]);
    }
    for (int side = 0; side < 4; ++side) {
      std::array<LO, 3> key;
      for (int k = 0; k < 3; ++k) key[k] = static_cast<LO>(tets[e].nodes[kTetFaceVertices[side][k]]);
      std::sort(key.begin(), key.end());
      faces[key].push_back({static_cast<LO>(e), side});
    }
  }

  // Side sets from the physical surfaces; a surface between two bodies gives one per body.
  std::map<int, std::map<int, SideSet>> sets;  // surface tag -> body -> set
  for (const auto& tri : triangles) {
    if (tri.physical == 0) continue;
    std::array<LO, 3> key{static_cast<LO>(tri.nodes[0]), static_cast<LO>(tri.nodes[1]), static_cast<LO>(tri.nodes[2])};
    std::sort(key.begin(), key.end());
    const auto it = faces.find(key);
    if (it == faces.end())
      fail("a triangle of Physical Surface " + std::to_string(tri.physical) + " is not a face of any tetrahedron");
    for (const auto& [element, side] : it->second) {
      auto& set = sets[tri.physical][tets[element].physical];
      set.elements.push_back(element);
      set.sides.push_back(side);
    }
  }
  int id = 1;
  for (auto& [surface, byBody] : sets) {
    const auto base = physicalName.count({2, surface}) ? physicalName[{2, surface}] : "surface_" + std::to_string(surface);
    for (auto& [body, set] : byBody) {
      set.name = byBody.size() > 1 ? base + "_" + mesh.blocks[blockOfBody[body]].name : base;
      set.id = id++;
      NodeSet ns{set.name, set.id, {}};
      for (size_t f = 0; f < set.elements.size(); ++f)
        for (int v : kTetFaceVertices[set.sides[f]]) ns.nodes.push_back(mesh.tets[set.elements[f]][v]);
      std::sort(ns.nodes.begin(), ns.nodes.end());
      ns.nodes.erase(std::unique(ns.nodes.begin(), ns.nodes.end()), ns.nodes.end());
      mesh.sideSets.push_back(set);
      mesh.nodeSets.push_back(std::move(ns));
    }
  }
  mesh.validate(path);
  return mesh;
}

}  // namespace tribos::mesh
