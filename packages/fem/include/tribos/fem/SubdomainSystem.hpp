#pragma once
/// \file SubdomainSystem.hpp
/// Per-subdomain T-FETI data: the floating stiffness K_s (CSR, no Dirichlet rows), the load
/// f_s and the orthonormal rigid body modes R_s (paper Section 4.1, ALGORITHMS.md 1).
/// Storage is std::vector so that subdomains can be assembled on threads without managed
/// Kokkos Views (TOOLCHAIN.md); the kernels work on unmanaged Views over it.
#include <array>
#include <string>
#include <vector>

#include "tribos/fem/Material.hpp"
#include "tribos/mesh/Decomposition.hpp"

namespace tribos::fem {

/// Square sparse matrix, compressed rows, column indices ascending within a row.
struct CsrMatrix {
  LO n = 0;
  std::vector<LO> rowPtr;       ///< n + 1 entries
  std::vector<LO> colInd;
  std::vector<double> values;
  /// y = A x
  void apply(const double* x, double* y) const;
  double frobeniusNorm() const;
  /// Value at (i, j), 0 when not stored.
  double at(LO i, LO j) const;
};

/// Constant surface traction p on the faces of a side set, plus a pressure normal to each
/// face (positive in compression: the face is pushed along its inward normal, so a curved
/// face is pressed along its own normal everywhere).
struct Traction {
  std::string sideSet;
  std::array<double, 3> p{0, 0, 0};
  double pressure = 0.0;
};

struct Loads {
  std::vector<Traction> tractions;
  /// Volume force density per element block (index as mesh.blocks); empty = none.
  std::vector<std::array<double, 3>> volumeForce;
};

struct SubdomainSystem {
  CsrMatrix K;                 ///< 3*nodes x 3*nodes, dof = 3*localNode + component
  std::vector<double> f;       ///< load vector
  std::vector<double> R;       ///< n x 6, column-major, orthonormal columns spanning Ker K
  /// Load histories: f_s of each named load on its own (stack: Scene::namedLoads), assembled
  /// with K_s while the subdomain's elements are at hand; empty otherwise.
  std::vector<std::vector<double>> loadParts;
};

/// Assembles K_s and f_s of one subdomain with Kokkos kernels (element matrices in
/// parallel over elements, then a race-free gather into CSR rows over nodes) and builds R_s.
/// `materials[b]` is the material of element block b (at least mesh.numBlocks() entries;
/// loads.volumeForce empty or one per block, else std::invalid_argument). A traction loads
/// only the faces whose element is in the subdomain, so subdomain loads sum to the global
/// load. No Dirichlet condition is applied (T-FETI: K_s is floating, Ker K_s = span R_s).
/// Throws core::InputError if a traction names a side set the mesh lacks, or an element is
/// inverted (naming its 1-based global id and its block).
/// Safe to call concurrently for different subdomains (no managed Views inside); the result
/// does not depend on the thread count, bit for bit.
SubdomainSystem assembleSubdomain(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain,
                                  const std::vector<Material>& materials, const Loads& loads);

/// f_s alone, as assembleSubdomain computes it (the same bits), without K_s: one load of a
/// load history at a time.
std::vector<double> assembleSubdomainLoads(const mesh::Mesh& mesh, const mesh::Subdomain& subdomain,
                                           const std::vector<Material>& materials, const Loads& loads);

/// The undecomposed stiffness and load of the whole mesh (dof = 3*globalNode + component):
/// a reference for tests (sum of subdomain matrices) and for direct solves.
SubdomainSystem assembleGlobal(const mesh::Mesh& mesh, const std::vector<Material>& materials,
                               const Loads& loads);

/// Orthonormal rigid body modes (3 translations, 3 rotations about the centroid, then
/// modified Gram-Schmidt applied twice, so R^T R = I to round-off) of a set of nodes:
/// n = 3*coords.size() rows, 6 columns, col-major; dof 3*node + component as in K_s.
/// Throws std::invalid_argument if the nodes are collinear (the modes are dependent).
std::vector<double> rigidBodyModes(const std::vector<std::array<double, 3>>& coords);

}  // namespace tribos::fem
