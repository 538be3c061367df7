#pragma once
/// \file PenetrationCheck.hpp
/// The check after the last solve (issue 41): no slave node inside a master body. The contact
/// rows are decided before the solve, from the reference mesh; a node they do not hold (out of
/// reach then, or slid off the master faces of its row) may end inside the master body with
/// exit 0 and no warning. Here every slave node of every non-bonded interface is projected
/// on its master surface with both moved by the displacement
/// (geometry::MasterSurface::pairingProjection, inside the body only); a node whose row still
/// holds it (the closest master face has a node of its row) is the solver's, checked by the
/// KKT conditions; any other node deeper than the tolerance makes the run not converged.
#include <array>
#include <string>
#include <vector>

#include "tribos/stack/Scene.hpp"

namespace tribos::feti {
struct ConstraintMatrix;
}

namespace tribos::stack {

/// A node that is not held is inside when deeper than this fraction of the master face it is
/// found under (1e-3 h: round-off and the facets' sag on a gently curved surface stay below).
inline constexpr double kPenetrationTolerance = 1e-3;

struct Penetration {
  std::string interface;  ///< its label, "Contact/<name> (slave -> master)"
  LO node = -1;           ///< the deepest node (global id)
  double depth = 0.0;     ///< how far inside, the mesh's units
  double tolerance = 0.0; ///< the depth allowed there
  GO nodes = 0;           ///< nodes of the interface deeper than their tolerance
  bool heldByRow = false; ///< false: no row holds it (unpaired, or slid off its row's faces)
};

/// The penetrations of the interfaces (one entry per interface with nodes beyond the tolerance)
/// in the displaced configuration `u` (per global node).
std::vector<Penetration> penetrationsAfterSolve(const Scene& scene, const feti::ConstraintMatrix& B,
                                                const std::vector<std::array<double, 3>>& u);

/// "contact check after the solve: slave node 12 of ... lies 0.08 inside the master body ..."
std::string describe(const Penetration& p);

}  // namespace tribos::stack
