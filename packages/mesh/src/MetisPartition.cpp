#include <metis.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/MeshFaces.hpp"

namespace tribos::mesh {

namespace {
// Called on the main thread only (METIS keeps global random state; see CholmodCholesky.cpp).
// Parts per body in proportion to its element count: Hamilton's largest-remainder rounding
// of the quotas q_b = numParts * count_b / total, then every body that rounded to 0 takes
// one part from the body that exceeds its quota the most (numParts >= number of bodies, so
// there always is a donor with 2 or more). The shares sum to numParts exactly.
std::vector<int> shareParts(const Mesh& mesh, int numParts) {
  // Exact integer arithmetic (q_b = P c_b / N as share + remainder / N), so that round-off
  // can never make the floors sum past numParts.
  const int nb = mesh.numBlocks();
  const long long total = mesh.numElements();
  std::vector<long long> scaled(nb);  // P * c_b = N * q_b
  std::vector<int> share(nb);
  int given = 0;
  for (int b = 0; b < nb; ++b) {
    scaled[b] = static_cast<long long>(numParts) * mesh.blocks[b].count;
    share[b] = static_cast<int>(scaled[b] / total);
    given += share[b];
  }
  // N * (share - q): how far a body's share exceeds its quota.
  auto excess = [&](int b) { return share[b] * total - scaled[b]; };
  std::vector<int> order(nb);
  std::iota(order.begin(), order.end(), 0);
  // Largest remainder first; ties go to the lower body index (stable), so it is deterministic.
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return excess(a) < excess(b); });
  for (int i = 0; given < numParts; ++i, ++given) share[order[i]]++;  // fewer than nb to give
  for (int b = 0; b < nb; ++b) {
    if (share[b] > 0) continue;
    int donor = -1;
    for (int d = 0; d < nb; ++d)
      if (share[d] > 1 && (donor < 0 || excess(d) > excess(donor))) donor = d;
    share[donor]--;
    share[b] = 1;
  }
  return share;
}
}  // namespace

std::vector<int> metisPartition(const Mesh& mesh, int numParts) {
  const int nb = mesh.numBlocks();
  core::requireInput(numParts >= nb, "Mesh/Subdomains: " + std::to_string(numParts) + " is fewer than the " +
                                         std::to_string(nb) + " bodies (element blocks); a subdomain cannot span two");
  // A body in several pieces has no contiguous partition (METIS would print "A contiguous
  // partition is requested for a non-contiguous input graph") and a subdomain spanning two
  // pieces has 12 rigid motions, not 6: an input error naming the block, before METIS.
  requireConnectedBlocks(mesh, mesh.file.empty() ? "mesh" : mesh.file);
  const auto share = shareParts(mesh, numParts);
  std::vector<int> part(mesh.numElements(), 0);
  int offset = 0;
  for (int b = 0; b < nb; ++b) {
    const ElementBlock& block = mesh.blocks[b];
    core::requireInput(share[b] <= block.count, "Mesh/Subdomains: " + std::to_string(numParts) +
                                                    " parts give element block \"" + block.name + "\" " +
                                                    std::to_string(share[b]) + " parts for only " +
                                                    std::to_string(block.count) + " elements");
    if (share[b] == 1) {
      std::fill(part.begin() + block.first, part.begin() + block.first + block.count, offset);
      offset += 1;
      continue;
    }
    // The block's own numbering of the element vertices (METIS wants 0..nn-1). Mid-edge
    // nodes are left out: two quadratic tetrahedra sharing an edge share three nodes, as
    // face neighbours (ncommon = 3) do.
    const auto vertices = [&](LO e) {
      const ElementNodes all = mesh.elementNodes(e);
      return ElementNodes{all.first, elementShape(mesh.elementType(e)).numVertices};
    };
    std::vector<LO> nodes;
    for (LO e = block.first; e < block.first + block.count; ++e)
      nodes.insert(nodes.end(), vertices(e).begin(), vertices(e).end());
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    std::vector<idx_t> eptr(block.count + 1, 0), eind;
    eind.reserve(4 * static_cast<size_t>(block.count));
    for (LO i = 0; i < block.count; ++i) {
      for (LO n : vertices(block.first + i))
        eind.push_back(static_cast<idx_t>(std::lower_bound(nodes.begin(), nodes.end(), n) - nodes.begin()));
      eptr[i + 1] = static_cast<idx_t>(eind.size());
    }
    idx_t ne = block.count, nn = static_cast<idx_t>(nodes.size()), ncommon = 3, nparts = share[b], objval = 0;
    std::vector<idx_t> epart(block.count), npart(nodes.size());
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    options[METIS_OPTION_CONTIG] = 1;  // connected subdomains: each has exactly 6 rigid motions
    const int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts,
                                          nullptr, options, &objval, epart.data(), npart.data());
    if (status != METIS_OK)
      throw std::runtime_error("METIS_PartMeshDual failed (status " + std::to_string(status) + ") on element block \"" +
                               block.name + "\"");
    // METIS may leave a part empty on tiny or odd meshes: renumber the non-empty parts.
    std::vector<int> used(share[b], -1);
    int next = 0;
    for (LO i = 0; i < block.count; ++i) {
      if (used[epart[i]] < 0) used[epart[i]] = next++;
      part[block.first + i] = offset + used[epart[i]];
    }
    offset += next;
  }
  return part;
}

}  // namespace tribos::mesh
