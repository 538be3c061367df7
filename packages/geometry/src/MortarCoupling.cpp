/// \file MortarCoupling.cpp
/// Dual mortar weights by element-based quadrature on the slave surface (header).
#include "tribos/geometry/MortarCoupling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "MortarQuadrature.hpp"

namespace tribos::geometry {

namespace {
/// Tolerance for "fully covered" (sum_j M_ij = D_i) and for "node-to-node" (w = unit vector).
constexpr double kCoverageTolerance = 1e-9;
constexpr double kNodeToNodeTolerance = 1e-10;

/// The integrals of one slave node: D_i, M_ij, int psi_i (chi(x) - x), and int psi_i over
/// the covered part (sum_j M_ij); and the range of the pointwise gap (chi(x) - x) . nu_i
/// over its support.
struct NodeIntegrals {
  double D = 0.0, covered = 0.0;
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
};

/// Adds one quadrature point's contributions to the integrals of the paired nodes of its face.
void addPoint(const SlavePoint& q, const mesh::FaceNodes& face, const MasterSurface::Projection& chi,
              const std::vector<int>& pairOf, const ContactSearchResult& search, SlaveIntegration& out) {
  const Vec3& xq = q.x;
  const double omega = q.omega;
  for (int v = 0; v < face.numNodes; ++v) {
    const int p = pairOf[face.node[v]];
    if (p < 0) continue;
    NodeIntegrals& I = out.integrals[p];
    I.D += omega * q.phi[v];
    if (chi.face < 0) continue;
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

SlaveIntegration integrateSlaveFaces(const mesh::Mesh& mesh, const std::string& slaveSideSet,
                                     const MasterSurface& master, const ContactSearchResult& search,
                                     double searchDistance) {
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
    for (const SlavePoint& q : slaveFacePoints(face, x)) {
      const auto chi = master.project(q.x, searchDistance);
      if (!chi.outcome.settled()) ++out.unsettledProjections;
      addPoint(q, face, chi, pairOf, search, out);
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
  if (!(I.D > 0.0) || std::abs(I.covered - I.D) > kCoverageTolerance * I.D) return fallback;
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
  row.gapLimited = std::abs(row.gap - weighted);
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
                                      double searchDistance, long long* unsettledProjections) {
  std::vector<MortarRow> rows;
  if (projectsOnMasterVertices(search)) {
    // Node-matching interface (header): node-to-node rows, whatever the triangles.
    for (const auto& pair : search.pairs) rows.push_back(nodeToSurfaceRow(pair));
    return rows;
  }
  const SlaveIntegration integration = integrateSlaveFaces(mesh, slaveSideSet, master, search, searchDistance);
  if (unsettledProjections) *unsettledProjections += integration.unsettledProjections;
  rows.reserve(search.pairs.size());
  for (size_t p = 0; p < search.pairs.size(); ++p)
    rows.push_back(rowFromIntegrals(search.pairs[p], integration.integrals[p], integration.edgeEnds));
  return rows;
}

}  // namespace tribos::geometry
