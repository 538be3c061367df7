// Per-subdomain assembly of K_s and f_s (paper Section 4.1) as Kokkos kernels.
//
// Thread safety (TOOLCHAIN.md): assembleSubdomain runs concurrently for different
// subdomains on OpenMP threads with Debian's Serial-only Kokkos, so it creates no managed
// View: all storage is std::vector, wrapped in unmanaged Views for the kernels, and only
// RangePolicy parallel_for is used. The scatter of element matrices is replaced by a
// race-free gather over node rows, so the kernels are also correct on a threaded back end.
#include <Kokkos_Core.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

#include "tribos/core/Errors.hpp"
#include "tribos/fem/ElementKernels.hpp"
#include "tribos/fem/SolidElements.hpp"
#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::fem {

namespace {
using ExecSpace = Kokkos::Serial;
template <class T>
using Unmanaged = Kokkos::View<T*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;

/// Element matrices: Ke(e) = the (3 n_e) x (3 n_e) matrix of element e (n_e nodes),
/// row-major, at Ke[matrixStart(e)].
struct ElementStiffnessKernel {
  Unmanaged<const double> coords;             // 3 per local node
  Unmanaged<const LO> nodes, nodeStart;       // element e: nodes[nodeStart(e) .. nodeStart(e + 1))
  Unmanaged<const mesh::ElementType> type;    // per element
  Unmanaged<const double> lambda, mu;         // per element
  Unmanaged<const size_t> matrixStart;        // per element
  Unmanaged<double> Ke;
  Unmanaged<double> volume;                   // per element

  KOKKOS_INLINE_FUNCTION void operator()(const LO e) const {
    double x[mesh::kMaxElementNodes][3];
    for (LO k = nodeStart(e); k < nodeStart(e + 1); ++k)
      for (int c = 0; c < 3; ++c) x[k - nodeStart(e)][c] = coords(3 * nodes(k) + c);
    volume(e) = solidStiffness(type(e), x, lambda(e), mu(e), &Ke(matrixStart(e)));
  }
};

/// Gather into the CSR rows of node a: sum over the elements around a of their blocks
/// (a, b). Each node row is written by one iteration only: no atomics needed.
struct GatherRowsKernel {
  Unmanaged<const LO> adjacencyPtr, adjacentElement, adjacentVertex;  // node -> (element, local vertex)
  Unmanaged<const LO> nodes, nodeStart;
  Unmanaged<const size_t> matrixStart;
  Unmanaged<const double> Ke;
  Unmanaged<const LO> nodeRowPtr, neighbour;  // sorted neighbour nodes of every node (incl. itself)
  Unmanaged<const LO> rowPtr;
  Unmanaged<double> values;

  KOKKOS_INLINE_FUNCTION LO position(const LO a, const LO b) const {
    LO lo = nodeRowPtr(a), hi = nodeRowPtr(a + 1);
    while (lo < hi) {
      const LO mid = (lo + hi) / 2;
      if (neighbour(mid) < b) lo = mid + 1;
      else hi = mid;
    }
    return lo - nodeRowPtr(a);
  }

  KOKKOS_INLINE_FUNCTION void operator()(const LO a) const {
    for (LO k = adjacencyPtr(a); k < adjacencyPtr(a + 1); ++k) {
      const LO e = adjacentElement(k), va = adjacentVertex(k);
      const LO count = nodeStart(e + 1) - nodeStart(e), dofs = 3 * count;
      for (LO vb = 0; vb < count; ++vb) {
        const LO pos = position(a, nodes(nodeStart(e) + vb));
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            values(rowPtr(3 * a + i) + 3 * pos + j) += Ke(matrixStart(e) + dofs * (3 * va + i) + 3 * vb + j);
      }
    }
  }
};

/// Consistent load of a constant traction on each face (paper Section 2, the Neumann part):
/// fe(9 f + 3 v + c) = area_f / 3 * p_c for the face's vertex v.
struct TractionLoadKernel {
  Unmanaged<const double> coords;     // 3 per local node
  Unmanaged<const LO> faceNodes;      // 3 per face, local node ids, face orientation kept
  double p[3];                        // traction, constant over the side set
  Unmanaged<double> fe;               // 9 per face

