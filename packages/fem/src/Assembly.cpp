// Per-subdomain assembly of K_s and f_s (paper Section 4.1) as Kokkos kernels.
//
// Thread safety (TOOLCHAIN.md): assembleSubdomain runs concurrently for different
// subdomains on OpenMP threads with Debian's Serial-only Kokkos, so it creates no managed
// View: all storage is std::vector, wrapped in unmanaged Views for the kernels, and only
// RangePolicy parallel_for is used. The scatter of element matrices is replaced by a
// race-free gather over node rows, so the kernels are also correct on a threaded back end.
#include <Kokkos_Core.hpp>

#include <algorithm>

#include "tribos/core/Errors.hpp"
#include "tribos/fem/ElementKernels.hpp"
#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::fem {

namespace {
using ExecSpace = Kokkos::Serial;
template <class T>
using Unmanaged = Kokkos::View<T*, Kokkos::HostSpace, Kokkos::MemoryTraits<Kokkos::Unmanaged>>;

/// Element matrices: Ke(e) = 12 x 12 block of element e, row-major, at Ke[144 e].
struct ElementStiffnessKernel {
  Unmanaged<const double> coords;      // 3 per local node
  Unmanaged<const LO> tets;            // 4 per element, local node ids
  Unmanaged<const double> lambda, mu;  // per element
  Unmanaged<double> Ke;                // 144 per element
  Unmanaged<double> volume;            // per element

  KOKKOS_INLINE_FUNCTION void operator()(const LO e) const {
    double x[4][3];
    for (int v = 0; v < 4; ++v)
      for (int c = 0; c < 3; ++c) x[v][c] = coords(3 * tets(4 * e + v) + c);
    double K[12][12];
    volume(e) = tetStiffness(x, lambda(e), mu(e), K);
    if (!(volume(e) > 0.0)) return;
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) Ke(144 * e + 12 * i + j) = K[i][j];
  }
};

/// Gather into the CSR rows of node a: sum over the elements around a of their blocks
/// (a, b). Each node row is written by one iteration only: no atomics needed.
struct GatherRowsKernel {
  Unmanaged<const LO> adjacencyPtr, adjacentElement, adjacentVertex;  // node -> (element, local vertex)
  Unmanaged<const LO> tets;
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
      for (int vb = 0; vb < 4; ++vb) {
        const LO pos = position(a, tets(4 * e + vb));
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            values(rowPtr(3 * a + i) + 3 * pos + j) += Ke(144 * e + 12 * (3 * va + i) + 3 * vb + j);
      }
    }
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

