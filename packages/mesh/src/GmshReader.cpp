// gmsh 4.1 ASCII reader. The file is read whole and split into tokens by a reader that
// knows its line and section, so every message can say "file: line 12 ($Nodes): ...".
// Nothing read from the file sizes an allocation before it has been checked against what
// the rest of the file can hold (a corrupt count once asked std::vector for 10^19 entries).
#include "tribos/mesh/GmshReader.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unordered_map>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/core/InputFiles.hpp"

namespace tribos::mesh {

namespace {
/// A surface element (3- or 6-node triangle, 4-node quadrilateral): a face of a volume one.
struct SurfaceElement {
  std::array<long long, kMaxFaceNodes> nodes;
  int numVertices;
  std::vector<int> physicals;  ///< every physical group of its surface (several may name it)
  long long tag;
};
/// A volume element, its nodes in Exodus order (ElementTypes.hpp).
struct VolumeElement {
  std::array<long long, kMaxElementNodes> nodes;
  ElementType type;
  int physical;
  long long tag;
};

/// What the sections hold, in gmsh's own numbering (tags).
struct GmshContent {
  std::map<std::pair<int, int>, std::string> physicalName;       // (dim, tag) -> name
  std::map<std::pair<int, int>, std::vector<int>> entityPhysical;  // (dim, entity) -> physical tags
  std::unordered_map<long long, std::array<double, 3>> nodes;     // node tag -> coordinates
  std::vector<VolumeElement> volumes;
  std::vector<SurfaceElement> surfaces;
};

/// Whitespace-separated tokens of the file. Every read names what it expected, so that a
/// truncated file or a stray word is reported with its line and section.
class Tokens {
 public:
  Tokens(std::string_view text, std::string source) : text_(text), source_(std::move(source)) {}

  /// Skips white space; false at the end of the text.
  bool more() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
    return pos_ < text_.size();
  }

  std::string_view word(const std::string& what) {
    if (!more()) fail("the file ends where " + what + " should be (truncated?)");
    const size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return text_.substr(start, pos_ - start);
  }

  long long integer(const std::string& what, long long min = LLONG_MIN, long long max = LLONG_MAX) {
    const auto token = word(what);
    long long value = 0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error == std::errc::result_out_of_range) fail(what + " \"" + shorten(token) + "\" is out of range");
    if (error != std::errc() || end != token.data() + token.size())
      fail(what + " must be an integer, not \"" + shorten(token) + "\"");
    if (value < min || value > max)
      fail(what + " is " + std::to_string(value) + ", outside " + std::to_string(min) + ".." + std::to_string(max));
    return value;
  }

  int smallInteger(const std::string& what, int min = INT_MIN, int max = INT_MAX) {
    return static_cast<int>(integer(what, min, max));
  }

  /// A count of items that take at least `tokensPerItem` tokens each: it cannot exceed what
  /// the rest of the file holds (every token is at least one character and one separator),
  /// which also bounds every allocation made from it.
  long long count(const std::string& what, int tokensPerItem) {
    const long long count = integer(what, 0);
    const long long room = static_cast<long long>((text_.size() - pos_) / 2 + 1) / tokensPerItem;
    if (count > room)
      fail(what + " is " + std::to_string(count) + ", more than the rest of the file can hold (at most " +
           std::to_string(room) + "): a corrupt count or a truncated file");
    return count;
  }

