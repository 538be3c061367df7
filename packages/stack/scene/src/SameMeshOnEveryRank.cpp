#include "tribos/stack/SameMeshOnEveryRank.hpp"

#include <array>
#include <vector>

#include "tribos/core/Errors.hpp"
#include "tribos/core/RankErrors.hpp"
#include "tribos/mesh/ExodusIO.hpp"

namespace tribos::stack {

namespace {
class Fnv1a {
 public:
  void add(const void* data, size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < bytes; ++i) hash_ = (hash_ ^ p[i]) * 0x100000001b3ULL;
  }
  template <class T>
  void addVector(const std::vector<T>& v) {
    addValue(v.size());
    if (!v.empty()) add(v.data(), v.size() * sizeof(T));
  }
  template <class T>
  void addValue(const T& x) {
    add(&x, sizeof x);
  }
  void addText(const std::string& s) {
    addValue(s.size());
    add(s.data(), s.size());
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};
}  // namespace

std::uint64_t meshChecksum(const mesh::Mesh& mesh) {
  Fnv1a h;
  h.addVector(mesh.coords);
  h.addVector(mesh.elements.types());
  h.addVector(mesh.elements.offsets());
  h.addVector(mesh.elements.flatNodes());
  h.addVector(mesh.elementNumbers);
  for (const auto& b : mesh.blocks) {
    h.addText(b.name);
    h.addValue(b.id);
    h.addValue(b.first);
    h.addValue(b.count);
  }
  for (const auto& s : mesh.nodeSets) {
    h.addText(s.name);
    h.addValue(s.id);
    h.addVector(s.nodes);
  }
  for (const auto& s : mesh.sideSets) {
    h.addText(s.name);
    h.addValue(s.id);
    h.addVector(s.elements);
    h.addVector(s.sides);
  }
  return h.value();
}

void requireSameMeshOnEveryRank(const mesh::Mesh& mesh, const std::string& file, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const std::array<unsigned long long, 3> mine = {meshChecksum(mesh), static_cast<unsigned long long>(mesh.numNodes()),
                                                  static_cast<unsigned long long>(mesh.numElements())};
  std::vector<unsigned long long> all(3 * static_cast<size_t>(size));
  MPI_Allgather(mine.data(), 3, MPI_UNSIGNED_LONG_LONG, all.data(), 3, MPI_UNSIGNED_LONG_LONG, comm);
  bool same = true;
  for (int r = 1; r < size; ++r) same = same && all[3 * r] == all[0];
  if (same) return;
  std::string what;
  for (int r = 0; r < size; ++r)
    what += (r ? "; " : "") + std::string("rank ") + std::to_string(r) + ": " + std::to_string(all[3 * r + 1]) +
            " nodes, " + std::to_string(all[3 * r + 2]) + " elements";
  throw core::InputError(file + ": the ranks read different meshes (" + what +
                         "): was the file replaced while the job started? Run again once it is complete");
}

mesh::Mesh readMeshOnEveryRank(const std::string& file, MPI_Comm comm) {
  mesh::Mesh mesh;
  core::onEveryRankOrNone([&] { mesh = mesh::readExodus(file).mesh; }, file + ": another rank could not read it",
                          comm);
  requireSameMeshOnEveryRank(mesh, file, comm);
  return mesh;
}

}  // namespace tribos::stack
