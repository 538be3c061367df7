#pragma once
/// \file SubdomainCount.hpp
/// How many subdomains a mesh read from a file is cut into when the scene does not say
/// (Mesh/Subdomains = 0): one per Mesh/Nodes Per Subdomain corner nodes, so that a subdomain's
/// size, and with it H/h, stays the same as the mesh is refined (issue 46; the measurements
/// behind the default size are in doc/measurements/curved_iterations.md, "How many subdomains").
/// Corner nodes (element vertices), not all nodes: H/h counts elements across a subdomain, and a
/// mesh of 10-node tetrahedra has about 6 times the nodes of the 4-node one on the same
/// vertices. Counted by all its nodes, the tet10 Hertz sphere was cut into 4 subdomains (144 PFP)
/// and the tet10 Cattaneo sphere into 5 (1 619 PFP, 11.4 s); by its vertices into 2 (92 PFP;
/// 737 PFP, 7.0 s).

#include <string>

#include "tribos/mesh/Mesh.hpp"

namespace tribos::stack {

struct SubdomainCount {
  int count = 0;
  /// Where `count` came from, for the set-up report: empty where the scene gave it, else
  /// e.g. "from the mesh: 6344 nodes / Mesh/Nodes Per Subdomain 2000".
  std::string reason;
};

/// `requested` > 0: that count, as given. 0: round(corners / nodesPerSubdomain), raised to one
/// per body (a subdomain cannot span two) and to one per rank (a rank without a subdomain
/// would idle); `nodes` (all of them) only for the report. The count depends on the mesh alone
/// unless the rank floor applies, so a scene gives the same decomposition, and the same
/// results, on every rank and thread layout whose rank count is at most that.
SubdomainCount chooseSubdomainCount(int requested, int corners, int nodes, int bodies, int nodesPerSubdomain,
                                    int ranks);

/// The nodes of `mesh` that are a vertex (corner node) of some element: all of them on a mesh of
/// linear elements, none of a quadratic element's mid-edge nodes.
int cornerNodeCount(const mesh::Mesh& mesh);

}  // namespace tribos::stack
