// Prototype (issue 11, doc/measurements/coarse_problem.md "Hybrid T-FETI"): the conditioning of hybrid
// T-FETI against T-FETI on the bonded bricks, one rank. Subdomains are grouped into clusters of
// c x c x c (structured bricks only); inside a cluster every pair of face neighbours is glued by
// the averages of the six rigid motions over their shared face (the "kernel" rows B0); every row
// of B stays. The cluster's generalised inverse solves the local saddle point
//     [F0  -G0^T] [mu   ]   [B0 K^+ f]
//     [G0   0   ] [alpha] = [R^T f   ]      (F0 = B0 K^+ B0^T, G0^T = B0 R)
// with the first subdomain's alpha fixed to zero (the cluster's own rigid motions), densely.
// The coarse space is the cluster's six rigid motions. Both methods run the same projected,
// Dirichlet-preconditioned CG from zero on the same random right-hand side in Ker G; the CG
// Lanczos coefficients give kappa.
//
// Usage: build/bin/tribos_htfeti_conditioning [grid (4x2x2)] [H/h (3)] [cluster edge c or AxBxC (2)]
//          [grid | metis | metis-recursive | metis-moved | greedy | bisection | kmeans | kmeans-moved]
//          (kmeans: mesh::compactClusters, the builder doc/measurements/coarse_problem.md recommends)
//        build/bin/tribos_htfeti_conditioning SCENE.xml [cluster size (8)] [method as above, not grid]
//          [Path=value overrides...]
//        HTFETI_WHERE=1 also prints the clusters that hold most of the top eigenvector of P M P F_H.
// Not a test and not part of the solver: a measurement for the design note.
#include <metis.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_LAPACK.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <functional>
#include <map>
#include <numeric>
#include <string>
#include <vector>

#include "SubdomainClusters.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/ProjectedCg.hpp"
#include "tribos/feti/SubdomainSolver.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

using namespace tribos;
using Vec = std::vector<double>;

namespace {
double dot(const Vec& a, const Vec& b) {
  double s = 0.0;
  for (size_t i = 0; i < a.size(); ++i) s += a[i] * b[i];
  return s;
}

// Row d of the six geometric rigid modes at the scaled point p: translations, then e_k x p.
void modeRow(int d, const double* p, double* v) {
  for (int j = 0; j < 3; ++j) v[j] = j == d ? 1.0 : 0.0;
  const double rotation[3][3] = {{0.0, p[2], -p[1]}, {-p[2], 0.0, p[0]}, {p[1], -p[0], 0.0}};
  for (int k = 0; k < 3; ++k) v[3 + k] = rotation[d][k];
}

// The nodes subdomains s and t share (sorted).
std::vector<LO> sharedNodes(const mesh::Decomposition& D, int s, int t) {
  const auto& ns = D.subdomains[s].nodes;
  const auto& nt = D.subdomains[t].nodes;
  std::vector<LO> shared;
  std::set_intersection(ns.begin(), ns.end(), nt.begin(), nt.end(), std::back_inserter(shared));
  return shared;
}

// Clusters of about `size` subdomains: METIS (k-way with contiguous parts, or recursive
// bisection) on the face-neighbour graph of each body's subdomains.
std::vector<int> metisClusters(const mesh::Mesh& M, const mesh::Decomposition& D,
                               int size, bool recursive) {
  const int S = D.numSubdomains();
  std::vector<int> cluster(S, -1);
  std::map<int, std::vector<int>> bodies;
  for (int s = 0; s < S; ++s) bodies[D.subdomains[s].body].push_back(s);
  int next = 0;
  for (auto& [body, members] : bodies) {
    idx_t n = static_cast<idx_t>(members.size()), parts = std::max<idx_t>(1, (n + size / 2) / size), ncon = 1;
    if (parts == 1) {
      for (int s : members) cluster[s] = next;
      ++next;
      continue;
    }
    std::vector<idx_t> xadj{0}, adjncy, part(n);
    for (idx_t a = 0; a < n; ++a) {
      for (idx_t b = 0; b < n; ++b)
        if (a != b && !mesh::sharedFaceNodes(M, D, members[a], members[b]).empty()) adjncy.push_back(b);
      xadj.push_back(static_cast<idx_t>(adjncy.size()));
    }
    idx_t options[METIS_NOPTIONS], cut = 0;
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_CONTIG] = 1;
    (recursive ? METIS_PartGraphRecursive : METIS_PartGraphKway)(&n, &ncon, xadj.data(), adjncy.data(), nullptr, nullptr, nullptr, &parts, nullptr, nullptr,
                        options, &cut, part.data());
    for (idx_t a = 0; a < n; ++a) cluster[members[a]] = next + static_cast<int>(part[a]);
    next += static_cast<int>(parts);
  }
  return cluster;
}

