/// \file MortarCoupling.cpp
/// Dual mortar weights by segment-based quadrature on the slave surface (header).
#include "tribos/geometry/MortarCoupling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#include "MortarQuadrature.hpp"
#include "MortarSegments.hpp"
#include "tribos/geometry/SmoothedFaces.hpp"

namespace tribos::geometry {

namespace {
/// Tolerance for "node-to-node" (w = unit vector).
constexpr double kNodeToNodeTolerance = 1e-10;

/// The integrals of one slave node: D_i, M_ij, int psi_i (chi(x) - x), and int psi_i over
/// the covered part (sum_j M_ij); and the range of the pointwise gap (chi(x) - x) . nu_i
/// over its support.
struct NodeIntegrals {
  double D = 0.0, covered = 0.0;
  long long missed = 0;  ///< quadrature points of its support that found no master face
  std::map<LO, double> M;
  Vec3 gapVector{0.0, 0.0, 0.0};
  double gapMin = std::numeric_limits<double>::infinity(), gapMax = -std::numeric_limits<double>::infinity();
};

/// The integrals of every paired slave node, by quadrature over every slave face touching
/// one (step 1 of dualMortarRows); a 6-node triangle's mid-edge nodes are mapped to their
/// edge's ends in `edgeEnds`.
struct SlaveIntegration {
  std::vector<NodeIntegrals> integrals;            ///< per pair of the search
  std::map<LO, std::pair<LO, LO>> edgeEnds;        ///< a 6-node triangle's mid-edge node -> its edge's ends
  long long unsettledProjections = 0;              ///< quadrature points whose projection did not settle
  long long segmentBasedFaces = 0, elementBasedFaces = 0;  ///< how the slave faces were integrated
};

/// Adds one quadrature point's contributions to the integrals of the paired nodes of its face
/// (all but D_i, which the whole face's rule gives: addTributaryArea).
/// `slaveOffset` and `masterOffset` move the point and its projection onto the smoothed surfaces
/// for the gap (SmoothedFaces.hpp; zero on faceted surfaces).
void addPoint(const SlavePoint& q, const mesh::FaceNodes& face, const MasterSurface::Projection& chi,
              const Vec3& slaveOffset, const Vec3& masterOffset, const std::vector<int>& pairOf,
              const ContactSearchResult& search, SlaveIntegration& out) {
  const Vec3 xq{q.x[0] + slaveOffset[0] - masterOffset[0], q.x[1] + slaveOffset[1] - masterOffset[1],
                q.x[2] + slaveOffset[2] - masterOffset[2]};
  const double omega = q.omega;
  for (int v = 0; v < face.numNodes; ++v) {
    const int p = pairOf[face.node[v]];
    if (p < 0) continue;
    NodeIntegrals& I = out.integrals[p];
    if (chi.face < 0) {
      ++I.missed;
      continue;
    }
    const double psi = q.psi[v];  // the dual basis function of node v
    I.covered += omega * psi;
    for (int j = 0; j < kMaxMasterFaceNodes; ++j)
      if (chi.weights[j] != 0.0) I.M[chi.nodes[j]] += omega * psi * chi.weights[j];
    const Vec3 gap{chi.point[0] - xq[0], chi.point[1] - xq[1], chi.point[2] - xq[2]};
    for (int d = 0; d < 3; ++d) I.gapVector[d] += omega * psi * gap[d];
    const Vec3& nu = search.pairs[p].normal;
    const double along = gap[0] * nu[0] + gap[1] * nu[1] + gap[2] * nu[2];
    I.gapMin = std::min(I.gapMin, along);
    I.gapMax = std::max(I.gapMax, along);
  }
}

/// D_i = int phi_i of the paired nodes of a face, by the whole face's rule.
void addTributaryArea(const std::vector<SlavePoint>& facePoints, const mesh::FaceNodes& face,
                      const std::vector<int>& pairOf, SlaveIntegration& out) {
  for (const SlavePoint& q : facePoints)
    for (int v = 0; v < face.numNodes; ++v)
      if (const int p = pairOf[face.node[v]]; p >= 0) out.integrals[p].D += q.omega * q.phi[v];
}

/// The master faces on which the slave face's nodes and centre project within the search
/// distance: where the walk over the master faces covering it starts (MortarSegments.hpp).
std::vector<LO> seedFaces(const SlaveBasis& basis, const mesh::FaceNodes& face, const MasterSurface& master,
                          double searchDistance) {
  std::vector<LO> seeds;
  const mesh::FaceTypeShape& shape = mesh::faceTypeShape(basis.type());
  std::array<double, 2> centre{0.0, 0.0};
  for (int v = 0; v < face.numVertices; ++v)
    for (int i = 0; i < 2; ++i) centre[i] += shape.referenceNodes[v][i] / face.numVertices;
  std::vector<Vec3> probes(basis.coordinates().begin(), basis.coordinates().begin() + face.numNodes);
  probes.push_back(basis.at(centre[0], centre[1], 0.0).x);
  for (const Vec3& x : probes)
    if (const LO f = master.pairingProjection(x, searchDistance).face; f >= 0) seeds.push_back(f);
  return seeds;
}

/// A quadrature point with its projection on the master surface.
struct ProjectedPoint {
  SlavePoint q;
  MasterSurface::Projection chi;
};

/// The element-based points of a slave face, projected.
std::vector<ProjectedPoint> projectAll(std::vector<SlavePoint> points, const MasterSurface& master,
                                       double searchDistance) {
  std::vector<ProjectedPoint> projected;
  projected.reserve(points.size());
  for (SlavePoint& q : points) {
    const auto chi = master.pairingProjection(q.x, searchDistance);
    projected.push_back({std::move(q), chi});
  }
  return projected;
}

/// A segment point projected along the slave's normal field n on the master face f whose image
/// holds it (MortarNormalProjection.hpp): false where the line misses f by more than round-off
/// of the images' straight edges (1e-6 of the reference domain), or the master lies beyond the
/// pairing's reach (farther than the search distance ahead, or deeper than the face's size).
bool alongNormalOnItsFace(const MasterSurface& master, LO f, const SlavePoint& q, const Vec3& n,
                          double searchDistance, MasterSurface::Projection& chi) {
  constexpr double kImageSlack = 1e-6;
  std::array<double, 2> eta;
  if (!masterPointAlongNormal(master, f, q.x, n, chi, eta)) return false;
  const mesh::FaceNodes& face = master.faceNodes(f);
  if (!insideReferenceDomain(mesh::faceType(face.numVertices, face.numNodes), eta, kImageSlack)) return false;
  const double ahead = (chi.point[0] - q.x[0]) * n[0] + (chi.point[1] - q.x[1]) * n[1] + (chi.point[2] - q.x[2]) * n[2];
  return chi.distance <= (ahead >= 0.0 ? searchDistance : master.faceSize(f));
}

/// The contact normals of a slave face's nodes where every node is paired and they are not all
/// alike (MortarNormalProjection.hpp); false otherwise (the closest points serve).
bool normalFieldOf(const mesh::FaceNodes& face, const std::vector<int>& pairOf, const ContactSearchResult& search,
                   SlaveNormalField& field) {
  for (int v = 0; v < face.numNodes; ++v) {
    const int p = pairOf[face.node[v]];
    if (p < 0) return false;
    field.nodal[v] = search.pairs[p].normal;
  }
  return normalsVary(field, face.numNodes);
}

/// The quadrature points of one slave face, projected: segment-based (MortarSegments.hpp), with
/// the element-based points where no master face's image covers the face; the element-based
/// rule alone where the segments cannot be formed or a segment point projects on another master
/// face than its segment's.
std::vector<ProjectedPoint> mortarPoints(const SlaveBasis& basis, const mesh::FaceNodes& face,
                                         const MasterSurface& master, double searchDistance,
                                         const SlaveNormalField* field, std::vector<SlavePoint> facePoints,
                                         SlaveIntegration& out) {
  SegmentPoints segments = segmentPoints(basis, master, seedFaces(basis, face, master, searchDistance), field);
  bool consistent = segments.usable;
  std::vector<ProjectedPoint> projected;
  for (size_t k = 0; consistent && k < segments.points.size(); ++k) {
    const SlavePoint& q = segments.points[k];
    MasterSurface::Projection chi;
    if (field)
      consistent = alongNormalOnItsFace(master, segments.pointFace[k], q, field->at(basis, q.xi[0], q.xi[1]),
                                        searchDistance, chi);
    else {
      chi = master.pairingProjection(q.x, searchDistance);
      consistent = chi.face == segments.pointFace[k];
    }
    projected.push_back({q, chi});
  }
  if (!consistent) {
    ++out.elementBasedFaces;
    return projectAll(std::move(facePoints), master, searchDistance);
  }
  ++out.segmentBasedFaces;
  std::vector<SlavePoint> uncovered;
  for (SlavePoint& q : facePoints)
    if (!segments.covers(q.xi)) uncovered.push_back(std::move(q));
  for (auto& p : projectAll(std::move(uncovered), master, searchDistance)) projected.push_back(std::move(p));
  return projected;
}

/// The master's smoothed faces (SmoothedFaces.hpp), each built on first use.
class SmoothedMaster {
 public:
  explicit SmoothedMaster(const MasterSurface& master) : master_(master), masterFaces_(master.numFaces()) {}
  /// The offset of the master's smoothed surface at a projection on it.
  Vec3 masterOffset(const MasterSurface::Projection& chi) {
    if (chi.face < 0) return {0.0, 0.0, 0.0};
    const mesh::FaceNodes& face = master_.faceNodes(chi.face);
    const mesh::FaceType type = mesh::faceType(face.numVertices, face.numNodes);
    if (type == mesh::FaceType::Tri6) return {0.0, 0.0, 0.0};
    auto& smoothed = masterFaces_[chi.face];
    if (!smoothed) {
      std::array<Vec3, 4> n{};
      for (int v = 0; v < face.numVertices; ++v) n[v] = master_.nodalNormal(face.node[v]);
      smoothed = std::make_unique<SmoothedFace>(type, master_.faceCoordinates(chi.face), n);
    }
    const auto eta = referenceFromWeights(type, chi.weights);
    return smoothed->offset(eta[0], eta[1]);
  }

