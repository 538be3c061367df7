#include "tribos/stack/SubdomainCount.hpp"

#include <algorithm>
#include <cmath>

namespace tribos::stack {

SubdomainCount chooseSubdomainCount(int requested, int nodes, int bodies, int nodesPerSubdomain, int ranks) {
  if (requested > 0) return {requested, ""};
  const int bySize = static_cast<int>(std::lround(static_cast<double>(nodes) / std::max(1, nodesPerSubdomain)));
  const int count = std::max({bySize, bodies, ranks, 1});
  std::string reason = "from the mesh: " + std::to_string(nodes) + " nodes / Mesh/Nodes Per Subdomain " +
                       std::to_string(nodesPerSubdomain);
  if (count == ranks && ranks > std::max(bySize, bodies)) reason += ", raised to one per rank";
  else if (count == bodies && bodies > bySize) reason += ", raised to one per body";
  return {count, reason};
}

}  // namespace tribos::stack
