#pragma once
/// \file SubdomainClusters.hpp
/// Face neighbours of subdomains, and compact clusters of them: the groups whose subdomains
/// hybrid T-FETI glues by face averages so that the coarse problem has six rows per cluster
/// instead of six per subdomain (doc/measurements/coarse_problem.md, "Hybrid T-FETI").
/// Measured there with perf/prototypes/htfeti_conditioning.cpp: the conditioning of the glued
/// cluster is set by its shape (slender clusters bend), and k-means clusters of the subdomain
/// centroids are the most compact of the builders tried on irregular decompositions. A
/// prototype beside that tool, not library code: the solver does not use clusters yet
/// (perf/prototypes/CMakeLists.txt).
#include <array>
#include <vector>

#include "tribos/mesh/Decomposition.hpp"

namespace tribos::mesh {

/// The nodes that subdomains s and t share when they share a face (at least three common
/// nodes, not all on one line), ascending; empty otherwise (edge or corner neighbours, none).
std::vector<LO> sharedFaceNodes(const Mesh& mesh, const Decomposition& D, int s, int t);

/// Per subdomain, its face neighbours in the same body, ascending. Needs every subdomain's
/// node list (before RankData releases those of other ranks).
std::vector<std::vector<int>> faceNeighbours(const Mesh& mesh, const Decomposition& D);

/// The mean of each subdomain's node coordinates.
std::vector<std::array<double, 3>> subdomainCentroids(const Mesh& mesh, const Decomposition& D);

/// Steps 2 and 3 of compactClusters on any grouping (ids >= 0 per subdomain): each group split
/// into its face-connected pieces, pieces of fewer than size / 2 subdomains joined to a
/// neighbour, ids renumbered 0, 1, ... in the order of their lowest subdomain.
std::vector<int> repairClusters(const Mesh& mesh, const Decomposition& D, std::vector<int> cluster, int size);

/// Clusters of about `size` (>= 1) subdomains, body by body, as cluster ids 0, 1, ... per
/// subdomain (numbered in the order of their lowest subdomain):
///  1. k-means of the subdomain centroids (mean node coordinates) with round(n / size) centres
///     per body of n subdomains (at least one), seeded by farthest points from the body's first
///     subdomain, 50 rounds of "each subdomain to its nearest centre (ties: the lower centre),
///     each centre to its members' mean";
///  2. each cluster split into its face-connected pieces (a cluster that is not has more than
///     six rigid motions);
///  3. pieces of fewer than size / 2 subdomains joined, in id order, to the neighbouring cluster
///     of the same body they share the most faces with (ties: the lower id).
/// Deterministic: the same decomposition gives the same clusters on every rank.
std::vector<int> compactClusters(const Mesh& mesh, const Decomposition& D, int size);

}  // namespace tribos::mesh
