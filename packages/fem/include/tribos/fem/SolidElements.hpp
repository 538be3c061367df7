#pragma once
/// \file SolidElements.hpp
/// Element kernels of every element type (mesh/ElementTypes.hpp), by numerical integration
/// over mesh::volumeRule and mesh::faceRule. The linear tetrahedron goes to the closed forms
/// of ElementKernels.hpp, so its results keep their bits. Dof ordering inside an element:
/// 3*node + component. Plain C++ (no Kokkos types), callable inside the assembly kernels.
#include "tribos/mesh/ShapeFunctions.hpp"

namespace tribos::fem {

/// Largest element matrix: a 10-node tetrahedron's 30 x 30.
inline constexpr int kMaxElementDofs = 3 * mesh::kMaxElementNodes;

/// K_e = sum_q w_q det J_q B_q^T D B_q (Hooke, Lame lambda and mu), row-major with
/// 3 * numNodes columns. Returns the volume; Ke is written only when det J > 0 at every
/// quadrature point (else the returned value is not positive: the smallest det J times the
/// reference volume, or the volume if that is smaller).
double solidStiffness(mesh::ElementType type, const double (*x)[3], double lambda, double mu, double* Ke);

/// The consistent load of a constant volume force density b: fe[3 k + c] = b_c int N_k.
/// Returns the volume.
double solidVolumeForce(mesh::ElementType type, const double (*x)[3], const double b[3], double* fe);

/// The strains and stresses of an element under nodal displacements u[3 k + c]: their means
/// over the element (weighted by det J at the quadrature points) and the strain energy
/// int sigma : eps / 2, exact for the element's displacement field. Tensor components
/// xx, yy, zz, xy, yz, xz as in tetStress.
struct ElementStress {
  double volume = 0.0;
  double eps[6] = {0, 0, 0, 0, 0, 0};
  double sigma[6] = {0, 0, 0, 0, 0, 0};
  double strainEnergy = 0.0;
  /// The stress at each node of the element, extrapolated from the quadrature points
  /// (mesh::nodalExtrapolation): varying within the element where the rule has more than one point.
  double atNodes[mesh::kMaxElementNodes][6] = {};
};
ElementStress solidStress(mesh::ElementType type, const double (*x)[3], const double* u, double lambda, double mu);

/// The consistent load on a face of `numNodes` nodes x (vertices first, as mesh::FaceNodes)
/// of a constant traction p plus a pressure q along the inward normal (positive in
/// compression): fe[3 k + c] = int N_k (p - q n)_c. Returns the face's area.
double faceLoad(mesh::FaceType type, const double (*x)[3], const double p[3], double pressure, double* fe);

}  // namespace tribos::fem