  double number(const std::string& what) {
    const auto token = word(what);
    double value = 0.0;
    const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error == std::errc::result_out_of_range) fail(what + " \"" + shorten(token) + "\" is out of range");
    if (error != std::errc() || end != token.data() + token.size())
      fail(what + " must be a number, not \"" + shorten(token) + "\"");
    return value;
  }

  /// A name in double quotes on the current line ("plate bottom").
  std::string quoted(const std::string& what) {
    const auto token = word(what);
    if (token.front() != '"') fail(what + " must be in double quotes, not " + shorten(token));
    const size_t open = pos_ - token.size();
    const size_t close = text_.find('"', open + 1);
    const size_t endOfLine = text_.find('\n', open);
    if (close == std::string_view::npos || close > endOfLine) fail(what + " has no closing double quote");
    pos_ = close + 1;
    return std::string(text_.substr(open + 1, close - open - 1));
  }

  void enter(std::string_view section) { section_ = std::string(section); }

  /// The section's closing keyword, "$End<name>".
  void leave() {
    const std::string end = "$End" + section_.substr(1);
    const auto token = word(end);
    if (token != end) fail("expected " + end + ", found \"" + shorten(token) + "\" (a count does not match the data?)");
    section_.clear();
  }

  /// Sections Tribos does not use ($Comments, $Periodic, $NodeData, ...) up to their end.
  void skipSection() {
    const std::string end = "$End" + section_.substr(1);
    while (word(end + " to close the section") != end) {
    }
    section_.clear();
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw core::InputError(source_ + ": line " + std::to_string(line_) +
                           (section_.empty() ? std::string() : " (" + section_ + ")") + ": " + what);
  }

 private:
  static std::string shorten(std::string_view token) {
    return token.size() <= 40 ? std::string(token) : std::string(token.substr(0, 40)) + "...";
  }

  std::string_view text_;
  std::string source_;
  size_t pos_ = 0;
  int line_ = 1;
  std::string section_;
};

void readFormat(Tokens& in) {
  const double version = in.number("the format version");
  const int fileType = in.smallInteger("the file type");
  in.integer("the data size");
  if (version < 4.0 || version >= 5.0 || fileType != 0)
    in.fail("only gmsh 4.x ASCII meshes are read (gmsh -format msh41); this file is version " +
            core::formatNumber(version) + (fileType != 0 ? " binary" : ""));
  in.leave();
}

void readPhysicalNames(Tokens& in, GmshContent& content) {
  const long long count = in.count("the number of physical names", 3);
  for (long long i = 0; i < count; ++i) {
    const int dim = in.smallInteger("a physical group's dimension", 0, 3);
    const int tag = in.smallInteger("a physical group's tag");
    content.physicalName[{dim, tag}] = in.quoted("the name of physical group " + std::to_string(tag));
  }
  in.leave();
}

void readEntities(Tokens& in, GmshContent& content) {
  long long counts[4];
  for (int dim = 0; dim < 4; ++dim) counts[dim] = in.count("the number of entities of dimension " + std::to_string(dim), 5);
  for (int dim = 0; dim < 4; ++dim)
    for (long long e = 0; e < counts[dim]; ++e) {
      const int tag = in.smallInteger("an entity tag");
      const std::string entity = "entity " + std::to_string(tag) + " (dimension " + std::to_string(dim) + ")";
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) in.number("a bounding-box coordinate of " + entity);
      std::vector<int> physical(in.count("the number of physical tags of " + entity, 1));
      for (int& p : physical) p = in.smallInteger("a physical tag of " + entity);
      content.entityPhysical[{dim, tag}] = std::move(physical);
      if (dim == 0) continue;
      const long long bounding = in.count("the number of bounding entities of " + entity, 1);
      for (long long k = 0; k < bounding; ++k) in.integer("a bounding entity of " + entity);
    }
  in.leave();
}

void readNodes(Tokens& in, GmshContent& content) {
  const long long blocks = in.count("the number of node blocks", 4);
  const long long total = in.count("the number of nodes", 4);
  if (total > INT_MAX) in.fail("more nodes than Tribos can index (" + std::to_string(total) + ")");
  in.integer("the smallest node tag");
  in.integer("the largest node tag");
  content.nodes.reserve(static_cast<size_t>(total));
  long long seen = 0;
  for (long long b = 0; b < blocks; ++b) {
    in.smallInteger("a node block's entity dimension", 0, 3);
    in.smallInteger("a node block's entity tag");
    if (in.smallInteger("the parametric flag", 0, 1) != 0) in.fail("parametric node coordinates are not supported");
    const long long inBlock = in.count("the number of nodes in a block", 4);
    if (inBlock > total - seen)
      in.fail("the node blocks hold more nodes than the section header says (" + std::to_string(total) + ")");
    std::vector<long long> tags(static_cast<size_t>(inBlock));
    for (auto& t : tags) t = in.integer("a node tag", 1);
    for (long long t : tags) {
      const std::string node = "node " + std::to_string(t);
      std::array<double, 3> x;
      for (int c = 0; c < 3; ++c) {
        x[c] = in.number(std::string("the ") + "xyz"[c] + " coordinate of " + node);
        if (!std::isfinite(x[c])) in.fail("the " + std::string(1, "xyz"[c]) + " coordinate of " + node + " is not finite");
      }
      if (!content.nodes.emplace(t, x).second) in.fail(node + " is defined twice");
    }
    seen += inBlock;
  }
  if (seen != total)
    in.fail("the node blocks hold " + std::to_string(seen) + " nodes but the section header says " +
            std::to_string(total));
  in.leave();
}