  KOKKOS_INLINE_FUNCTION void operator()(const LO f) const {
    double x[3][3], load[9];
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) x[v][c] = coords(3 * faceNodes(3 * f + v) + c);
    triangleTraction(x, p, load);
    for (int k = 0; k < 9; ++k) fe(9 * f + k) = load[k];
  }
};

/// Consistent load of the volume force density b of each element's block (V/4 * b per
/// vertex of a linear tetrahedron), at fe[3 nodeStart(e)].
struct VolumeForceKernel {
  Unmanaged<const double> coords;  // 3 per local node
  Unmanaged<const LO> nodes, nodeStart;
  Unmanaged<const mesh::ElementType> type;
  Unmanaged<const double> force;   // 3 per element: b of its block
  Unmanaged<double> fe;            // 3 per element node

  KOKKOS_INLINE_FUNCTION void operator()(const LO e) const {
    double x[mesh::kMaxElementNodes][3];
    for (LO k = nodeStart(e); k < nodeStart(e + 1); ++k)
      for (int c = 0; c < 3; ++c) x[k - nodeStart(e)][c] = coords(3 * nodes(k) + c);
    const double b[3] = {force(3 * e), force(3 * e + 1), force(3 * e + 2)};
    solidVolumeForce(type(e), x, b, &fe(3 * nodeStart(e)));
  }
};

template <class T>
Unmanaged<T> view(std::vector<T>& v) {
  return Unmanaged<T>(v.data(), v.size());
}
template <class T>
Unmanaged<const T> view(const std::vector<T>& v) {
  return Unmanaged<const T>(v.data(), v.size());
}
}  // namespace

