#include "tribos/stack/SubdomainCount.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tribos::stack {

SubdomainCount chooseSubdomainCount(int requested, int corners, int nodes, int bodies, int nodesPerSubdomain,
                                    int ranks) {
  if (requested > 0) return {requested, ""};
  const int bySize = static_cast<int>(std::lround(static_cast<double>(corners) / std::max(1, nodesPerSubdomain)));
  const int count = std::max({bySize, bodies, ranks, 1});
  const std::string counted = corners == nodes ? std::to_string(nodes) + " nodes"
                                               : std::to_string(corners) + " corner nodes (of " +
                                                     std::to_string(nodes) + ")";
  std::string reason = "from the mesh: " + counted + " / Mesh/Nodes Per Subdomain " + std::to_string(nodesPerSubdomain);
  if (count == ranks && ranks > std::max(bySize, bodies)) reason += ", raised to one per rank";
  else if (count == bodies && bodies > bySize) reason += ", raised to one per body";
  return {count, reason};
}

int cornerNodeCount(const mesh::Mesh& mesh) {
  std::vector<char> corner(mesh.numNodes(), 0);
  for (LO e = 0; e < mesh.numElements(); ++e) {
    const mesh::ElementNodes nodes = mesh.elementNodes(e);
    const int vertices = mesh::elementShape(mesh.elements.type(e)).numVertices;
    for (int v = 0; v < vertices; ++v) corner[nodes[v]] = 1;
  }
  return static_cast<int>(std::count(corner.begin(), corner.end(), 1));
}

}  // namespace tribos::stack