/// The gmsh element types Tribos reads (gmsh's "MSH file format" numbering).
struct GmshType {
  int type;
  int dim;
  int nodes;
  const char* name;
};
/// Points, lines and faces; the volume types are the element catalogue's (ElementShape::gmshType).
constexpr GmshType kLowerDimensionTypes[] = {
    {15, 0, 1, "point"},          {1, 1, 2, "2-node line"},     {8, 1, 3, "3-node line"},
    {2, 2, 3, "3-node triangle"}, {9, 2, 6, "6-node triangle"}, {3, 2, 4, "4-node quadrilateral"}};

const GmshType* gmshType(int type) {
  static const std::vector<GmshType> kReadTypes = [] {
    std::vector<GmshType> all(std::begin(kLowerDimensionTypes), std::end(kLowerDimensionTypes));
    for (int t = 0; t < kNumElementTypes; ++t) {
      const ElementShape& shape = elementShape(static_cast<ElementType>(t));
      all.push_back({shape.gmshType, 3, shape.numNodes, shape.description});
    }
    return all;
  }();
  for (const auto& t : kReadTypes)
    if (t.type == type) return &t;
  return nullptr;
}

/// What to do instead, for the volume types (and their faces) gmsh makes that Tribos does not take.
std::string refusedVolumeAdvice(int type) {
  switch (type) {
    case 12:
    case 17:
      return " (a 27- or 20-node hexahedron: mesh with Mesh.ElementOrder = 1 for 8-node hexahedra, or with "
             "tetrahedra and Mesh.ElementOrder = 2 for 10-node tetrahedra)";
    case 13:
    case 18: return " (a quadratic prism: mesh with Mesh.ElementOrder = 1 for 6-node prisms)";
    case 7:
    case 14:
    case 19: return " (a pyramid: mesh without Mesh.Recombine3DAll, or with tetrahedra only)";
    case 29: return " (a 20-node tetrahedron: use Mesh.ElementOrder = 2 for 10-node tetrahedra)";
    case 10:
    case 16:
      return " (the face of a 27- or 20-node hexahedron or a quadratic prism: mesh with Mesh.ElementOrder = 1 for "
             "8-node hexahedra and 6-node prisms, or with tetrahedra and Mesh.ElementOrder = 2 for 10-node tetrahedra)";
    default: return "";
  }
}

void checkElementBlockType(Tokens& in, int dim, int entity, int type) {
  const std::string where = "entity " + std::to_string(entity) + " (dimension " + std::to_string(dim) + ")";
  const GmshType* known = gmshType(type);
  if (dim == 3 && (known == nullptr || known->dim != 3))
    in.fail("volume " + where + " has elements of gmsh type " + std::to_string(type) + refusedVolumeAdvice(type) +
            "; Tribos takes 4-node tetrahedra (type 4), 10-node tetrahedra (11), 8-node hexahedra (5) and 6-node "
            "prisms (6)");
  if (known == nullptr)
    in.fail(where + " has elements of gmsh type " + std::to_string(type) + refusedVolumeAdvice(type) +
            ", which Tribos does not read (points, lines, 3- and 6-node triangles, 4-node quadrilaterals and the "
            "volume types 4, 11, 5 and 6 only)");
  if (known->dim != dim)
    in.fail(where + " holds elements of gmsh type " + std::to_string(type) + ", which do not have its dimension");
}

/// A volume element of gmsh type `gmshType` (one the catalogue has: checked by the caller) with
/// its nodes in Exodus order (ElementShape::gmshNode).
VolumeElement volumeElement(int gmshType, const std::array<long long, kMaxElementNodes>& v, int group, long long tag) {
  VolumeElement e{v, ElementType::Tet4, group, tag};
  elementTypeOfGmsh(gmshType, e.type);
  const ElementShape& shape = elementShape(e.type);
  for (int k = 0; k < shape.numNodes; ++k) e.nodes[k] = v[shape.gmshNode[k]];
  return e;
}