SubdomainSystem assembleSubdomain(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain,
                                  const std::vector<Material>& materials, const Loads& loads) {
  const LO numNodes = subdomain.numNodes(), numElements = static_cast<LO>(subdomain.elements.size());
  std::vector<double> coords(3 * static_cast<size_t>(numNodes));
  for (LO k = 0; k < numNodes; ++k)
    for (int c = 0; c < 3; ++c) coords[3 * k + c] = mesh.coords[subdomain.nodes[k]][c];
  std::vector<LO> tets(4 * static_cast<size_t>(numElements));
  std::vector<double> lambda(numElements), mu(numElements);
  for (LO e = 0; e < numElements; ++e) {
    for (int v = 0; v < 4; ++v) tets[4 * e + v] = subdomain.tets[e][v];
    const int block = mesh.blockOf(subdomain.elements[e]);
    lambda[e] = materials.at(block).lambda;
    mu[e] = materials.at(block).mu;
  }

  // (1) Element matrices in parallel over elements.
  std::vector<double> Ke(144 * static_cast<size_t>(numElements)), volume(numElements);
  Kokkos::parallel_for("tribos::fem::elementStiffness", Kokkos::RangePolicy<ExecSpace>(0, numElements),
                       ElementStiffnessKernel{view(coords), view(tets), view(lambda), view(mu), view(Ke), view(volume)});
  for (LO e = 0; e < numElements; ++e)
    if (!(volume[e] > 0.0)) {
      const LO global = subdomain.elements[e];
      throw core::InputError("element " + std::to_string(global + 1) + " of block \"" +
                             mesh.blocks[mesh.blockOf(global)].name + "\" is inverted or degenerate (volume " +
                             std::to_string(volume[e]) + ")");
    }

  // (2) Graph on the host: node -> adjacent (element, vertex); node -> neighbour nodes.
  std::vector<LO> adjacencyPtr(numNodes + 1, 0), adjacentElement(4 * static_cast<size_t>(numElements)),
      adjacentVertex(4 * static_cast<size_t>(numElements));
  for (LO t : tets) adjacencyPtr[t + 1]++;
  for (LO a = 0; a < numNodes; ++a) adjacencyPtr[a + 1] += adjacencyPtr[a];
  {
    std::vector<LO> fill(adjacencyPtr.begin(), adjacencyPtr.end() - 1);
    for (LO e = 0; e < numElements; ++e)
      for (int v = 0; v < 4; ++v) {
        const LO k = fill[tets[4 * e + v]]++;
        adjacentElement[k] = e;
        adjacentVertex[k] = v;
      }
  }
  std::vector<LO> nodeRowPtr(numNodes + 1, 0), neighbour;
  neighbour.reserve(16 * static_cast<size_t>(numNodes));
  std::vector<LO> scratch;
  for (LO a = 0; a < numNodes; ++a) {
    scratch.clear();
    for (LO k = adjacencyPtr[a]; k < adjacencyPtr[a + 1]; ++k)
      for (int v = 0; v < 4; ++v) scratch.push_back(tets[4 * adjacentElement[k] + v]);
    std::sort(scratch.begin(), scratch.end());
    scratch.erase(std::unique(scratch.begin(), scratch.end()), scratch.end());
    neighbour.insert(neighbour.end(), scratch.begin(), scratch.end());
    nodeRowPtr[a + 1] = static_cast<LO>(neighbour.size());
  }
  SubdomainSystem system;
  CsrMatrix& K = system.K;
  K.n = 3 * numNodes;
  K.rowPtr.assign(K.n + 1, 0);
  for (LO a = 0; a < numNodes; ++a) {
    const LO degree = nodeRowPtr[a + 1] - nodeRowPtr[a];
    for (int i = 0; i < 3; ++i) K.rowPtr[3 * a + i + 1] = K.rowPtr[3 * a + i] + 3 * degree;
  }
  K.colInd.resize(K.rowPtr[K.n]);
  for (LO a = 0; a < numNodes; ++a)
    for (int i = 0; i < 3; ++i) {
      LO k = K.rowPtr[3 * a + i];
      for (LO p = nodeRowPtr[a]; p < nodeRowPtr[a + 1]; ++p)
        for (int j = 0; j < 3; ++j) K.colInd[k++] = 3 * neighbour[p] + j;
    }
  K.values.assign(K.colInd.size(), 0.0);

  // (3) Race-free gather into CSR rows, in parallel over nodes.
  Kokkos::parallel_for("tribos::fem::gatherStiffnessRows", Kokkos::RangePolicy<ExecSpace>(0, numNodes),
                       GatherRowsKernel{view(adjacencyPtr), view(adjacentElement), view(adjacentVertex), view(tets),
                                        view(Ke), view(nodeRowPtr), view(neighbour), view(K.rowPtr),
                                        view(K.values)});

  // (4) Loads: face / element contributions computed in a kernel, summed sequentially (in
  // a fixed order, so f_s does not depend on the thread count).
  system.f.assign(K.n, 0.0);
  for (const auto& traction : loads.tractions) {
    const auto& set = mesh.sideSet(traction.sideSet);
    std::vector<LO> faceNodes;
    for (size_t f = 0; f < set.elements.size(); ++f) {
      if (!std::binary_search(subdomain.elements.begin(), subdomain.elements.end(), set.elements[f])) continue;
      const auto& tet = mesh.tets[set.elements[f]];
      for (int v : mesh::kTetFaceVertices[set.sides[f]])
        faceNodes.push_back(static_cast<LO>(
            std::lower_bound(subdomain.nodes.begin(), subdomain.nodes.end(), tet[v]) - subdomain.nodes.begin()));
    }
    const LO numFaces = static_cast<LO>(faceNodes.size() / 3);
    std::vector<double> fe(9 * static_cast<size_t>(numFaces));
    const auto faceView = view(static_cast<const std::vector<LO>&>(faceNodes));
    const auto coordView = view(static_cast<const std::vector<double>&>(coords));
    const auto feView = view(fe);
    const double p[3] = {traction.p[0], traction.p[1], traction.p[2]};
    Kokkos::parallel_for(
        "tribos::fem::tractionLoads", Kokkos::RangePolicy<ExecSpace>(0, numFaces), KOKKOS_LAMBDA(const LO f) {
          double x[3][3], load[9];
          for (int v = 0; v < 3; ++v)
            for (int c = 0; c < 3; ++c) x[v][c] = coordView(3 * faceView(3 * f + v) + c);
          const double pc[3] = {p[0], p[1], p[2]};
          triangleTraction(x, pc, load);
          for (int k = 0; k < 9; ++k) feView(9 * f + k) = load[k];
        });
    for (LO f = 0; f < numFaces; ++f)
      for (int v = 0; v < 3; ++v)
        for (int c = 0; c < 3; ++c) system.f[3 * faceNodes[3 * f + v] + c] += fe[9 * f + 3 * v + c];
  }
  if (!loads.volumeForce.empty()) {
    for (LO e = 0; e < numElements; ++e) {
      const auto& b = loads.volumeForce.at(mesh.blockOf(subdomain.elements[e]));
      double x[4][3], fe[12];
      for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) x[v][c] = coords[3 * tets[4 * e + v] + c];
      const double bc[3] = {b[0], b[1], b[2]};
      tetVolumeForce(x, bc, fe);
      for (int v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) system.f[3 * tets[4 * e + v] + c] += fe[3 * v + c];
    }
  }

  // (5) Rigid body modes of the floating subdomain.
  std::vector<std::array<double, 3>> local(numNodes);
  for (LO k = 0; k < numNodes; ++k) local[k] = mesh.coords[subdomain.nodes[k]];
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
  all.tets = mesh.tets;
  return assembleSubdomain(mesh, all, materials, loads);
}

}  // namespace tribos::fem
