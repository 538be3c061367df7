#pragma once
/// \file SubdomainCount.hpp
/// How many subdomains a mesh read from a file is cut into when the scene does not say
/// (Mesh/Subdomains = 0): one per Mesh/Nodes Per Subdomain nodes, so that a subdomain's size,
/// and with it H/h, stays the same as the mesh is refined (issue 46; the measurements behind
/// the default size are in doc/measurements/curved_iterations.md, "How many subdomains").

#include <string>

namespace tribos::stack {

struct SubdomainCount {
  int count = 0;
  /// Where `count` came from, for the set-up report: empty where the scene gave it, else
  /// e.g. "from the mesh: 6344 nodes / Mesh/Nodes Per Subdomain 2000".
  std::string reason;
};

/// `requested` > 0: that count, as given. 0: round(nodes / nodesPerSubdomain), raised to one
/// per body (a subdomain cannot span two) and to one per rank (a rank without a subdomain
/// would idle). The count depends on the mesh alone unless the rank floor applies, so a scene
/// gives the same decomposition, and the same results, on every rank and thread layout whose
/// rank count is at most that.
SubdomainCount chooseSubdomainCount(int requested, int nodes, int bodies, int nodesPerSubdomain, int ranks);

}  // namespace tribos::stack
