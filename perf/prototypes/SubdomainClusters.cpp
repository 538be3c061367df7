#include "SubdomainClusters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <map>
#include <stdexcept>
#include <utility>

namespace tribos::mesh {

namespace {
using Point = std::array<double, 3>;

double distance2(const Point& a, const Point& b) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

// Three or more nodes not on one line: the largest triangle from the first node against the
// largest squared distance from it (1e-8 relative), so a straight edge of many nodes is no face.
bool spansAFace(const Mesh& mesh, const std::vector<LO>& shared) {
  if (shared.size() < 3) return false;
  const Point& x0 = mesh.coords[shared[0]];
  double area = 0.0, size = 0.0;
  for (size_t i = 1; i < shared.size(); ++i) {
    Point u;
    for (int k = 0; k < 3; ++k) u[k] = mesh.coords[shared[i]][k] - x0[k];
    size = std::max(size, u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (size_t j = i + 1; j < shared.size(); ++j) {
      Point v;
      for (int k = 0; k < 3; ++k) v[k] = mesh.coords[shared[j]][k] - x0[k];
      const double cx = u[1] * v[2] - u[2] * v[1], cy = u[2] * v[0] - u[0] * v[2], cz = u[0] * v[1] - u[1] * v[0];
      area = std::max(area, std::sqrt(cx * cx + cy * cy + cz * cz));
    }
  }
  return area > 1e-8 * size;
}

// Lloyd's k-means of the centroids of one body's subdomains into cluster ids first, first + 1, ...
void kmeansOfBody(const std::vector<Point>& centroid, const std::vector<int>& members, int size, int first,
                  std::vector<int>& cluster) {
  const int k = std::max(1, static_cast<int>(std::lround(static_cast<double>(members.size()) / size)));
  std::vector<Point> centre{centroid[members[0]]};
  while (static_cast<int>(centre.size()) < k) {  // the member farthest from every centre so far
    int far = members[0];
    double best = -1.0;
    for (int s : members) {
      double d = 1e300;
      for (const Point& c : centre) d = std::min(d, distance2(centroid[s], c));
      if (d > best) best = d, far = s;
    }
    centre.push_back(centroid[far]);
  }
  for (int round = 0; round < 50; ++round) {
    for (int s : members) {
      int nearest = 0;
      for (int c = 1; c < k; ++c)
        if (distance2(centroid[s], centre[c]) < distance2(centroid[s], centre[nearest])) nearest = c;
      cluster[s] = first + nearest;
    }
    std::vector<Point> sum(k, Point{0.0, 0.0, 0.0});
    std::vector<int> count(k, 0);
    for (int s : members) {
      const int c = cluster[s] - first;
      ++count[c];
      for (int j = 0; j < 3; ++j) sum[c][j] += centroid[s][j];
    }
    for (int c = 0; c < k; ++c)
      if (count[c] > 0)
        for (int j = 0; j < 3; ++j) centre[c][j] = sum[c][j] / count[c];
  }
}

// Step 2: one id per face-connected piece of each cluster, in the order of the lowest subdomain.
std::vector<int> connectedPieces(const std::vector<int>& cluster, const std::vector<std::vector<int>>& neighbours) {
  const int S = static_cast<int>(cluster.size());
  std::vector<int> piece(S, -1);
  int next = 0;
  for (int s = 0; s < S; ++s) {
    if (piece[s] >= 0) continue;
    std::vector<int> stack{s};
    piece[s] = next;
    while (!stack.empty()) {
      const int a = stack.back();
      stack.pop_back();
      for (int b : neighbours[a])
        if (piece[b] < 0 && cluster[b] == cluster[a]) piece[b] = next, stack.push_back(b);
    }
    ++next;
  }
  return piece;
}

// Step 3, then ids renumbered in the order of their lowest subdomain.
void mergeSmallPieces(std::vector<int>& cluster, const std::vector<std::vector<int>>& neighbours, int size) {
  const int S = static_cast<int>(cluster.size());
  const int count = S == 0 ? 0 : *std::max_element(cluster.begin(), cluster.end()) + 1;
  std::vector<std::vector<int>> members(count);
  for (int s = 0; s < S; ++s) members[cluster[s]].push_back(s);
  for (int id = 0; id < count; ++id) {
    if (members[id].empty() || 2 * static_cast<int>(members[id].size()) >= size) continue;
    std::map<int, int> faces;  // neighbouring cluster -> shared faces
    for (int m : members[id])
      for (int t : neighbours[m])
        if (cluster[t] != id) ++faces[cluster[t]];
    if (faces.empty()) continue;  // a body of its own
    const int into = std::max_element(faces.begin(), faces.end(), [](auto a, auto b) { return a.second < b.second; })->first;
    for (int m : members[id]) cluster[m] = into, members[into].push_back(m);
    members[id].clear();
  }
  std::map<int, int> renumber;
  for (int s = 0; s < S; ++s) cluster[s] = renumber.try_emplace(cluster[s], static_cast<int>(renumber.size())).first->second;
}
}  // namespace

std::vector<Point> subdomainCentroids(const Mesh& mesh, const Decomposition& D) {
  std::vector<Point> c(D.numSubdomains(), Point{0.0, 0.0, 0.0});
  for (int s = 0; s < D.numSubdomains(); ++s)
    for (LO node : D.subdomains[s].nodes)
      for (int k = 0; k < 3; ++k) c[s][k] += mesh.coords[node][k] / D.subdomains[s].numNodes();
  return c;
}

std::vector<LO> sharedFaceNodes(const Mesh& mesh, const Decomposition& D, int s, int t) {
  const auto& a = D.subdomains.at(s).nodes;
  const auto& b = D.subdomains.at(t).nodes;
  std::vector<LO> shared;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(shared));
  return spansAFace(mesh, shared) ? shared : std::vector<LO>{};
}

std::vector<std::vector<int>> faceNeighbours(const Mesh& mesh, const Decomposition& D) {
  const int S = D.numSubdomains();
  // The subdomains of every node, then the nodes of every pair that shares one.
  std::vector<std::vector<int>> subdomainsOf(mesh.numNodes());
  for (int s = 0; s < S; ++s)
    for (LO node : D.subdomains[s].nodes) subdomainsOf[node].push_back(s);
  std::map<std::pair<int, int>, std::vector<LO>> sharedBy;
  for (LO node = 0; node < mesh.numNodes(); ++node) {
    const auto& list = subdomainsOf[node];
    for (size_t i = 0; i < list.size(); ++i)
      for (size_t j = i + 1; j < list.size(); ++j)
        if (D.subdomains[list[i]].body == D.subdomains[list[j]].body) sharedBy[{list[i], list[j]}].push_back(node);
  }
  std::vector<std::vector<int>> neighbours(S);
  for (const auto& [pair, nodes] : sharedBy)
    if (spansAFace(mesh, nodes)) neighbours[pair.first].push_back(pair.second), neighbours[pair.second].push_back(pair.first);
  for (auto& list : neighbours) std::sort(list.begin(), list.end());
  return neighbours;
}

std::vector<int> compactClusters(const Mesh& mesh, const Decomposition& D, int size) {
  if (size < 1) throw std::invalid_argument("tribos::mesh::compactClusters: the cluster size must be at least 1");
  const int S = D.numSubdomains();
  const std::vector<Point> centroid = subdomainCentroids(mesh, D);
  std::map<int, std::vector<int>> bodies;
  for (int s = 0; s < S; ++s) bodies[D.subdomains[s].body].push_back(s);
  std::vector<int> cluster(S, -1);
  int next = 0;
  for (const auto& [body, members] : bodies) {
    kmeansOfBody(centroid, members, size, next, cluster);
    next = *std::max_element(cluster.begin(), cluster.end()) + 1;
  }
  return repairClusters(mesh, D, std::move(cluster), size);
}

std::vector<int> repairClusters(const Mesh& mesh, const Decomposition& D, std::vector<int> cluster, int size) {
  const auto neighbours = faceNeighbours(mesh, D);
  cluster = connectedPieces(cluster, neighbours);
  mergeSmallPieces(cluster, neighbours, size);
  return cluster;
}

}  // namespace tribos::mesh