namespace {
void requireConsistentArguments(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain,
                                const std::vector<Material>& materials, const Loads& loads) {
  // Programming errors of the caller (the driver sizes these from the mesh's blocks).
  if (materials.size() < static_cast<size_t>(mesh.numBlocks()))
    throw std::invalid_argument("tribos::fem::assembleSubdomain: " + std::to_string(materials.size()) +
                                " materials for " + std::to_string(mesh.numBlocks()) + " element blocks");
  if (!loads.volumeForce.empty() && loads.volumeForce.size() < static_cast<size_t>(mesh.numBlocks()))
    throw std::invalid_argument("tribos::fem::assembleSubdomain: Loads::volumeForce has " +
                                std::to_string(loads.volumeForce.size()) + " entries for " +
                                std::to_string(mesh.numBlocks()) + " element blocks (give one per block or none)");
  if (static_cast<size_t>(subdomain.localElements.size()) != subdomain.elements.size())
    throw std::invalid_argument("tribos::fem::assembleSubdomain: subdomain has " +
                                std::to_string(subdomain.elements.size()) + " elements but " +
                                std::to_string(subdomain.localElements.size()) + " local connectivities");
}

/// The subdomain's elements as the kernels read them: local coordinates, connectivity and
/// the Lame parameters per element.
struct LocalElements {
  LO numNodes = 0, numElements = 0;
  std::vector<double> coords;             ///< 3 per local node
  const mesh::Connectivity* connectivity;  ///< the subdomain's, in local node numbering
  std::vector<double> lambda, mu;
  const std::vector<LO>& nodes() const { return connectivity->flatNodes(); }
  const std::vector<LO>& nodeStart() const { return connectivity->offsets(); }
  const std::vector<mesh::ElementType>& types() const { return connectivity->types(); }
};

LocalElements localElements(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain,
                            const std::vector<Material>& materials) {
  LocalElements el;
  el.numNodes = subdomain.numNodes();
  el.numElements = static_cast<LO>(subdomain.elements.size());
  el.coords.resize(3 * static_cast<size_t>(el.numNodes));
  for (LO k = 0; k < el.numNodes; ++k)
    for (int c = 0; c < 3; ++c) el.coords[3 * k + c] = mesh.coords[subdomain.nodes[k]][c];
  el.connectivity = &subdomain.localElements;
  el.lambda.resize(el.numElements);
  el.mu.resize(el.numElements);
  for (LO e = 0; e < el.numElements; ++e) {
    const int block = mesh.blockOf(subdomain.elements[e]);
    el.lambda[e] = materials.at(block).lambda;
    el.mu[e] = materials.at(block).mu;
  }
  return el;
}

// (1) Element matrices K_e = int B^T D B (paper Section 2, Hooke's law with Lame lambda, mu),
// independent per element, into a buffer of (3 n_e)^2 values per element. An inverted element
// would give a negative-definite K_e and a meaningless K_s: the kernel skips it and the
// host reports it below, naming it as the user's mesh does (1-based id, block name).
std::vector<double> elementMatrices(const LocalElements& el, const std::vector<size_t>& matrixStart,
                                    const mesh::Mesh& mesh, const mesh::Subdomain& subdomain) {
  std::vector<double> Ke(matrixStart.back()), volume(el.numElements);
  Kokkos::parallel_for("tribos::fem::elementStiffness", Kokkos::RangePolicy<ExecSpace>(0, el.numElements),
                       ElementStiffnessKernel{view(el.coords), view(el.nodes()), view(el.nodeStart()),
                                              view(el.types()), view(el.lambda), view(el.mu), view(matrixStart),
                                              view(Ke), view(volume)});
  for (LO e = 0; e < el.numElements; ++e)
    if (!(volume[e] > 0.0)) {
      const LO global = subdomain.elements[e];
      throw core::InputError(mesh.elementLabel(global) + " is inverted or degenerate (volume " +
                             std::to_string(volume[e]) + ")");
    }
  return Ke;
}

/// Where each element's matrix starts in the buffer of step (1), and its end last.
std::vector<size_t> matrixStarts(const LocalElements& el) {
  std::vector<size_t> start(el.numElements + 1, 0);
  for (LO e = 0; e < el.numElements; ++e) {
    const size_t dofs = 3 * static_cast<size_t>(el.nodeStart()[e + 1] - el.nodeStart()[e]);
    start[e + 1] = start[e] + dofs * dofs;
  }
  return start;
}

/// (2) The graph on the host: node -> adjacent (element, local vertex), by counting sort so
/// the elements around a node are in ascending order (fixes the summation order of step 3),
/// and node -> sorted neighbour nodes (itself included).
struct NodeGraph {
  std::vector<LO> adjacencyPtr, adjacentElement, adjacentVertex;
  std::vector<LO> nodeRowPtr, neighbour;
};

NodeGraph nodeGraph(const mesh::Connectivity& elements, LO numNodes) {
  NodeGraph g;
  const std::vector<LO>& all = elements.flatNodes();
  g.adjacencyPtr.assign(numNodes + 1, 0);
  g.adjacentElement.resize(all.size());
  g.adjacentVertex.resize(all.size());
  for (LO t : all) g.adjacencyPtr[t + 1]++;
  for (LO a = 0; a < numNodes; ++a) g.adjacencyPtr[a + 1] += g.adjacencyPtr[a];
  std::vector<LO> fill(g.adjacencyPtr.begin(), g.adjacencyPtr.end() - 1);
  for (LO e = 0; e < elements.size(); ++e) {
    const mesh::ElementNodes nodes = elements.nodes(e);
    for (int v = 0; v < nodes.size(); ++v) {
      const LO k = fill[nodes[v]]++;
      g.adjacentElement[k] = e;
      g.adjacentVertex[k] = v;
    }
  }
  g.nodeRowPtr.assign(numNodes + 1, 0);
  g.neighbour.reserve(16 * static_cast<size_t>(numNodes));
  std::vector<LO> scratch;
  for (LO a = 0; a < numNodes; ++a) {
    scratch.clear();
    for (LO k = g.adjacencyPtr[a]; k < g.adjacencyPtr[a + 1]; ++k)
      for (LO n : elements.nodes(g.adjacentElement[k])) scratch.push_back(n);
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    g.neighbour.insert(g.neighbour.end(), scratch.begin(), scratch.end());
    g.nodeRowPtr[a + 1] = static_cast<LO>(g.neighbour.size());
  }
  return g;
}

/// K's pattern from the graph: every node pair that shares an element gets a dense 3x3
/// block, so row 3a+i lists 3*neighbour+j in ascending order; the values zero.
void stiffnessPattern(const NodeGraph& g, LO numNodes, CsrMatrix& K) {
  K.n = 3 * numNodes;
  K.rowPtr.assign(K.n + 1, 0);
  for (LO a = 0; a < numNodes; ++a) {
    const LO degree = g.nodeRowPtr[a + 1] - g.nodeRowPtr[a];
    for (int i = 0; i < 3; ++i) K.rowPtr[3 * a + i + 1] = K.rowPtr[3 * a + i] + 3 * degree;
  }
  K.colInd.resize(K.rowPtr[K.n]);
  for (LO a = 0; a < numNodes; ++a)
    for (int i = 0; i < 3; ++i) {
      LO k = K.rowPtr[3 * a + i];
      for (LO p = g.nodeRowPtr[a]; p < g.nodeRowPtr[a + 1]; ++p)
        for (int j = 0; j < 3; ++j) K.colInd[k++] = 3 * g.neighbour[p] + j;
    }
  K.values.assign(K.colInd.size(), 0.0);
}

/// The traction and pressure on quadrilaterals and 6-node triangles (local node ids), by
/// quadrature over each face, into f.
void addOtherFaceLoads(const std::vector<mesh::FaceNodes>& faces, const LocalElements& el, const Traction& traction,
                       std::vector<double>& f) {
  for (const auto& face : faces) {
    double x[mesh::kMaxFaceNodes][3], fe[3 * mesh::kMaxFaceNodes];
    for (int k = 0; k < face.numNodes; ++k)
      for (int c = 0; c < 3; ++c) x[k][c] = el.coords[3 * face.node[k] + c];
    faceLoad(mesh::faceType(face.numVertices, face.numNodes), x, traction.p.data(), traction.pressure, fe);
    for (int k = 0; k < face.numNodes; ++k)
      for (int c = 0; c < 3; ++c) f[3 * face.node[k] + c] += fe[3 * k + c];
  }
}

/// The traction and pressure loads of the faces whose element lies in this subdomain, into f
/// (each face is loaded once over all subdomains, so the subdomain loads sum to the global
/// one). A pressure q on a face of outward normal n and area A loads each vertex with
/// -q n A / 3 (the consistent load of the constant traction -q n).
void addTractionLoads(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain, const LocalElements& el,
                      const Loads& loads, std::vector<double>& f) {
  for (const auto& traction : loads.tractions) {
    const auto& set = mesh.sideSet(traction.sideSet);  // InputError naming a missing set
    std::vector<LO> faceNodes;
    std::vector<std::array<double, 3>> faceNormals;  // outward, of length twice the area
    std::vector<mesh::FaceNodes> otherFaces;          // quadrilaterals and 6-node triangles
    const auto local = [&](LO n) {
      return static_cast<LO>(std::lower_bound(subdomain.nodes.begin(), subdomain.nodes.end(), n) -
                             subdomain.nodes.begin());
    };
    for (size_t face = 0; face < set.elements.size(); ++face) {
      if (!std::binary_search(subdomain.elements.begin(), subdomain.elements.end(), set.elements[face])) continue;
      mesh::FaceNodes nodes = mesh.faceNodes(set.elements[face], set.sides[face]);
      for (LO& n : nodes.node) n = local(n);
      if (nodes.numNodes != 3) {
        otherFaces.push_back(nodes);
        continue;
      }
      if (traction.pressure != 0.0) faceNormals.push_back(mesh.faceNormal(set.elements[face], set.sides[face]));
      faceNodes.insert(faceNodes.end(), nodes.begin(), nodes.end());
    }
    const LO numFaces = static_cast<LO>(faceNodes.size() / 3);
    std::vector<double> fe(9 * static_cast<size_t>(numFaces));
    TractionLoadKernel kernel{view(std::as_const(el.coords)), view(std::as_const(faceNodes)), {}, view(fe)};
    for (int c = 0; c < 3; ++c) kernel.p[c] = traction.p[c];
    Kokkos::parallel_for("tribos::fem::tractionLoads", Kokkos::RangePolicy<ExecSpace>(0, numFaces), kernel);
    for (LO face = 0; face < numFaces; ++face)
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) f[3 * faceNodes[3 * face + v] + c] += fe[9 * face + 3 * v + c];
    for (size_t face = 0; face < faceNormals.size(); ++face)
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) f[3 * faceNodes[3 * face + v] + c] -= traction.pressure * faceNormals[face][c] / 6.0;
    addOtherFaceLoads(otherFaces, el, traction, f);
  }
}