 private:
  const MasterSurface& master_;
  std::vector<std::unique_ptr<SmoothedFace>> masterFaces_;
};

/// The smoothed surfaces of Contact/Surface Geometry = Smoothed: the master's, and the slave
/// faces' from the slave's nodal normals (in the symmetry planes of `held`).
class SmoothedSurfaces : public SmoothedMaster {
 public:
  SmoothedSurfaces(const mesh::Mesh& mesh, const mesh::SideSet& slaveSet, const MasterSurface& master,
                   const HeldAxes& held)
      : SmoothedMaster(master), slaveNormals_(unitNodalNormals(mesh, slaveSet, held)) {}
  SmoothedFace slaveFace(const mesh::FaceNodes& face, const FaceCoordinates& x) const {
    std::array<Vec3, 4> n{};
    for (int v = 0; v < std::min(face.numVertices, 4); ++v) n[v] = slaveNormals_[face.node[v]];
    return SmoothedFace(mesh::faceType(face.numVertices, face.numNodes), x, n);
  }

 private:
  std::vector<Vec3> slaveNormals_;
};

/// MortarRow::facetSag of every row: the smoothed master's offset along the pair's normal at
/// the slave node's own projection.
void measureFacetSags(const MasterSurface& master, const ContactSearchResult& search, std::vector<MortarRow>& rows) {
  SmoothedMaster smoothed(master);
  for (size_t p = 0; p < rows.size(); ++p) {
    const ContactPair& pair = search.pairs[p];
    MasterSurface::Projection chi;
    chi.face = pair.masterFace;
    chi.weights = pair.weights;
    const Vec3 o = smoothed.masterOffset(chi);
    rows[p].facetSag = std::abs(o[0] * pair.normal[0] + o[1] * pair.normal[1] + o[2] * pair.normal[2]);
  }
}

SlaveIntegration integrateSlaveFaces(const mesh::Mesh& mesh, const std::string& slaveSideSet,
                                     const MasterSurface& master, const ContactSearchResult& search,
                                     double searchDistance, SmoothedSurfaces* smoothed) {
  std::vector<int> pairOf(mesh.numNodes(), -1);
  for (size_t p = 0; p < search.pairs.size(); ++p) pairOf[search.pairs[p].slaveNode] = static_cast<int>(p);
  SlaveIntegration out;
  out.integrals.resize(search.pairs.size());
  const mesh::SideSet& set = mesh.sideSet(slaveSideSet);
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const mesh::FaceNodes face = mesh.faceNodes(set.elements[f], set.sides[f]);
    bool anyPaired = false;
    for (LO n : face) anyPaired = anyPaired || pairOf[n] >= 0;
    if (!anyPaired) continue;
    FaceCoordinates x{};
    for (int v = 0; v < face.numNodes; ++v) x[v] = mesh.coords[face.node[v]];
    for (int m = 0; face.numNodes == 6 && m < 3; ++m)
      out.edgeEnds[face.node[3 + m]] = {face.node[m], face.node[(m + 1) % 3]};
    const SlaveBasis basis(face, x);
    const SmoothedFace smoothedSlave = smoothed ? smoothed->slaveFace(face, x) : SmoothedFace();
    std::vector<SlavePoint> facePoints = slaveFacePoints(face, x);
    addTributaryArea(facePoints, face, pairOf, out);
    SlaveNormalField field;
    const bool alongNormals = normalFieldOf(face, pairOf, search, field);
    for (const auto& [q, chi] : mortarPoints(basis, face, master, searchDistance, alongNormals ? &field : nullptr,
                                             std::move(facePoints), out)) {
      if (!chi.outcome.settled()) ++out.unsettledProjections;
      const Vec3 slaveOffset = smoothed ? smoothedSlave.offset(q.xi[0], q.xi[1]) : Vec3{0.0, 0.0, 0.0};
      const Vec3 masterOffset = smoothed ? smoothed->masterOffset(chi) : Vec3{0.0, 0.0, 0.0};
      addPoint(q, face, chi, slaveOffset, masterOffset, pairOf, search, out);
    }
  }
  return out;
}

/// The dual mortar row of one pair from its integrals (step 2 of dualMortarRows): the
/// node-to-surface row where the support is not fully covered, exactly node-to-node where the
/// mortar weights are (matching meshes).
MortarRow rowFromIntegrals(const ContactPair& pair, const NodeIntegrals& I,
                           const std::map<LO, std::pair<LO, LO>>& edgeEnds) {
  MortarRow fallback = nodeToSurfaceRow(pair);
  if (I.missed > 0 || !(I.D > 0.0) || !(I.covered > 0.0)) return fallback;
  MortarRow row;
  for (const auto& [masterNode, m] : I.M) {
    row.masterNodes.push_back(masterNode);
    row.weights.push_back(m / I.covered);
  }
  if (fallback.masterNodes.size() == 1) {
    // The node sits on a master vertex: node-to-node if the mortar weights agree.
    double deviation = 0.0;
    for (size_t k = 0; k < row.masterNodes.size(); ++k)
      deviation = std::max(deviation, std::abs(row.weights[k] - (row.masterNodes[k] == fallback.masterNodes[0])));
    if (deviation <= kNodeToNodeTolerance) return fallback;
  }
  // The dual basis is negative on part of the support: where the gap varies much within it
  // (a master that curves away within one slave element: a fillet of 1.5 slave elements)
  // the weighted gap can leave the range of the gap itself, a weighted overlap where the
  // surfaces are apart (the rounded punch then rose under a downward load). Kept within
  // the range of the pointwise gap over the support: unchanged where it already is
  // (the Hertz scenes, where the gap varies slowly), never an overlap where none is.
  const double weighted =
      (I.gapVector[0] * pair.normal[0] + I.gapVector[1] * pair.normal[1] + I.gapVector[2] * pair.normal[2]) /
      I.covered;
  if (!(I.gapMin <= I.gapMax) || !std::isfinite(weighted)) return fallback;  // no finite projection: no clamp on it
  row.gap = std::clamp(weighted, I.gapMin, I.gapMax);
  // Reported where the change is more than a hundredth of the range: the range is that of the
  // quadrature points, which need not reach the gap's extremes (the corners of the segments), so
  // an exact integral may lie a little beyond it (8e-8 of a range of 2e-5 on the push-out's
  // faceted cylinder), which is not the coarse-element effect the clamp is for.
  const double change = std::abs(row.gap - weighted);
  const double noise = 1e-2 * (I.gapMax - I.gapMin) + 1e-9 * (std::abs(I.gapMin) + std::abs(I.gapMax));
  row.gapLimited = change > noise ? change : 0.0;
  if (const auto ends = edgeEnds.find(pair.slaveNode); ends != edgeEnds.end()) {
    // The row holds u~_m = (u_m - alpha (u_a + u_b)) / (1 - 2 alpha) (header).
    const double keep = 1.0 - 2.0 * kQuadraticTransformAlpha;
    row.slaveWeight = 1.0 / keep;
    row.slaveNodes = {ends->second.first, ends->second.second};
    row.slaveWeights = {-kQuadraticTransformAlpha / keep, -kQuadraticTransformAlpha / keep};
  }
  return row;
}
}  // namespace