void readElements(Tokens& in, GmshContent& content) {
  const long long blocks = in.count("the number of element blocks", 4);
  const long long total = in.count("the number of elements", 2);
  in.integer("the smallest element tag");
  in.integer("the largest element tag");
  long long seen = 0;
  for (long long b = 0; b < blocks; ++b) {
    const int dim = in.smallInteger("an element block's entity dimension", 0, 3);
    const int entity = in.smallInteger("an element block's entity tag");
    const int type = in.smallInteger("an element type");
    checkElementBlockType(in, dim, entity, type);
    const GmshType& kind = *gmshType(type);
    const int perElement = kind.nodes;
    const long long inBlock = in.count("the number of elements in a block", 1 + perElement);
    if (inBlock > total - seen)
      in.fail("the element blocks hold more elements than the section header says (" + std::to_string(total) + ")");
    const auto physical = content.entityPhysical.find({dim, entity});
    const int group = physical == content.entityPhysical.end() || physical->second.empty() ? 0 : physical->second.front();
    for (long long e = 0; e < inBlock; ++e) {
      const long long tag = in.integer("an element tag", 1);
      std::array<long long, kMaxElementNodes> v{};
      for (int k = 0; k < perElement; ++k) v[k] = in.integer("a node tag of element " + std::to_string(tag), 1);
      if (kind.dim == 3) content.volumes.push_back(volumeElement(type, v, group, tag));
      if (kind.dim == 2) {
        SurfaceElement face{{}, type == 3 ? 4 : 3, {}, tag};
        std::copy_n(v.begin(), perElement, face.nodes.begin());
        if (physical != content.entityPhysical.end()) face.physicals = physical->second;
        content.surfaces.push_back(std::move(face));
      }
    }
    seen += inBlock;
  }
  if (seen != total)
    in.fail("the element blocks hold " + std::to_string(seen) + " elements but the section header says " +
            std::to_string(total));
  if (content.volumes.size() > static_cast<size_t>(INT_MAX)) in.fail("more volume elements than Tribos can index");
  in.leave();
}

/// The sections, in any order after $MeshFormat; unknown ones are skipped.
GmshContent readSections(std::string_view text, const std::string& source) {
  Tokens in(text, source);
  GmshContent content;
  bool sawFormat = false, sawNodes = false, sawElements = false;
  while (in.more()) {
    const auto section = in.word("a section");
    if (section.empty() || section.front() != '$' || section.rfind("$End", 0) == 0)
      in.fail(sawFormat ? "\"" + std::string(section.substr(0, 40)) + "\" outside a section (a count does not match the data?)"
                        : "not a gmsh mesh ($MeshFormat missing)");
    in.enter(section);
    if (section == "$MeshFormat") {
      readFormat(in);
      sawFormat = true;
      continue;
    }
    if (!sawFormat) in.fail("not a gmsh mesh ($MeshFormat missing)");
    if (section == "$PhysicalNames") {
      readPhysicalNames(in, content);
    } else if (section == "$Entities") {
      readEntities(in, content);
    } else if (section == "$Nodes") {
      readNodes(in, content);
      sawNodes = true;
    } else if (section == "$Elements") {
      readElements(in, content);
      sawElements = true;
    } else {
      in.skipSection();
    }
  }
  if (!sawFormat) in.fail("not a gmsh mesh ($MeshFormat missing)");
  if (!sawNodes || !sawElements) in.fail(std::string("the file has no ") + (sawNodes ? "$Elements" : "$Nodes") + " section");
  if (content.volumes.empty()) in.fail("no volume elements (mesh in 3D with a Physical Volume)");
  return content;
}

std::string volumeName(const GmshContent& content, int physical) {
  const auto it = content.physicalName.find({3, physical});
  return it != content.physicalName.end() ? it->second : "volume_" + std::to_string(physical);
}

std::string surfaceName(const GmshContent& content, int physical) {
  const auto it = content.physicalName.find({2, physical});
  return it != content.physicalName.end() ? it->second : "surface_" + std::to_string(physical);
}