/// The volume forces of the subdomain's elements, into f.
void addVolumeForces(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain, const LocalElements& el,
                     const Loads& loads, std::vector<double>& f) {
  if (loads.volumeForce.empty()) return;
  const LO numElements = el.numElements;
  const std::vector<LO>& nodes = el.nodes();
  std::vector<double> force(3 * static_cast<size_t>(numElements)), fe(3 * nodes.size());
  for (LO e = 0; e < numElements; ++e)
    for (int c = 0; c < 3; ++c) force[3 * e + c] = loads.volumeForce[mesh.blockOf(subdomain.elements[e])][c];
  Kokkos::parallel_for("tribos::fem::volumeForceLoads", Kokkos::RangePolicy<ExecSpace>(0, numElements),
                       VolumeForceKernel{view(std::as_const(el.coords)), view(nodes), view(el.nodeStart()),
                                         view(el.types()), view(std::as_const(force)), view(fe)});
  for (size_t k = 0; k < nodes.size(); ++k)
    for (int c = 0; c < 3; ++c) f[3 * nodes[k] + c] += fe[3 * k + c];
}
}  // namespace

std::vector<double> assembleSubdomainLoads(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain,
                                           const std::vector<Material>& materials, const Loads& loads) {
  requireConsistentArguments(mesh, subdomain, materials, loads);
  LocalElements el = localElements(mesh, subdomain, materials);
  std::vector<double> f(3 * static_cast<size_t>(el.numNodes), 0.0);
  addTractionLoads(mesh, subdomain, el, loads, f);
  addVolumeForces(mesh, subdomain, el, loads, f);
  return f;
}

