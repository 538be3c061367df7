#include "tribos/mesh/Decomposition.hpp"

#include <algorithm>

#include "tribos/core/Errors.hpp"

namespace tribos::mesh {

long long Decomposition::numPrimalDofs() const {
  long long n = 0;
  for (const auto& s : subdomains) n += s.numDofs();
  return n;
}

Decomposition buildDecomposition(const Mesh& mesh, const std::vector<int>& elementPart) {
  if (static_cast<LO>(elementPart.size()) != mesh.numElements())
    throw core::InputError("decomposition: " + std::to_string(elementPart.size()) + " part ids for " +
                           std::to_string(mesh.numElements()) + " elements");
  int numParts = 0;
  for (LO e = 0; e < mesh.numElements(); ++e) {
    if (elementPart[e] < 0)
      throw core::InputError("decomposition: element " + std::to_string(e + 1) + " has negative part " +
                             std::to_string(elementPart[e]));
    numParts = std::max(numParts, elementPart[e] + 1);
  }
  Decomposition d;
  d.elementPart = elementPart;
  d.subdomains.resize(numParts);
  for (auto& s : d.subdomains) s.body = -1;
  // Elements in ascending order per part, and the body of each part (one block only: a
  // subdomain never spans two bodies).
  for (int b = 0; b < mesh.numBlocks(); ++b)
    for (LO e = mesh.blocks[b].first; e < mesh.blocks[b].first + mesh.blocks[b].count; ++e) {
      Subdomain& s = d.subdomains[elementPart[e]];
      if (s.body >= 0 && s.body != b)
        throw core::InputError("decomposition: subdomain " + std::to_string(elementPart[e]) +
                               " spans element blocks \"" + mesh.blocks[s.body].name + "\" and \"" +
                               mesh.blocks[b].name + "\"; a subdomain must lie in one body");
      s.body = b;
      s.elements.push_back(e);
    }
  // Local nodes: ascending global ids; local connectivity by binary search.
  for (int p = 0; p < numParts; ++p) {
    Subdomain& s = d.subdomains[p];
    if (s.elements.empty())
      throw core::InputError("decomposition: subdomain " + std::to_string(p) + " has no elements");
    s.nodes.reserve(4 * s.elements.size());
    for (LO e : s.elements)
      for (LO n : mesh.elementNodes(e)) s.nodes.push_back(n);
    std::sort(s.nodes.begin(), s.nodes.end());
    s.nodes.erase(std::unique(s.nodes.begin(), s.nodes.end()), s.nodes.end());
    s.localElements.reserve(s.elements.size(), 4);
    for (LO e : s.elements) {
      LO local[kMaxElementNodes];
      const ElementNodes global = mesh.elementNodes(e);
      for (int v = 0; v < global.size(); ++v)
        local[v] = static_cast<LO>(std::lower_bound(s.nodes.begin(), s.nodes.end(), global[v]) - s.nodes.begin());
      s.localElements.add(mesh.elementType(e), local);
    }
  }
  return d;
}

int firstSubdomain(int rank, int numSubdomains, int numRanks) {
  return static_cast<int>(static_cast<long long>(rank) * numSubdomains / numRanks);
}

int ownerRank(int s, int numSubdomains, int numRanks) {
  // The largest rank r with firstSubdomain(r) <= s.
  int r = static_cast<int>((static_cast<long long>(s) * numRanks) / numSubdomains);
  while (r + 1 < numRanks && firstSubdomain(r + 1, numSubdomains, numRanks) <= s) ++r;
  while (r > 0 && firstSubdomain(r, numSubdomains, numRanks) > s) --r;
  return r;
}

}  // namespace tribos::mesh
