#pragma once
/// \file MortarSegments.hpp
/// Segment-based integration of the mortar integrals on one slave face (private to the
/// package; Puso & Laursen 2004, Popp et al. 2010): the master faces over the slave face are
/// mapped into its reference domain, each clipped against it, and every clipped polygon is
/// integrated with a rule exact for quartics on the triangles it is cut into. The master shape
/// functions are then smooth inside every piece, their kinks on its edges: on flat faces
/// (affine geometry) M_ij is exact to round-off for every pair of 3-node, 4-node (parallelogram)
/// and 6-node faces, and a uniform pressure is transferred exactly (the contact patch test). The
/// element-based rule of MortarQuadrature.hpp resolves the kinks only to a sixth of the slave
/// element (a patch-test error of 1e-3).
///
/// How the master faces are found: from the faces on which the slave face's nodes and centre
/// project, then outwards through neighbouring faces (sharing a node) as long as their images
/// meet the slave face. A master face is mapped node by node of its outline onto the slave
/// face, extended beyond its edges: along the slave's normal field where the face's contact
/// normals differ (a curved or faceted-curved surface), by closest points where they are all
/// alike (a flat face; MortarNormalProjection.hpp says why); a face that turns
/// its back to the slave face there (its image has the slave face's orientation: the far side
/// of a curved master) does not cover it. Where the images overlap (a master folded over itself
/// in projection) or a node cannot be mapped, the face is reported unusable and the caller keeps
/// the element-based rule for it. So does the caller where a point's closest master point is on
/// another face than the one whose image holds it (a master curving away from the slave surface
/// across a gap: the images are taken along the slave's normal, the projections along the
/// master's, and a kink of the master functions would fall inside a segment). What no image covers (a sliver along the master surface's
/// edge: on a faceted cylinder whose facets are offset by an interference, the master's edge
/// projects a little inside the slave's) is left to the caller: MortarCoupling integrates it
/// with the element-based points that lie there, projected on the master as before.
#include <vector>

#include "MortarNormalProjection.hpp"
#include "MortarQuadrature.hpp"
#include "tribos/geometry/MasterSurface.hpp"

namespace tribos::geometry {

struct SegmentPoints {
  bool usable = false;             ///< false: fall back to the element-based rule (header)
  std::vector<SlavePoint> points;  ///< on the parts of the slave face master faces cover
  std::vector<LO> pointFace;       ///< per point, the master face whose image holds it
  int masterFaces = 0;             ///< master faces whose images meet the slave face
  /// The pieces, in the slave face's reference coordinates (counter-clockwise polygons).
  std::vector<std::vector<std::array<double, 2>>> pieces;
  /// True if the reference point xi lies in a piece (or on its edge).
  bool covers(const std::array<double, 2>& xi) const;
};

/// The segment quadrature of the slave face of `basis`, whose master faces are searched from
/// `seeds` (faces of `master`). The master nodes are mapped by closest points, or along the
/// slave's normal field where `field` is given (MortarNormalProjection.hpp).
SegmentPoints segmentPoints(const SlaveBasis& basis, const MasterSurface& master, const std::vector<LO>& seeds,
                            const SlaveNormalField* field = nullptr);

}  // namespace tribos::geometry
