#include <metis.h>

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "tribos/core/Errors.hpp"
#include "tribos/mesh/Decomposition.hpp"

namespace tribos::mesh {

namespace {
// Called on the main thread only (METIS keeps global random state; see CholmodCholesky.cpp).
// Parts per body in proportion to its element count (largest remainder, at least one each).
std::vector<int> shareParts(const Mesh& mesh, int numParts) {
  const int nb = mesh.numBlocks();
  std::vector<int> share(nb, 1);
  const double total = mesh.numElements();
  std::vector<std::pair<double, int>> remainder;
  int given = nb;
  for (int b = 0; b < nb; ++b) {
    const double exact = numParts * mesh.blocks[b].count / total;
    const int extra = std::max(0, static_cast<int>(exact) - 1);
    share[b] += extra;
    given += extra;
    remainder.push_back({exact - share[b], b});
  }
  std::sort(remainder.begin(), remainder.end(), [](auto a, auto b) { return a.first > b.first; });
  for (size_t i = 0; given < numParts; i = (i + 1) % remainder.size(), ++given) share[remainder[i].second]++;
  return share;
}
}  // namespace

std::vector<int> metisPartition(const Mesh& mesh, int numParts) {
  const int nb = mesh.numBlocks();
  core::requireInput(numParts >= nb, "Mesh/Subdomains: " + std::to_string(numParts) + " is fewer than the " +
                                         std::to_string(nb) + " bodies (element blocks); a subdomain cannot span two");
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
    // The block's own node numbering (METIS wants 0..nn-1).
    std::vector<LO> nodes;
    for (LO e = block.first; e < block.first + block.count; ++e) nodes.insert(nodes.end(), mesh.tets[e].begin(), mesh.tets[e].end());
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    std::vector<idx_t> eptr(block.count + 1), eind(4 * static_cast<size_t>(block.count));
    for (LO i = 0; i < block.count; ++i) {
      eptr[i] = 4 * i;
      for (int v = 0; v < 4; ++v)
        eind[4 * i + v] = static_cast<idx_t>(std::lower_bound(nodes.begin(), nodes.end(), mesh.tets[block.first + i][v]) - nodes.begin());
    }
    eptr[block.count] = 4 * block.count;
    idx_t ne = block.count, nn = static_cast<idx_t>(nodes.size()), ncommon = 3, nparts = share[b], objval = 0;
    std::vector<idx_t> epart(block.count), npart(nodes.size());
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_NUMBERING] = 0;
    options[METIS_OPTION_CONTIG] = 1;  // connected subdomains where the body allows
    int status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts, nullptr,
                                    options, &objval, epart.data(), npart.data());
    if (status != METIS_OK) {  // e.g. a body made of disconnected pieces: drop contiguity
      options[METIS_OPTION_CONTIG] = 0;
      status = METIS_PartMeshDual(&ne, &nn, eptr.data(), eind.data(), nullptr, nullptr, &ncommon, &nparts, nullptr,
                                  options, &objval, epart.data(), npart.data());
    }
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
