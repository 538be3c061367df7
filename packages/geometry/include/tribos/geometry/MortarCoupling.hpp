#pragma once
/// \file MortarCoupling.hpp
/// Dual mortar coupling of the slave nodes to the master surface (Wohlmuth's biorthogonal
/// multipliers), the default contact discretisation for non-matching meshes.
///
/// Why: the node-to-surface rows (ContactSearch.hpp: the slave node against the master
/// displacement interpolated at its projection) do not pass the contact patch test on
/// non-matching meshes; measured on the Hertz scenes here, the nodal pressure oscillates by
/// +-6 % (line contact) and +-15 % (point contact) around Hertz's and does not settle under
/// refinement. The mortar rows weigh the master nodes by integrals over the slave surface,
/// which removes that oscillation while keeping one row per slave node and direction:
///   row of slave node i:  u_i - sum_j w_ij u_j,   w_ij = M_ij / D_i,
///   D_i  = int_Gamma_s phi_i,        (the slave node's tributary area)
///   M_ij = int_Gamma_s psi_i (phi_j o chi),
/// with phi_i the slave surface's P1 hat function, psi_i = 4 phi_i - 1 on each slave
/// triangle its dual (int psi_i phi_k = delta_ik int phi_k), on a slave quadrilateral the
/// bilinear phi_i and psi = D M^{-1} phi per face (D, M its lumped and consistent mass
/// matrices: the bilinear dual basis, ALGORITHMS.md 12), on a 6-node slave triangle the dual
/// of the transformed quadratic basis of Popp, Wohlmuth, Gee & Wall (2012) (alpha = 1/5; the
/// rows of its mid-edge nodes then hold their edge's ends too), phi_j the master shape functions
/// evaluated at the projection chi of the slave point on the master surface. Since
/// sum_j phi_j = 1, sum_j M_ij = int psi_i = D_i: the weights sum to one, as the
/// node-to-surface weights do; some may be negative. The initial gap is weighted the same
/// way, d_i = (int psi_i (chi(x) - x) dGamma / D_i) . nu_i, and kept within the range of the
/// pointwise gap (chi(x) - x) . nu_i over the node's support: psi_i < 0 on part of it, so
/// where the gap varies much within one slave element (a master curving away, a fillet of
/// 1.5 slave elements) the weighted gap could be an overlap where the surfaces are apart.
///
/// The integrals are segment-based (MortarSegments.hpp): the master faces are mapped onto each
/// slave face and clipped there, and on a slave face whose nodes' contact normals differ (a
/// curved surface) the master nodes are mapped, and the segment points projected, along the
/// normals interpolated over the face (Popp et al. 2010; MortarNormalProjection.hpp), which on
/// a faceted fit puts a master vertex's image on the slave vertex facing it. Where the segments
/// cannot be formed the integrals are evaluated by quadrature on the slave faces (a triangle cut into
/// kSubdivisions^2 sub-triangles, 3-point rule exact for quadratics on each; a quadrilateral
/// into kSubdivisions^2 sub-squares of its reference square, 2 x 2 Gauss points each), projecting
/// every quadrature point on the master surface — element-based integration, without
/// clipping the slave and master triangles against each other. Exact when a slave triangle
/// lies inside one master triangle (matching meshes: w_ij = delta_ij to round-off, snapped to
/// exactly node-to-node); otherwise the kinks of phi_j inside a slave triangle are resolved
/// to the sub-triangle size.
///
/// An interface where every slave node projects onto a master vertex (matching nodes, also
/// across a gap) keeps the node-to-node rows: the paper's discretisation, also where the two
/// sides' triangles are cut along different diagonals (the two-brick generator alternates
/// them), where the mortar rows would spread over the neighbouring master nodes.
///
/// A slave node whose support is only partly over the master surface (some quadrature
/// points find no master face within the search distance, e.g. at the edge of the master
/// surface) keeps its node-to-surface row: the dual weights need the whole support.
#include <string>
#include <vector>

#include "tribos/geometry/ContactSearch.hpp"

namespace tribos::geometry {

/// The transformation of the 6-node triangle's basis for its dual basis (Popp, Wohlmuth, Gee &
/// Wall 2012): phi~_v = phi_v + alpha (phi_m + phi_m') at a vertex v (m, m' its edges' mid
/// nodes), phi~_m = (1 - 2 alpha) phi_m at a mid-edge node.
inline constexpr double kQuadraticTransformAlpha = 0.2;

/// The master side of one slave node's rows, and on a 6-node triangle the slave side of a
/// mid-edge node's row: s_i u_i + sum_k s_ik u_k - sum_j w_ij u_j (times the direction)
/// against d_i. That is the slave displacement's coefficient of the transformed basis,
/// u~_m = (u_m - alpha (u_a + u_b)) / (1 - 2 alpha), against the master's interpolation.
struct MortarRow {
  std::vector<LO> masterNodes;   ///< ascending
  std::vector<double> weights;   ///< w_ij, sum 1
  double slaveWeight = 1.0;      ///< s_i: 1, or 1 / (1 - 2 alpha) at a 6-node triangle's mid-edge node
  /// A mid-edge node of a 6-node slave triangle: the ends of its edge, with s_ik = -alpha /
  /// (1 - 2 alpha); empty otherwise. s_i + sum_k s_ik = 1.
  std::vector<LO> slaveNodes;
  std::vector<double> slaveWeights;
  double gap = 0.0;              ///< d_i along the pair's normal (< 0: initial overlap)
  bool nodeToSurface = false;    ///< the node kept its node-to-surface row (header)
  /// How far the weighted gap left the range of the pointwise gap over the node's support
  /// (it is kept at its edge; 0 where it did not): the slave elements are coarse for the
  /// master's curvature there.
  double gapLimited = 0.0;
  /// How far the master's smoothed surface (SmoothedFaces.hpp) lies from its face along the
  /// normal at the node's projection: the facets' sag there if the surface is meant to be curved
  /// (measured whatever Contact/Surface Geometry says; 0 on flat masters and at master vertices).
  double facetSag = 0.0;
};

/// One row per pair of `search` (same order). `master` must be built on the master set
/// of the search; `searchDistance` as there. `unsettledProjections`, if given, is increased by
/// the quadrature points whose projection on a curved master face did not settle
/// (FaceProjection.hpp). `smoothedGeometry`: the gaps are measured between the smoothed
/// surfaces of the linear faces (Contact/Surface Geometry = Smoothed; Nagata's curved faces from
/// the nodal normals, geometry/SmoothedFaces.hpp), with the slave's nodal normals in the
/// symmetry planes of `held`.
std::vector<MortarRow> dualMortarRows(const mesh::Mesh& mesh, const std::string& slaveSideSet,
                                      const MasterSurface& master, const ContactSearchResult& search,
                                      double searchDistance, long long* unsettledProjections = nullptr,
                                      bool smoothedGeometry = false, const HeldAxes& held = {});

/// True if every pair's projection is a master vertex (weights a unit vector).
bool projectsOnMasterVertices(const ContactSearchResult& search);

/// The node-to-surface row of a pair (its projection's vertices and weights, zeros dropped).
MortarRow nodeToSurfaceRow(const ContactPair& pair);

}  // namespace tribos::geometry