/// The sorted gmsh node tags of a face's vertices; a triangle's fourth is -1.
using FaceKey = std::array<long long, 4>;

FaceKey faceKey(const long long* vertices, int numVertices) {
  FaceKey key{-1, -1, -1, -1};
  std::copy_n(vertices, numVertices, key.begin());
  std::sort(key.begin(), key.begin() + numVertices);
  return key;
}

/// Reverses the orientation of an element (its mirror image, ElementShape::mirrorNode): for
/// elements from writers with the other orientation convention.
void reorient(ElementType type, long long* nodes) {
  const ElementShape& shape = elementShape(type);
  long long original[kMaxElementNodes];
  std::copy_n(nodes, shape.numNodes, original);
  for (int k = 0; k < shape.numNodes; ++k) nodes[k] = original[shape.mirrorNode[k]];
}

/// Builds the Mesh: bodies in the order of their physical tags, elements sorted by body (so
/// blocks are contiguous), nodes numbered in order of first use, one per (node, body) when
/// the bodies are split.
class MeshBuilder {
 public:
  MeshBuilder(GmshContent& content, const std::string& source, bool splitBodies)
      : content_(content), source_(source), split_(splitBodies) {}

  Mesh build() {
    // By body, and within a body by type, so that each type is one Exodus block on output.
    std::stable_sort(content_.volumes.begin(), content_.volumes.end(), [](const VolumeElement& a, const VolumeElement& b) {
      return a.physical != b.physical ? a.physical < b.physical : a.type < b.type;
    });
    for (size_t e = 0; e < content_.volumes.size(); ++e) addVolume(static_cast<LO>(e));
    addSurfaces();
    mesh_.file = source_;
    mesh_.validate(source_);
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw core::InputError(source_ + ": " + what); }

  LO nodeId(long long gmshNode, int body, const std::string& user) {
    const auto it = content_.nodes.find(gmshNode);
    if (it == content_.nodes.end())
      fail(user + " references node " + std::to_string(gmshNode) + ", which $Nodes does not define");
    const auto key = std::make_pair(gmshNode, split_ ? body : 0);
    const auto [pos, inserted] = nodeIds_.insert({key, static_cast<LO>(mesh_.coords.size())});
    if (inserted) mesh_.coords.push_back(it->second);
    return pos->second;
  }

  void addVolume(LO e) {
    VolumeElement& volume = content_.volumes[e];
    const std::string name = volumeName(content_, volume.physical);
    if (blockOfBody_.count(volume.physical) == 0) {  // elements are sorted by body: a new block
      for (const auto& block : mesh_.blocks)  // Exodus joins blocks of one name into one body
        if (block.name == name)
          fail("Physical Volumes " + std::to_string(block.id) + " and " + std::to_string(volume.physical) +
               " are both named \"" + name + "\"; give each body its own name");
      blockOfBody_[volume.physical] = mesh_.numBlocks();
      mesh_.blocks.push_back({name, volume.physical > 0 ? volume.physical : mesh_.numBlocks() + 1, e, 0});
    }
    mesh_.blocks.back().count++;
    const std::string element = "element " + std::to_string(volume.tag) + " of Physical Volume \"" + name + "\"";
    const ElementShape& shape = elementShape(volume.type);
    LO nodes[kMaxElementNodes];
    for (int v = 0; v < shape.numNodes; ++v) nodes[v] = nodeId(volume.nodes[v], volume.physical, element);
    mesh_.elements.add(volume.type, nodes);
    mesh_.elementNumbers.push_back(volume.tag);  // messages from Mesh::validate name gmsh's tags
    const double size = mesh_.elementVolume(e), edge = mesh_.longestEdge(e);
    if (!(std::abs(size) > kDegenerateVolumeRatio * edge * edge * edge))
      fail(element + " is degenerate (volume " + core::formatNumber(size) + " for a longest edge of " +
           core::formatNumber(edge) + ")");
    if (size < 0.0) {  // the other orientation convention: reorder
      reorient(volume.type, volume.nodes.data());
      LO* stored = mesh_.elements.mutableNodes(e);
      for (int v = 0; v < shape.numNodes; ++v) stored[v] = nodeId(volume.nodes[v], volume.physical, element);
    }
    for (int side = 0; side < shape.numFaces; ++side) {
      const FaceShape& face = shape.faces[side];
      long long vertices[4];
      for (int k = 0; k < face.numVertices; ++k) vertices[k] = volume.nodes[face.nodes[k]];
      faces_[faceKey(vertices, face.numVertices)].push_back({e, side});
    }
  }