// Clusters of about `size` subdomains grown greedily, body by body, for compactness: a cluster
// starts at the unassigned subdomain with the fewest unassigned face neighbours (a corner of
// what is left) and takes, one at a time, the unassigned neighbour that shares the most faces
// with it (ties: the fewest unassigned neighbours, then the lowest index). A cluster left with
// fewer than size / 2 subdomains joins the neighbouring cluster it shares the most faces with.
std::vector<int> greedyClusters(const mesh::Mesh& M, const mesh::Decomposition& D,
                                int size) {
  const int S = D.numSubdomains();
  const std::vector<std::vector<int>> neighbours = mesh::faceNeighbours(M, D);
  std::vector<int> cluster(S, -1);
  auto freeNeighbours = [&](int s) {
    return static_cast<int>(std::count_if(neighbours[s].begin(), neighbours[s].end(), [&](int t) { return cluster[t] < 0; }));
  };
  std::vector<std::vector<int>> members;
  for (;;) {
    int seed = -1;
    for (int s = 0; s < S; ++s)
      if (cluster[s] < 0 && (seed < 0 || freeNeighbours(s) < freeNeighbours(seed))) seed = s;
    if (seed < 0) break;
    const int id = static_cast<int>(members.size());
    members.push_back({seed});
    cluster[seed] = id;
    while (static_cast<int>(members[id].size()) < size) {
      int best = -1, bestShared = -1, bestFree = 0;
      for (int m : members[id])
        for (int t : neighbours[m]) {
          if (cluster[t] >= 0) continue;
          const int shared = static_cast<int>(
              std::count_if(neighbours[t].begin(), neighbours[t].end(), [&](int u) { return cluster[u] == id; }));
          const int free = freeNeighbours(t);
          if (shared > bestShared || (shared == bestShared && (free < bestFree || (free == bestFree && t < best))))
            best = t, bestShared = shared, bestFree = free;
        }
      if (best < 0) break;
      members[id].push_back(best);
      cluster[best] = id;
    }
  }
  return mesh::repairClusters(M, D, cluster, size);  // small leftovers join a neighbour cluster
}

// Clusters by recursive coordinate bisection of the subdomains' centroids (each split halves a
// set across its longest extent, ties by the other axes), body by body, until a set has at most
// `size` subdomains; a set that is not face-connected is then split into its face-connected
// pieces, and pieces of fewer than size / 2 subdomains join the neighbouring cluster they share
// the most faces with.
std::vector<int> bisectionClusters(const mesh::Mesh& M, const mesh::Decomposition& D,
                                   int size) {
  const int S = D.numSubdomains();
  const std::vector<std::array<double, 3>> centroid = mesh::subdomainCentroids(M, D);
  std::vector<int> cluster(S, -1);
  int next = 0;
  std::function<void(std::vector<int>)> split = [&](std::vector<int> set) {
    if (static_cast<int>(set.size()) <= size) {
      for (int s : set) cluster[s] = next;
      ++next;
      return;
    }
    int axis = 0;
    double extent = -1.0;
    for (int j = 0; j < 3; ++j) {
      double lo = 1e300, hi = -1e300;
      for (int s : set) lo = std::min(lo, centroid[s][j]), hi = std::max(hi, centroid[s][j]);
      if (hi - lo > extent) extent = hi - lo, axis = j;
    }
    std::sort(set.begin(), set.end(), [&](int a, int b) {
      for (int k = 0; k < 3; ++k) {
        const int j = (axis + k) % 3;
        if (std::abs(centroid[a][j] - centroid[b][j]) > 1e-9 * (1.0 + std::abs(centroid[a][j])))
          return centroid[a][j] < centroid[b][j];
      }
      return a < b;
    });
    const size_t half = set.size() / 2;
    split(std::vector<int>(set.begin(), set.begin() + half));
    split(std::vector<int>(set.begin() + half, set.end()));
  };
  std::map<int, std::vector<int>> bodies;
  for (int s = 0; s < S; ++s) bodies[D.subdomains[s].body].push_back(s);
  for (auto& [body, members] : bodies) split(members);
  return mesh::repairClusters(M, D, cluster, size);
}

// Subdomains held by one face inside their cluster moved, where they can be, to the neighbouring
// cluster they share the most (at least two) faces with: the cluster they leave keeps at least
// size / 2 subdomains and stays face-connected, the one they join stays under 3 size / 2. Sweeps
// until nothing moves (at most 20).
std::vector<int> moveDanglingSubdomains(const mesh::Mesh& M, const mesh::Decomposition& D,
                                        std::vector<int> cluster, int size) {
  const int S = D.numSubdomains();
  const std::vector<std::vector<int>> neighbours = mesh::faceNeighbours(M, D);
  std::map<int, int> count;
  for (int c : cluster) ++count[c];
  auto connectedWithout = [&](int c, int removed) {
    int start = -1, members = 0;
    for (int s = 0; s < S; ++s)
      if (cluster[s] == c && s != removed) start = s, ++members;
    if (start < 0) return true;
    std::vector<char> seen(S, 0);
    std::vector<int> stack{start};
    seen[start] = 1;
    int reached = 1;
    while (!stack.empty()) {
      const int a = stack.back();
      stack.pop_back();
      for (int b : neighbours[a])
        if (!seen[b] && b != removed && cluster[b] == c) seen[b] = 1, ++reached, stack.push_back(b);
    }
    return reached == members;
  };
  for (int sweep = 0; sweep < 20; ++sweep) {
    int moved = 0;
    for (int s = 0; s < S; ++s) {
      std::map<int, int> faces;
      for (int t : neighbours[s]) ++faces[cluster[t]];
      const int own = faces[cluster[s]];
      if (own > 1 || 2 * (count[cluster[s]] - 1) < size) continue;
      int best = -1;
      for (auto [c, k] : faces)
        if (c != cluster[s] && k >= 2 && k > own && 2 * (count[c] + 1) <= 3 * size && (best < 0 || k > faces[best])) best = c;
      if (best < 0 || !connectedWithout(cluster[s], s)) continue;
      --count[cluster[s]];
      ++count[best];
      cluster[s] = best;
      ++moved;
    }
    if (moved == 0) break;
  }
  return cluster;
}