MortarRow nodeToSurfaceRow(const ContactPair& pair) {
  MortarRow row;
  row.nodeToSurface = true;
  row.gap = pair.gap;
  std::map<LO, double> sorted;
  for (int v = 0; v < kMaxMasterFaceNodes; ++v)
    if (pair.weights[v] != 0.0) sorted[pair.masterNodes[v]] += pair.weights[v];
  for (const auto& [node, w] : sorted) {
    row.masterNodes.push_back(node);
    row.weights.push_back(w);
  }
  return row;
}

bool projectsOnMasterVertices(const ContactSearchResult& search) {
  for (const auto& pair : search.pairs)
    if (std::count(pair.weights.begin(), pair.weights.end(), 1.0) != 1) return false;
  return !search.pairs.empty();
}

std::vector<MortarRow> dualMortarRows(const mesh::Mesh& mesh, const std::string& slaveSideSet,
                                      const MasterSurface& master, const ContactSearchResult& search,
                                      double searchDistance, long long* unsettledProjections,
                                      bool smoothedGeometry, const HeldAxes& held) {
  std::vector<MortarRow> rows;
  if (projectsOnMasterVertices(search)) {
    // Node-matching interface (header): node-to-node rows, whatever the triangles.
    for (const auto& pair : search.pairs) rows.push_back(nodeToSurfaceRow(pair));
    return rows;
  }
  std::unique_ptr<SmoothedSurfaces> smoothed;
  if (smoothedGeometry) smoothed = std::make_unique<SmoothedSurfaces>(mesh, mesh.sideSet(slaveSideSet), master, held);
  const SlaveIntegration integration =
      integrateSlaveFaces(mesh, slaveSideSet, master, search, searchDistance, smoothed.get());
  if (unsettledProjections) *unsettledProjections += integration.unsettledProjections;
  rows.reserve(search.pairs.size());
  for (size_t p = 0; p < search.pairs.size(); ++p)
    rows.push_back(rowFromIntegrals(search.pairs[p], integration.integrals[p], integration.edgeEnds));
  measureFacetSags(master, search, rows);
  return rows;
}

}  // namespace tribos::geometry