  /// Side sets (and node sets of the same name) from the physical surfaces: every group of a
  /// surface, also where several name the same faces. A group on the faces of several bodies
  /// (an interface, or faces of separate bodies) gives one set per body, <group>_<body>, and
  /// the whole group as well, <group>.
  void addSurfaces() {
    std::map<int, std::map<int, SideSet>> sets;  // surface tag -> body -> set
    for (const auto& face : content_.surfaces)
      for (int group : face.physicals)
        if (group != 0) addSurfaceElement(face, group, sets);
    int id = 1;
    for (auto& [surface, byBody] : sets) {
      const std::string base = surfaceName(content_, surface);
      SideSet whole{base, 0, {}, {}};
      for (auto& [body, set] : byBody) {
        set.name = byBody.size() > 1 ? base + "_" + mesh_.blocks[blockOfBody_[body]].name : base;
        addSideAndNodeSet(set, id++);
        whole.elements.insert(whole.elements.end(), set.elements.begin(), set.elements.end());
        whole.sides.insert(whole.sides.end(), set.sides.begin(), set.sides.end());
      }
      if (byBody.size() > 1) addSideAndNodeSet(whole, id++);
    }
  }

  /// The faces of one surface element of physical group `group`, in the set of each body it
  /// bounds.
  void addSurfaceElement(const SurfaceElement& face, int group, std::map<int, std::map<int, SideSet>>& sets) {
    const std::string text = std::string(face.numVertices == 4 ? "quadrilateral " : "triangle ") +
                             std::to_string(face.tag) + " of Physical Surface \"" + surfaceName(content_, group) + "\"";
    for (int k = 0; k < face.numVertices; ++k)
      if (!content_.nodes.count(face.nodes[k]))
        fail(text + " references node " + std::to_string(face.nodes[k]) + ", which $Nodes does not define");
    const auto it = faces_.find(faceKey(face.nodes.data(), face.numVertices));
    if (it == faces_.end()) fail(text + " is not a face of any volume element");
    for (const auto& [element, side] : it->second) {
      auto& set = sets[group][content_.volumes[element].physical];
      set.elements.push_back(element);
      set.sides.push_back(side);
    }
  }

  /// `set` with id `id`, and the node set of its faces' nodes under the same name and id.
  void addSideAndNodeSet(SideSet set, int id) {
    set.id = id;
    NodeSet nodes{set.name, id, {}};
    for (size_t f = 0; f < set.elements.size(); ++f)
      for (LO n : mesh_.faceNodes(set.elements[f], set.sides[f])) nodes.nodes.push_back(n);
    std::sort(nodes.nodes.begin(), nodes.nodes.end());
    nodes.nodes.erase(std::unique(nodes.nodes.begin(), nodes.nodes.end()), nodes.nodes.end());
    mesh_.sideSets.push_back(std::move(set));
    mesh_.nodeSets.push_back(std::move(nodes));
  }

  GmshContent& content_;
  const std::string& source_;
  const bool split_;
  Mesh mesh_;
  std::map<std::pair<long long, int>, LO> nodeIds_;  // (gmsh node, body or 0) -> node
  std::map<int, int> blockOfBody_;                    // physical tag -> block index
  std::map<FaceKey, std::vector<std::pair<LO, int>>> faces_;  // -> (element, side)
};
}  // namespace

Mesh parseGmsh(std::string_view text, const std::string& source, bool splitBodies) {
  GmshContent content = readSections(text, source);
  return MeshBuilder(content, source, splitBodies).build();
}

Mesh readGmsh(const std::string& path, bool splitBodies) {
  core::requireRegularInputFile(path, "the gmsh file");  // a FIFO or a device: never opened
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::InputError(path + ": cannot open the gmsh file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw core::InputError(path + ": reading the gmsh file failed");
  return parseGmsh(text.str(), path, splitBodies);
}

}  // namespace tribos::mesh
