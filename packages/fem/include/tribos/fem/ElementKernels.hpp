#pragma once
/// \file ElementKernels.hpp
/// P1 tetrahedron kernels, callable from Kokkos kernels on the host (KOKKOS_INLINE_FUNCTION)
/// and from plain C++. Dof ordering inside an element: 3*vertex + component.
#include <Kokkos_Core.hpp>

namespace tribos::fem {

/// Element stiffness K_e (12x12, row-major) of the linear tetrahedron x[4][3] with Lame
/// constants lambda, mu: K_e = V B^T D B (constant strain). Returns the signed volume V;
/// Ke is written only when V > 0.
KOKKOS_INLINE_FUNCTION double tetStiffness(const double x[4][3], double lambda, double mu,
                                           double Ke[12][12]);

/// Consistent load of a constant traction p on the triangle x[3][3]: each vertex gets
/// area/3 * p (fe[3*vertex + component]). Returns the area.
KOKKOS_INLINE_FUNCTION double triangleTraction(const double x[3][3], const double p[3], double fe[9]);

/// Consistent load of a constant volume force density b on the tetrahedron: each vertex
/// gets V/4 * b. Returns the signed volume.
KOKKOS_INLINE_FUNCTION double tetVolumeForce(const double x[4][3], const double b[3], double fe[12]);

/// Constant strain and Cauchy stress of the linear tetrahedron with nodal displacements
/// u[3*vertex + component] (Hooke: sigma = lambda tr(eps) I + 2 mu eps). Both in the order
/// xx, yy, zz, xy, yz, xz as tensor components (eps_xy = (du_x/dy + du_y/dx) / 2, not the
/// engineering shear). Returns the signed volume; eps and sigma are written only when V > 0.
KOKKOS_INLINE_FUNCTION double tetStress(const double x[4][3], const double u[12], double lambda, double mu,
                                        double eps[6], double sigma[6]);

/// von Mises equivalent stress sqrt(3 J2) of sigma (order as in tetStress).
KOKKOS_INLINE_FUNCTION double vonMisesStress(const double sigma[6]);

/// Strain energy density sigma : eps / 2 (tensor components, order as in tetStress): the
/// element's strain energy is V times this, and the sum over elements is u^T K u / 2.
KOKKOS_INLINE_FUNCTION double strainEnergyDensity(const double eps[6], const double sigma[6]);

}  // namespace tribos::fem

#include "tribos/fem/ElementKernels_impl.hpp"
