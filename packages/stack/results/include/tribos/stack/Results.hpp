#pragma once
/// \file Results.hpp
/// What an analyst reads off a solution, on the user's global mesh (rank 0, after the
/// displacement and the reactions are gathered): element and nodal stresses, the strain
/// energy, the reaction force of every displacement condition and the force balance of the
/// whole system (doc/theory.md, "Results").
#include <array>
#include <string>
#include <vector>

#include "tribos/stack/Scene.hpp"

namespace tribos::stack {

/// Stress component order of every stress field, as in fem::tetStress.
inline constexpr const char* kStressComponents[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};

struct StressResults {
  /// Cauchy stress per element (constant in a linear tetrahedron; otherwise its mean over the
  /// element, weighted by det J at the quadrature points), components kStressComponents.
  std::array<std::vector<double>, 6> element;
  std::vector<double> elementVonMises;
  /// Per node, within the node's body (stresses jump across bodies; a node shared by two
  /// bodies shows the first body's): where the elements around it are linear, the stress of
  /// the displacement gradient recovered at the node by a quadratic fit over a patch
  /// (PatchRecovery.hpp); elsewhere (10-node tetrahedra) the volume-weighted mean of each
  /// element's stress extrapolated to the node from its quadrature points
  /// (fem::ElementStress::atNodes: their strain is linear, exact at the node). Von Mises is
  /// that of the nodal tensor.
  std::array<std::vector<double>, 6> nodal;
  std::vector<double> nodalVonMises;
  double strainEnergy = 0.0;  ///< u^T K u / 2 = sum over elements of V sigma:eps / 2
};

/// Stresses from the displacement of every global node, each element with the material of
/// its block (scene.materials).
StressResults evaluateStresses(const Scene& scene, const std::vector<std::array<double, 3>>& displacement);

struct ConditionReaction {
  std::string name;              ///< the Dirichlet node set, or the Boundary/<name> sublist
  std::array<double, 3> force{};  ///< sum over the set's nodes of the reactions of its components
};

struct ForceBalance {
  /// Per Dirichlet node set, then per displacement condition. A component prescribed by two
  /// conditions at one node counts in both, so these need not add up to totalReaction.
  std::vector<ConditionReaction> reactions;
  std::array<double, 3> totalReaction{};  ///< every prescribed component once
  std::array<double, 3> appliedLoad{};    ///< sum of the nodal loads f
  /// |totalReaction + appliedLoad| / scale (contact forces are internal and cancel), the
  /// scale the largest of |appliedLoad|, the sum of the nodal loads' lengths and the sum of
  /// the nodal reactions' lengths: not zero when the loads cancel (opposite pressures) or
  /// vanish (prescribed displacements only).
  double relativeImbalance = 0.0;
};

/// Reactions per condition and the balance, from the nodal reactions (gatherReactions) and
/// the applied load (totalLoad).
ForceBalance forceBalance(const Scene& scene, const std::vector<std::array<double, 3>>& nodalReaction,
                          const std::array<double, 3>& appliedLoad, double appliedLoadMagnitude);

}  // namespace tribos::stack