struct Sparse {  // one row of B0 restricted to one subdomain: (local dof, value)
  std::vector<std::pair<LO, double>> terms;
};

struct Cluster {
  std::vector<int> subdomains;
  std::array<double, 3> centre{};
  double scale = 1.0;
  int rows = 0;                                  // B0 rows
  std::map<int, std::vector<Sparse>> b0;         // per subdomain: its part of every B0 row (rows x)
  std::map<int, std::vector<int>> rowsOf;        // per subdomain: the B0 rows that touch it
  std::map<int, Vec> z;                          // per subdomain: K^+ B0_s^T on rowsOf, n x |rowsOf|
  std::vector<double> saddle;                    // LU of the reduced saddle matrix
  std::vector<int> pivots;
  int size = 0;
};

struct Result {
  int iterations = 0;
  double kappa = 0.0, lo = 0.0, hi = 0.0;
};

// Projected preconditioned CG from zero for A x = b (b in Ker G); A, M and P given.
Result projectedCg(const std::function<void(const Vec&, Vec&)>& A, const std::function<void(const Vec&, Vec&)>& M,
                   const std::function<void(Vec&)>& P, const Vec& b, double tolerance) {
  Vec x(b.size(), 0.0), w = b, z(b.size()), p, q(b.size());
  const double normB = std::sqrt(dot(w, w));
  M(w, z);
  P(z);
  p = z;
  double wz = dot(w, z);
  std::vector<double> alphas, betas;
  Result r;
  for (; r.iterations < 2000; ++r.iterations) {
    A(p, q);
    P(q);
    const double pq = dot(p, q), alpha = wz / pq;
    for (size_t i = 0; i < x.size(); ++i) x[i] += alpha * p[i], w[i] -= alpha * q[i];
    M(w, z);
    P(z);
    const double wzNew = dot(w, z), beta = wzNew / wz;
    wz = wzNew;
    alphas.push_back(alpha);
    betas.push_back(beta);
    for (size_t i = 0; i < p.size(); ++i) p[i] = z[i] + beta * p[i];
    if (std::sqrt(dot(w, w)) <= tolerance * normB) {
      ++r.iterations;
      break;
    }
  }
  betas.pop_back();
  const auto [lo, hi] = feti::lanczosExtremes(alphas, betas);
  r.lo = lo;
  r.hi = hi;
  r.kappa = hi / lo;
  return r;
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  {
    Tpetra::ScopeGuard tpetra(&argc, &argv);
    core::warmUpKokkosForThreads();
    // GRID H/h EDGE [grid | metis | metis-recursive | greedy | bisection]: the bricks, clusters of EDGE^3
    // subdomains (EDGE^3 blocks of the grid, METIS on the face-neighbour graph, greedyClusters or
    // bisectionClusters);
    // FILE.xml SIZE [metis | metis-recursive | greedy | bisection] [Path=value...]: any scene, clusters of
    // about SIZE.
    const std::string first = argc > 1 ? argv[1] : "4x2x2";
    const bool fromFile = first.size() > 4 && first.substr(first.size() - 4) == ".xml";
    const std::string grid = fromFile ? "-" : first, h = fromFile ? "-" : (argc > 2 ? argv[2] : "3");
    // EDGE: c (blocks of c x c x c) or AxBxC (blocks of A x B x C subdomains).
    const std::string edgeText = fromFile ? "0" : (argc > 3 ? argv[3] : "2");
    int edgeDims[3] = {0, 0, 0};
    if (std::sscanf(edgeText.c_str(), "%dx%dx%d", &edgeDims[0], &edgeDims[1], &edgeDims[2]) != 3)
      edgeDims[0] = edgeDims[1] = edgeDims[2] = std::atoi(edgeText.c_str());
    const int edge = edgeDims[0];
    const std::string how = fromFile ? (argc > 3 ? argv[3] : "metis") : (argc > 4 ? argv[4] : "grid");
    const bool recursive = how == "metis-recursive";
    const int metisSize = fromFile ? (argc > 2 ? std::atoi(argv[2]) : 8)
                                   : (how == "grid" ? 0 : edge * edge * edge);
    int gridDims[3] = {0, 0, 0};
    if (!fromFile) std::sscanf(grid.c_str(), "%dx%dx%d", &gridDims[0], &gridDims[1], &gridDims[2]);

    Teuchos::ParameterList params("Tribos");
    const auto valid = stack::sceneValidParameters();
    std::vector<std::string> overrides;
    if (fromFile) {
      std::ifstream in(first);
      std::stringstream text;
      text << in.rdbuf();
      params = *core::parameterListFromXml(text.str(), first);
      for (int a = 4; a < argc; ++a) overrides.push_back(argv[a]);
    } else {
      overrides = {"Mesh/Subdomains Per Brick=" + grid, "Mesh/H Over h=" + h,
                   "Contact/Slave Side Set=contact_aluminium", "Contact/Master Side Set=contact_steel"};
    }
    overrides.push_back("Contact/Friction Model=Bonded");
    for (const std::string& o : overrides) core::applyOverride(params, *valid, o);
    core::validateAndSetDefaults(params, *valid, "htfeti");
    const auto scene = stack::buildScene(params, fromFile ? first : std::string("htfeti"));
    std::vector<fem::SubdomainSystem> systems, copies;
    stack::assembleOwnedSubdomains(scene, MPI_COMM_WORLD, systems);
    copies = systems;
    const auto B = feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), 1);
    feti::TotalFetiSettings settings;
    settings.dirichletPreconditioner = true;
    const feti::TotalFeti feti(scene.mesh, scene.decomposition, std::move(copies), B,
                               Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_WORLD)), settings);
    const auto& D = scene.decomposition;
    const mesh::Mesh& M = scene.mesh;
    const auto& coords = M.coords;
    const int S = D.numSubdomains();
    const LO nd = static_cast<LO>(B.numRows);
    auto toDual = [&](const Vec& v) {
      auto d = feti.createDualVector();
      auto view = d->getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (LO i = 0; i < nd; ++i) view(i, 0) = v[i];
      return d;
    };
    auto fromDual = [&](const feti::DualVector& d, Vec& v) {
      auto view = d.getLocalViewHost(Tpetra::Access::ReadOnly);
      v.resize(nd);
      for (LO i = 0; i < nd; ++i) v[i] = view(i, 0);
    };

    // Subdomain solvers (K^+: the regularised factor, a generalised inverse).
    std::vector<feti::SubdomainSolver> solvers(S);
    for (int s = 0; s < S; ++s) {
      std::vector<std::array<double, 3>> xs;
      for (LO node : D.subdomains[s].nodes) xs.push_back(coords[node]);
      solvers[s].compute(systems[s], xs, feti::Factorization::Cholmod);
    }
    // Clusters: subdomain grid index from the centroid within its body's bounding box.
    std::map<int, std::array<double, 6>> box;  // body -> lo, hi
    for (int s = 0; s < S; ++s) {
      auto& b = box.try_emplace(D.subdomains[s].body, std::array<double, 6>{1e300, 1e300, 1e300, -1e300, -1e300, -1e300})
                    .first->second;
      for (LO node : D.subdomains[s].nodes)
        for (int j = 0; j < 3; ++j) b[j] = std::min(b[j], coords[node][j]), b[3 + j] = std::max(b[3 + j], coords[node][j]);
    }
    std::map<std::array<int, 4>, int> clusterId;
    std::vector<int> clusterOf(S);
    std::vector<Cluster> clusters;
    if (metisSize > 0) {
      clusterOf = how == "greedy"      ? greedyClusters(M, D, metisSize)
                  : how == "kmeans"    ? mesh::compactClusters(M, D, metisSize)
                  : how == "kmeans-moved" ? moveDanglingSubdomains(M, D, mesh::compactClusters(M, D, metisSize), metisSize)
                  : how == "metis-moved" ? moveDanglingSubdomains(M, D, metisClusters(M, D, metisSize, false), metisSize)
                  : how == "bisection" ? bisectionClusters(M, D, metisSize)
                                       : metisClusters(M, D, metisSize, recursive);
      clusters.resize(*std::max_element(clusterOf.begin(), clusterOf.end()) + 1);
      for (int s = 0; s < S; ++s) clusters[clusterOf[s]].subdomains.push_back(s);
    }
    const std::vector<std::array<double, 3>> centroids = mesh::subdomainCentroids(M, D);
    for (int s = 0; s < S && metisSize == 0; ++s) {
      const std::array<double, 3>& c = centroids[s];
      const auto& b = box[D.subdomains[s].body];
      std::array<int, 4> key{D.subdomains[s].body, 0, 0, 0};
      for (int j = 0; j < 3; ++j)
        key[1 + j] = static_cast<int>(std::floor((c[j] - b[j]) / ((b[3 + j] - b[j]) / gridDims[j]))) / edgeDims[j];
      auto [it, fresh] = clusterId.try_emplace(key, static_cast<int>(clusters.size()));
      if (fresh) clusters.emplace_back();
      clusterOf[s] = it->second;
      clusters[it->second].subdomains.push_back(s);
    }
    {  // clusters whose subdomains are not face-connected have more than six rigid motions
      int disconnected = 0;
      for (const Cluster& C : clusters) {
        std::vector<int> seen(C.subdomains.size(), 0), stack{0};
        seen[0] = 1;
        while (!stack.empty()) {
          const int a = stack.back();
          stack.pop_back();
          for (size_t b = 0; b < C.subdomains.size(); ++b)
            if (!seen[b] && !mesh::sharedFaceNodes(M, D, C.subdomains[a], C.subdomains[b]).empty()) seen[b] = 1, stack.push_back(static_cast<int>(b));
        }
        disconnected += std::count(seen.begin(), seen.end(), 0) > 0;
      }
      // Kernel faces per subdomain inside its cluster (3 in a 2 x 2 x 2 block; 1: held by one face)
      int oneFace = 0;
      double faces = 0.0;
      for (const Cluster& C : clusters)
        for (int s : C.subdomains) {
          int k = 0;
          for (int t : C.subdomains) k += t != s && !mesh::sharedFaceNodes(M, D, s, t).empty();
          faces += k;
          oneFace += k == 1;
        }
      std::printf("clusters: %zu, not face-connected: %d, kernel faces per subdomain %.2f, held by one face: %d\n",
                  clusters.size(), disconnected, faces / S, oneFace);
      // Pairs of a cluster that share nodes but no face and have no common face neighbour in the
      // cluster (no face path of length two): FETI-DP's "acceptable face path" fails for them.
      int edgePairs = 0, cornerPairs = 0;
      for (const Cluster& C : clusters)
        for (int s : C.subdomains)
          for (int t : C.subdomains) {
            if (t <= s || !mesh::sharedFaceNodes(M, D, s, t).empty()) continue;
            const size_t n = sharedNodes(D, s, t).size();
            if (n == 0) continue;
            bool path = false;
            for (int u : C.subdomains)
              path = path || (u != s && u != t && !mesh::sharedFaceNodes(M, D, s, u).empty() && !mesh::sharedFaceNodes(M, D, u, t).empty());
            if (path) continue;
            (n > 1 ? edgePairs : cornerPairs) += 1;
          }
      std::printf("pairs without a face path of length 2: %d sharing an edge, %d sharing a corner\n", edgePairs, cornerPairs);
      // Aspect ratio of each cluster: sqrt of the largest over the smallest eigenvalue of the
      // covariance of its nodes' coordinates (1 for a cube, 4 for a 4 x 1 x 1 bar).
      double maxAspect = 0.0, meanAspect = 0.0;
      for (const Cluster& C : clusters) {
        std::vector<LO> nodes;
        for (int s : C.subdomains) nodes.insert(nodes.end(), D.subdomains[s].nodes.begin(), D.subdomains[s].nodes.end());
        std::sort(nodes.begin(), nodes.end());
        nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
        double mean[3] = {0, 0, 0}, cov[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        for (LO n : nodes)
          for (int j = 0; j < 3; ++j) mean[j] += coords[n][j] / nodes.size();
        for (LO n : nodes)
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) cov[3 * i + j] += (coords[n][i] - mean[i]) * (coords[n][j] - mean[j]) / nodes.size();
        double eig[3], work[9];
        int info = 0;
        Teuchos::LAPACK<int, double>().SYEV('N', 'U', 3, cov, 3, eig, work, 9, &info);
        const double aspect = std::sqrt(eig[2] / eig[0]);
        maxAspect = std::max(maxAspect, aspect);
        meanAspect += aspect / clusters.size();
      }
      std::printf("cluster aspect ratio: max %.2f, mean %.2f\n", maxAspect, meanAspect);
    }
    for (Cluster& C : clusters) {  // centre and rms radius of the cluster's nodes
      std::map<LO, int> nodes;
      for (int s : C.subdomains)
        for (LO node : D.subdomains[s].nodes) nodes[node] = 1;
      for (auto& [node, one] : nodes)
        for (int j = 0; j < 3; ++j) C.centre[j] += coords[node][j] / nodes.size();
      double r2 = 0.0;
      for (auto& [node, one] : nodes)
        for (int j = 0; j < 3; ++j) r2 += std::pow(coords[node][j] - C.centre[j], 2) / nodes.size();
      C.scale = std::sqrt(r2);
    }
    auto scaled = [&](const Cluster& C, LO node, double* p) {
      for (int j = 0; j < 3; ++j) p[j] = (coords[node][j] - C.centre[j]) / C.scale;
    };

    // B0: six face-average rows per pair of face neighbours in a cluster.
    for (Cluster& C : clusters) {
      for (size_t a = 0; a < C.subdomains.size(); ++a)
        for (size_t b = a + 1; b < C.subdomains.size(); ++b) {
          const int s = C.subdomains[a], t = C.subdomains[b];
          const auto& ns = D.subdomains[s].nodes;
          const auto& nt = D.subdomains[t].nodes;
          const std::vector<LO> shared = mesh::sharedFaceNodes(M, D, s, t);
          if (shared.empty()) continue;
          auto localOf = [&](const std::vector<LO>& nodes, LO node) {
            return static_cast<LO>(std::lower_bound(nodes.begin(), nodes.end(), node) - nodes.begin());
          };
          // Row m: the average over the shared nodes of rigid mode m's component of u_s - u_t.
          const double w = 1.0 / std::sqrt(static_cast<double>(shared.size()));
          for (int m = 0; m < 6; ++m) {
            for (int other : C.subdomains) C.b0[other].emplace_back();
            for (LO node : shared) {
              double p[3], row[6];
              scaled(C, node, p);
              for (int d = 0; d < 3; ++d) {
                modeRow(d, p, row);
                if (row[m] == 0.0) continue;
                C.b0[s].back().terms.push_back({3 * localOf(ns, node) + d, w * row[m]});
                C.b0[t].back().terms.push_back({3 * localOf(nt, node) + d, -w * row[m]});
              }
            }
            ++C.rows;
          }
        }
    }

    // Per cluster: Z_s = K_s^+ B0_s^T, F0, G0^T and the LU of the reduced saddle matrix.
    Teuchos::LAPACK<int, double> lapack;
    for (Cluster& C : clusters) {
      const int m0 = C.rows, ns = static_cast<int>(C.subdomains.size());
      for (int s : C.subdomains) {
        const LO n = D.subdomains[s].numDofs();
        auto& rows = C.rowsOf[s];
        for (int r = 0; r < m0; ++r)
          if (!C.b0[s][r].terms.empty()) rows.push_back(r);
        auto& z = C.z[s];
        z.assign(static_cast<size_t>(n) * rows.size(), 0.0);
        for (size_t j = 0; j < rows.size(); ++j) {
          Vec rhs(n, 0.0);
          for (auto [dof, v] : C.b0[s][rows[j]].terms) rhs[dof] += v;
          solvers[s].applyGeneralizedInverse(rhs.data(), &z[j * n], 1);
        }
      }
      C.size = m0 + 6 * (ns - 1);
      std::vector<double> A(static_cast<size_t>(C.size) * C.size, 0.0);  // column-major
      auto at = [&](int i, int j) -> double& { return A[static_cast<size_t>(j) * C.size + i]; };
      for (int s : C.subdomains) {
        const LO n = D.subdomains[s].numDofs();
        const auto& rows = C.rowsOf[s];
        for (size_t a = 0; a < rows.size(); ++a)
          for (size_t b = 0; b < rows.size(); ++b) {
            double v = 0.0;
            for (auto [dof, c] : C.b0[s][rows[a]].terms) v += c * C.z[s][b * n + dof];
            at(rows[a], rows[b]) += v;
          }
      }
      for (int k = 1; k < ns; ++k) {
        const int s = C.subdomains[k];
        const LO n = D.subdomains[s].numDofs();
        for (int i = 0; i < m0; ++i)
          for (int mode = 0; mode < 6; ++mode) {
            double v = 0.0;  // (B0_s R_s)_{i, mode}
            for (auto [dof, b] : C.b0[s][i].terms) v += b * systems[s].R[static_cast<size_t>(mode) * n + dof];
            at(i, m0 + 6 * (k - 1) + mode) = -v;
            at(m0 + 6 * (k - 1) + mode, i) = v;
          }
      }
      C.saddle = A;
      C.pivots.assign(C.size, 0);
      int info = 0;
      lapack.GETRF(C.size, C.size, C.saddle.data(), C.size, C.pivots.data(), &info);
      if (info != 0) std::printf("cluster LU failed: info %d (size %d)\n", info, C.size);
    }

    // u = K_c^+ f on one cluster: f[s] in, u[s] out (local dofs); w and rhs: scratch.
    std::vector<Vec> f(S), w(S);
    for (int s = 0; s < S; ++s) f[s].assign(D.subdomains[s].numDofs(), 0.0), w[s] = f[s];
    auto clusterSolve = [&](const Cluster& C) {
      const int m0 = C.rows, ns = static_cast<int>(C.subdomains.size());
      std::vector<double> rhs(C.size, 0.0);
      for (int k = 0; k < ns; ++k) {
        const int s = C.subdomains[k];
        const LO n = D.subdomains[s].numDofs();
        solvers[s].applyGeneralizedInverse(f[s].data(), w[s].data(), 1);
        for (int r : C.rowsOf.at(s))
          for (auto [dof, b] : C.b0.at(s)[r].terms) rhs[r] += b * w[s][dof];
        if (k > 0)
          for (int mode = 0; mode < 6; ++mode) {
            double v = 0.0;
            for (LO dof = 0; dof < n; ++dof) v += systems[s].R[static_cast<size_t>(mode) * n + dof] * f[s][dof];
            rhs[m0 + 6 * (k - 1) + mode] = v;
          }
      }
      int info = 0;
      lapack.GETRS('N', C.size, 1, C.saddle.data(), C.size, C.pivots.data(), rhs.data(), C.size, &info);
      for (int k = 0; k < ns; ++k) {
        const int s = C.subdomains[k];
        const LO n = D.subdomains[s].numDofs();
        Vec& u = f[s];
        u = w[s];
        const auto& rows = C.rowsOf.at(s);
        const Vec& z = C.z.at(s);
        for (size_t j = 0; j < rows.size(); ++j) {
          const double mu = rhs[rows[j]];
          for (LO dof = 0; dof < n; ++dof) u[dof] -= z[j * n + dof] * mu;
        }
        if (k > 0)
          for (int mode = 0; mode < 6; ++mode)
            for (LO dof = 0; dof < n; ++dof)
              u[dof] += systems[s].R[static_cast<size_t>(mode) * n + dof] * rhs[m0 + 6 * (k - 1) + mode];
      }
    };
    // F_H x = B K_c^+ B^T x.
    double fhSeconds = 0.0;
    int fhCalls = 0;
    auto applyFH = [&](const Vec& x, Vec& y) {
      const auto start = std::chrono::steady_clock::now();
      y.assign(nd, 0.0);
      for (const Cluster& C : clusters) {
        for (int s : C.subdomains) {
          const auto& blk = B.blocks[s];
          Vec& fs = f[s];
          std::fill(fs.begin(), fs.end(), 0.0);
          for (size_t r = 0; r < blk.rows.size(); ++r)
            for (LO k = blk.rowPtr[r]; k < blk.rowPtr[r + 1]; ++k) fs[blk.dof[k]] += blk.value[k] * x[blk.rows[r]];
        }
        clusterSolve(C);
        for (int s : C.subdomains) {
          const auto& blk = B.blocks[s];
          for (size_t r = 0; r < blk.rows.size(); ++r)
            for (LO k = blk.rowPtr[r]; k < blk.rowPtr[r + 1]; ++k) y[blk.rows[r]] += blk.value[k] * f[s][blk.dof[k]];
        }
      }
      fhSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++fhCalls;
    };
    // G_H = R_c^T B^T (6 per cluster), by rows of B, and its projector (dense G_H G_H^T).
    const int l = 6 * static_cast<int>(clusters.size());
    std::vector<std::map<int, double>> GH(nd);  // row r: coarse index -> value
    for (int s = 0; s < S; ++s) {
      const Cluster& C = clusters[clusterOf[s]];
      const auto& blk = B.blocks[s];
      for (size_t r = 0; r < blk.rows.size(); ++r)
        for (LO k = blk.rowPtr[r]; k < blk.rowPtr[r + 1]; ++k) {
          const LO dof = blk.dof[k];
          double p[3], row[6];
          scaled(C, D.subdomains[s].nodes[dof / 3], p);
          modeRow(dof % 3, p, row);
          for (int m = 0; m < 6; ++m) GH[blk.rows[r]][6 * clusterOf[s] + m] += blk.value[k] * row[m];
        }
    }
    std::vector<double> GGt(static_cast<size_t>(l) * l, 0.0);
    for (LO r = 0; r < nd; ++r)
      for (auto [i, a] : GH[r])
        for (auto [j, b] : GH[r]) GGt[static_cast<size_t>(j) * l + i] += a * b;
    int info = 0;
    lapack.POTRF('L', l, GGt.data(), l, &info);
    if (info != 0) std::printf("G_H G_H^T not positive definite: info %d\n", info);
    auto projectH = [&](Vec& x) {
      Vec a(l, 0.0);
      for (LO r = 0; r < nd; ++r)
        for (auto [i, g] : GH[r]) a[i] += g * x[r];
      int inf = 0;
      lapack.POTRS('L', l, 1, GGt.data(), l, a.data(), l, &inf);
      for (LO r = 0; r < nd; ++r)
        for (auto [i, g] : GH[r]) x[r] -= g * a[i];
    };
    auto dirichlet = [&](const Vec& x, Vec& y) {
      auto in = toDual(x), out = feti.createDualVector();
      feti.applyDirichlet(*in, *out);
      fromDual(*out, y);
    };
    // T-FETI's operators, through the same CG.
    double ftSeconds = 0.0;
    int ftCalls = 0;
    auto applyFT = [&](const Vec& x, Vec& y) {
      auto in = toDual(x), out = feti.createDualVector();
      const auto start = std::chrono::steady_clock::now();
      feti.applyPF(*in, *out);
      ftSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      ++ftCalls;
      fromDual(*out, y);
    };
    auto projectT = [&](Vec& x) {
      auto in = toDual(x);
      feti.project(*in, *in);
      fromDual(*in, x);
    };
    Vec b(nd);
    for (LO r = 0; r < nd; ++r) b[r] = std::sin(0.37 * r + 0.1) + 0.3 * std::cos(1.3 * r);
    // Right-hand sides in the range of P F P: F_H vanishes on the multipliers of B's rows inside
    // a cluster whose forces B0^T takes up (six per kernel face), so a random vector would not
    // be consistent; the dual problem's own right-hand side is.
    Vec bT = b, bH = b, tmp;
    projectT(bT);
    applyFT(bT, tmp);
    bT = tmp;
    projectT(bT);
    projectH(bH);
    applyFH(bH, tmp);
    bH = tmp;
    projectH(bH);
    {  // Checks: P F_H P symmetric and positive on two vectors of Ker G_H; on cluster 0, B0 u = 0
       // for u = K_c^+ B^T x, and R_c^T B^T x = 0 (x in Ker G_H).
      Vec x(nd), y(nd), fx, fy;
      for (LO r = 0; r < nd; ++r) x[r] = std::cos(0.71 * r), y[r] = std::sin(1.13 * r + 0.4);
      projectH(x);
      projectH(y);
      applyFH(x, fx);
      projectH(fx);
      applyFH(y, fy);
      projectH(fy);
      std::printf("check: x.PFy %.6e y.PFx %.6e x.PFx %.6e y.PFy %.6e\n", dot(x, fy), dot(y, fx), dot(x, fx), dot(y, fy));
      const Cluster& C = clusters[0];
      for (int s : C.subdomains) {
        const auto& blk = B.blocks[s];
        std::fill(f[s].begin(), f[s].end(), 0.0);
        for (size_t r = 0; r < blk.rows.size(); ++r)
          for (LO k = blk.rowPtr[r]; k < blk.rowPtr[r + 1]; ++k) f[s][blk.dof[k]] += blk.value[k] * x[blk.rows[r]];
      }
      std::map<int, Vec> load;
      for (int s : C.subdomains) load[s] = f[s];
      clusterSolve(C);
      const std::vector<Vec>& u = f;
      double b0u = 0.0, b0scale = 0.0;
      for (int i = 0; i < C.rows; ++i) {
        double v = 0.0;
        for (int s : C.subdomains)
          for (auto [dof, b] : C.b0.at(s)[i].terms) v += b * u[s][dof], b0scale = std::max(b0scale, std::abs(b * u[s][dof]));
        b0u = std::max(b0u, std::abs(v));
      }
      double rc[6] = {0, 0, 0, 0, 0, 0};
      for (int s : C.subdomains)
        for (LO dof = 0; dof < D.subdomains[s].numDofs(); ++dof) {
          double p[3], row[6];
          scaled(C, D.subdomains[s].nodes[dof / 3], p);
          modeRow(dof % 3, p, row);
          for (int m = 0; m < 6; ++m) rc[m] += row[m] * load[s][dof];
        }
      std::printf("check: |B0 u| %.3e (terms %.3e), R_c^T f %.3e %.3e %.3e\n", b0u, b0scale, rc[0], rc[3], rc[5]);
    }
    int faces = 0;
    for (const Cluster& C : clusters) faces += C.rows / 6;
    const Result t = projectedCg(applyFT, dirichlet, projectT, bT, 1e-10);
    const Result hy = projectedCg(applyFH, dirichlet, projectH, bH, 1e-10);
    if (std::getenv("HTFETI_WHERE")) {  // where the top eigenvector of P M P F_H lies, by cluster
      Vec v(nd), fv, mv;
      for (LO r = 0; r < nd; ++r) v[r] = std::sin(0.61 * r + 0.2);
      projectH(v);
      for (int it = 0; it < 200; ++it) {
        applyFH(v, fv);
        projectH(fv);
        dirichlet(fv, mv);
        projectH(mv);
        const double n = std::sqrt(dot(mv, mv));
        for (LO r = 0; r < nd; ++r) v[r] = mv[r] / n;
      }
      std::vector<double> share(clusters.size(), 0.0);
      for (int s = 0; s < S; ++s)
        for (LO row : B.blocks[s].rows) share[clusterOf[s]] += v[row] * v[row];
      std::vector<int> order(clusters.size());
      std::iota(order.begin(), order.end(), 0);
      std::sort(order.begin(), order.end(), [&](int a, int b) { return share[a] > share[b]; });
      const auto cen = mesh::subdomainCentroids(M, D);
      for (int k = 0; k < 3; ++k) {
        std::printf("cluster %d: share %.3f, subdomain centroids:", order[k], share[order[k]]);
        for (int s : clusters[order[k]].subdomains) std::printf(" (%.2f %.2f %.2f)", cen[s][0], cen[s][1], cen[s][2]);
        std::printf("\n");
      }
    }
    // applyPF = F x then P: the projection's own time (no memo hit: a new vector each time) off.
    double pSeconds = 0.0;
    for (int k = 0; k < 10; ++k) {
      Vec v(nd);
      for (LO r = 0; r < nd; ++r) v[r] = std::sin(0.1 * k + 0.37 * r);
      auto d = toDual(v);
      const auto start = std::chrono::steady_clock::now();
      feti.project(*d, *d);
      pSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / 10;
    }
    ftSeconds -= ftCalls * pSeconds;
    std::printf("grid,h,subdomains,clusters,kernel_faces,l_tfeti,l_htfeti,tfeti_its,tfeti_kappa,htfeti_its,htfeti_kappa,"
                "tfeti_F_ms,htfeti_F_ms\n");
    std::printf("%s,%s,%d,%zu,%d,%d,%d,%d,%.3g,%d,%.3g,%.3f,%.3f\n", grid.c_str(), h.c_str(), S, clusters.size(), faces,
                6 * S, l, t.iterations, t.kappa, hy.iterations, hy.kappa, 1e3 * ftSeconds / ftCalls,
                1e3 * fhSeconds / fhCalls);
  }
  MPI_Finalize();
  return 0;
}