SubdomainSystem assembleSubdomain(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain,
                                  const std::vector<Material>& materials, const Loads& loads) {
  requireConsistentArguments(mesh, subdomain, materials, loads);
  LocalElements el = localElements(mesh, subdomain, materials);
  const std::vector<size_t> matrixStart = matrixStarts(el);
  std::vector<double> Ke = elementMatrices(el, matrixStart, mesh, subdomain);  // (1)
  NodeGraph graph = nodeGraph(subdomain.localElements, el.numNodes);  // (2)
  SubdomainSystem system;
  CsrMatrix& K = system.K;
  stiffnessPattern(graph, el.numNodes, K);
  // (3) Race-free gather: iteration a owns the 3 rows of node a and sums the blocks (a, b)
  // of the elements around a. No two iterations write the same entry, so no atomics are
  // needed and the result is the same (bitwise) on any back end and any thread count.
  Kokkos::parallel_for("tribos::fem::gatherStiffnessRows", Kokkos::RangePolicy<ExecSpace>(0, el.numNodes),
                       GatherRowsKernel{view(graph.adjacencyPtr), view(graph.adjacentElement),
                                        view(graph.adjacentVertex), view(el.nodes()), view(el.nodeStart()),
                                        view(matrixStart), view(std::as_const(Ke)), view(graph.nodeRowPtr),
                                        view(graph.neighbour), view(K.rowPtr), view(K.values)});
  // (4) Loads f_s: element/face contributions in kernels, then summed on the host in a
  // fixed order (load by load, face by face), so f_s does not depend on the thread count.
  system.f.assign(K.n, 0.0);
  addTractionLoads(mesh, subdomain, el, loads, system.f);
  addVolumeForces(mesh, subdomain, el, loads, system.f);
  // (5) Rigid body modes of the floating subdomain.
  std::vector<std::array<double, 3>> local(el.numNodes);
  for (LO k = 0; k < el.numNodes; ++k) local[k] = mesh.coords[subdomain.nodes[k]];
  system.R = rigidBodyModes(local);
  return system;
}

SubdomainSystem assembleGlobal(const mesh::Mesh& mesh, const std::vector<Material>& materials, const Loads& loads) {
  // The whole mesh as one "subdomain": all elements, all nodes (global numbering).
  mesh::Subdomain all;
  all.body = 0;
  all.elements.resize(mesh.numElements());
  for (LO e = 0; e < mesh.numElements(); ++e) all.elements[e] = e;
  all.nodes.resize(mesh.numNodes());
  for (LO n = 0; n < mesh.numNodes(); ++n) all.nodes[n] = n;
  all.localElements = mesh.elements;
  return assembleSubdomain(mesh, all, materials, loads);
}

}  // namespace tribos::fem
