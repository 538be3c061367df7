#pragma once
/// \file Material.hpp
/// Isotropic linear elasticity (Hooke's law, paper Section 2) by Lame constants.
namespace tribos::fem {

struct Material {
  double lambda = 0.0;  ///< Lame's first parameter [stress]
  double mu = 0.0;      ///< shear modulus [stress]
  /// From Young's modulus E > 0 and Poisson's ratio -1 < nu < 0.5.
  static Material fromYoungPoisson(double E, double nu) {
    return {E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), E / (2.0 * (1.0 + nu))};
  }
};

}  // namespace tribos::fem
