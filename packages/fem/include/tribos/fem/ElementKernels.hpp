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

}  // namespace tribos::fem

#include "tribos/fem/ElementKernels_impl.hpp"
