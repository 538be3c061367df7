/// \file ContactSearch.cpp
/// Node-to-surface contact search (header). Cost: O(F log F) to build the tree over the F
/// master faces, O(log F) expected per slave node; the tree prunes by the distance of the
/// best face found so far, so a large search distance costs no more than a small one.
#include "tribos/mesh/ContactSearch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/mesh/ShapeFunctions.hpp"

namespace tribos::mesh {

namespace {
using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 minus(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double norm(const Vec3& v) { return std::sqrt(dot(v, v)); }

std::string str(double x) { return core::formatNumber(x); }
std::string str(const Vec3& x) { return core::formatPoint(x); }

struct Box {
  Vec3 low, high;
  /// Squared distance from x to the box (0 inside).
  double distance2(const Vec3& x) const {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) {
      const double out = std::max({low[d] - x[d], 0.0, x[d] - high[d]});
      d2 += out * out;
    }
    return d2;
  }
};

/// A bounding-volume tree over triangles, stored implicitly: the faces of a range
/// [lo, hi) are split at their median centroid along the widest axis; the box of the
/// range is kept at its middle position. Queries visit ranges nearest-first and skip
/// those farther than the best distance so far.
class TriangleTreeImpl {
 public:
  explicit TriangleTreeImpl(std::vector<std::array<Vec3, 3>> triangles)
      : triangles_(std::move(triangles)), order_(triangles_.size()), boxes_(triangles_.size()) {
    std::iota(order_.begin(), order_.end(), LO{0});
    build(0, order_.size());
  }

  /// Calls visit(face, bestDistance2) for every face whose box lies within
  /// sqrt(bestDistance2) of x; visit may lower bestDistance2.
  template <class Visit>
  void query(const Vec3& x, double& bestDistance2, Visit&& visit) const {
    search(0, order_.size(), x, bestDistance2, visit);
  }

  const std::array<Vec3, 3>& triangle(LO face) const { return triangles_[face]; }

 private:
  static size_t middle(size_t lo, size_t hi) { return lo + (hi - lo) / 2; }

  Vec3 centroid(LO face) const {
    const auto& t = triangles_[face];
    return {(t[0][0] + t[1][0] + t[2][0]) / 3.0, (t[0][1] + t[1][1] + t[2][1]) / 3.0,
            (t[0][2] + t[1][2] + t[2][2]) / 3.0};
  }

  void build(size_t lo, size_t hi) {
    if (lo >= hi) return;
    Box box{triangles_[order_[lo]][0], triangles_[order_[lo]][0]};
    for (size_t i = lo; i < hi; ++i)
      for (const Vec3& v : triangles_[order_[i]])
        for (int d = 0; d < 3; ++d) {
          box.low[d] = std::min(box.low[d], v[d]);
          box.high[d] = std::max(box.high[d], v[d]);
        }
    int axis = 0;
    for (int d = 1; d < 3; ++d)
      if (box.high[d] - box.low[d] > box.high[axis] - box.low[axis]) axis = d;
    const size_t mid = middle(lo, hi);
    std::nth_element(order_.begin() + lo, order_.begin() + mid, order_.begin() + hi,
                     [&](LO a, LO b) { return centroid(a)[axis] < centroid(b)[axis]; });
    boxes_[mid] = box;
    build(lo, mid);
    build(mid + 1, hi);
  }

  template <class Visit>
  void search(size_t lo, size_t hi, const Vec3& x, double& best2, Visit& visit) const {
    if (lo >= hi) return;
    const size_t mid = middle(lo, hi);
    if (boxes_[mid].distance2(x) > best2) return;
    visit(order_[mid], best2);
    const size_t leftMid = middle(lo, mid), rightMid = middle(mid + 1, hi);
    const double left = lo < mid ? boxes_[leftMid].distance2(x) : kFar;
    const double right = mid + 1 < hi ? boxes_[rightMid].distance2(x) : kFar;
    if (left <= right) {
      search(lo, mid, x, best2, visit);
      search(mid + 1, hi, x, best2, visit);
    } else {
      search(mid + 1, hi, x, best2, visit);
      search(lo, mid, x, best2, visit);
    }
  }

  static constexpr double kFar = std::numeric_limits<double>::infinity();
  std::vector<std::array<Vec3, 3>> triangles_;
  std::vector<LO> order_;
  std::vector<Box> boxes_;
};

/// Unit vectors of the summed normals; zero where the sum is zero.
std::vector<Vec3> unitNodalNormals(const Mesh& mesh, const SideSet& set) {
  auto n = summedFaceNormals(mesh, set);
  for (auto& v : n) {
    const double length = norm(v);
    if (length > 0.0)
      for (double& c : v) c /= length;
  }
  return n;
}

/// The largest absolute coordinate (at least 1): the scale of round-off in distances.
double coordinateScale(const Mesh& mesh) {
  double scale = 1.0;
  for (const auto& x : mesh.coords) scale = std::max({scale, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
  return scale;
}
}  // namespace

LO ContactPair::nearestMasterNode() const {
  return masterNodes[std::max_element(weights.begin(), weights.end()) - weights.begin()];
}

std::vector<LO> sideSetNodes(const Mesh& mesh, const SideSet& set) {
  std::vector<LO> nodes;
  nodes.reserve(3 * set.elements.size());
  for (size_t f = 0; f < set.elements.size(); ++f)
    for (LO n : mesh.faceNodes(set.elements[f], set.sides[f])) nodes.push_back(n);
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::vector<Vec3> summedFaceNormals(const Mesh& mesh, const SideSet& set) {
  std::vector<Vec3> normal(mesh.numNodes(), Vec3{0.0, 0.0, 0.0});
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const Vec3 n = mesh.faceNormal(set.elements[f], set.sides[f]);
    // Every node of the face: a 6-node triangle's mid-edge nodes are contact nodes too, and
    // the master normal is interpolated with its quadratic shape functions.
    for (LO node : mesh.faceNodes(set.elements[f], set.sides[f]))
      for (int d = 0; d < 3; ++d) normal[node][d] += n[d];
  }
  return normal;
}

std::array<double, 3> closestPointOnTriangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the vertices, then of the edges, else the interior; each test uses
  // the dot products of the edge vectors with x - vertex, so vertex and edge regions give
  // exact 0 / 1 weights (matching meshes pair node-to-node exactly).
  const Vec3 ab = minus(b, a), ac = minus(c, a), ax = minus(x, a);
  const double d1 = dot(ab, ax), d2 = dot(ac, ax);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Vec3 bx = minus(x, b);
  const double d3 = dot(ab, bx), d4 = dot(ac, bx);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double t = d1 / (d1 - d3);
    return {1.0 - t, t, 0.0};
  }
  const Vec3 cx = minus(x, c);
  const double d5 = dot(ab, cx), d6 = dot(ac, cx);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double t = d2 / (d2 - d6);
    return {1.0 - t, 0.0, t};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - t, t};
  }
  const double inverse = 1.0 / (va + vb + vc);
  const double v = vb * inverse, w = vc * inverse;
  return {1.0 - v - w, v, w};
}

class MasterSurface::Tree : public TriangleTreeImpl {
  using TriangleTreeImpl::TriangleTreeImpl;
};

namespace {
/// Reference corners (xi, eta) of the quadrilateral's vertices (mesh::faceShapeFunctions).
constexpr double kQuadCorners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
/// Reference points (r, s) of a 6-node triangle's nodes: vertices, then mid-edges 01, 12, 20.
constexpr double kTri6Nodes[6][2] = {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};

/// The triangles a face is searched as (face node indices), per face type.
struct FacePieces {
  int count;
  int node[4][3];
};
constexpr FacePieces kTri3Pieces = {1, {{0, 1, 2}}};
constexpr FacePieces kQuad4Pieces = {2, {{0, 1, 2}, {0, 2, 3}}};
constexpr FacePieces kTri6Pieces = {4, {{0, 3, 5}, {3, 1, 4}, {5, 4, 2}, {3, 4, 5}}};
const FacePieces& facePieces(const FaceNodes& face) {
  if (face.numVertices == 4) return kQuad4Pieces;
  return face.numNodes == 6 ? kTri6Pieces : kTri3Pieces;
}

/// A bound on the distance between a face and its pieces: a quadrilateral's twist |x0 - x1 +
/// x2 - x3| / 4 (the bilinear term at the centre), a 6-node triangle's largest bow of a
/// mid-edge node off its edge's chord; 0 for a 3-node triangle.
double deviationFromPieces(const FaceNodes& face, const std::array<Vec3, kMaxMasterFaceNodes>& x) {
  if (face.numVertices == 4) {
    Vec3 twist;
    for (int d = 0; d < 3; ++d) twist[d] = (x[0][d] - x[1][d] + x[2][d] - x[3][d]) / 4;
    return norm(twist);
  }
  double bow = 0.0;
  for (int m = 0; face.numNodes == 6 && m < 3; ++m) {
    Vec3 off;
    for (int d = 0; d < 3; ++d) off[d] = x[3 + m][d] - (x[m][d] + x[(m + 1) % 3][d]) / 2;
    bow = std::max(bow, norm(off));
  }
  return bow;
}

/// The point and tangents of a 6-node triangle x at (r, s), and its shape functions.
void quadraticTriangle(const std::array<Vec3, kMaxMasterFaceNodes>& x, double r, double s, Vec3& point, Vec3& dR,
                       Vec3& dS, std::array<double, kMaxMasterFaceNodes>& N) {
  const FaceGeometry g = faceGeometry(FaceType::Tri6, x.data(), r, s);
  point = g.point;
  dR = g.tangent0;
  dS = g.tangent1;
  std::copy(g.N.begin(), g.N.end(), N.begin());
}

/// The point of the 6-node triangle x closest to `target`, from (r, s) on: Gauss-Newton steps
/// within the reference triangle. A step that would leave it stops on the edge it crosses
/// (r = 0, s = 0 or r + s = 1), and the position along that edge takes the step of the model
/// restricted to it (as closestOnBilinear: the closest point of an edge is not where the free
/// step, cut off, would put it).
void closestOnQuadraticTriangle(const std::array<Vec3, kMaxMasterFaceNodes>& x, const Vec3& target, double& r,
                                double& s) {
  Vec3 point, dR, dS;
  std::array<double, kMaxMasterFaceNodes> N;
  for (int iteration = 0; iteration < 50; ++iteration) {
    quadraticTriangle(x, r, s, point, dR, dS, N);
    const Vec3 res = minus(point, target);
    const double a = dot(dR, dR), b = dot(dR, dS), c = dot(dS, dS);
    const double g0 = dot(dR, res), g1 = dot(dS, res), det = a * c - b * b;
    if (!(det > 0.0)) return;
    double nr = r - (c * g0 - b * g1) / det, ns = s - (a * g1 - b * g0) / det;
    if (nr < 0.0) {  // on r = 0: the model's step in s with r's step fixed at -r
      nr = 0.0;
      ns = std::clamp(s - (g1 - b * r) / c, 0.0, 1.0);
    } else if (ns < 0.0) {  // on s = 0
      ns = 0.0;
      nr = std::clamp(r - (g0 - b * s) / a, 0.0, 1.0);
    } else if (nr + ns > 1.0) {  // on r + s = 1: move along (1, -1) from (r, 1 - r)
      const double k = 1.0 - r - s, curvature = a - 2.0 * b + c;
      const double u = curvature > 0.0 ? -((g0 - g1) + k * (b - c)) / curvature : 0.0;
      nr = std::clamp(r + u, 0.0, 1.0);
      ns = 1.0 - nr;
    }
    const double change = std::abs(nr - r) + std::abs(ns - s);
    r = nr;
    s = ns;
    if (change < 1e-15) return;
  }
}

/// The bilinear face's point, tangents and shape functions at (xi, eta).
void bilinear(const std::array<Vec3, kMaxMasterFaceNodes>& x, double xi, double eta, Vec3& point, Vec3& dXi,
              Vec3& dEta, std::array<double, kMaxMasterFaceNodes>& N) {
  const FaceGeometry g = faceGeometry(FaceType::Quad4, x.data(), xi, eta);
  point = g.point;
  dXi = g.tangent0;
  dEta = g.tangent1;
  std::copy(g.N.begin(), g.N.end(), N.begin());
}

/// The point of the bilinear quadrilateral x closest to `target`, from the reference point
/// (xi, eta) on: Gauss-Newton steps on |X(xi, eta) - target|^2 within [-1, 1]^2. A step that
/// would leave the square along one coordinate stops at its edge, and the other coordinate
/// takes the step of the model with the first one fixed there (the closest point of an edge
/// is not where the free step, cut off, would put it). For a flat face this inverts the
/// bilinear map at the point found on the face's triangles.
void closestOnBilinear(const std::array<Vec3, kMaxMasterFaceNodes>& x, const Vec3& target, double& xi, double& eta) {
  Vec3 point, dXi, dEta;
  std::array<double, kMaxMasterFaceNodes> N;
  for (int iteration = 0; iteration < 50; ++iteration) {
    bilinear(x, xi, eta, point, dXi, dEta, N);
    const Vec3 r = minus(point, target);
    const double a = dot(dXi, dXi), b = dot(dXi, dEta), c = dot(dEta, dEta);
    const double g0 = dot(dXi, r), g1 = dot(dEta, r), det = a * c - b * b;
    if (!(det > 0.0)) return;
    double step0 = -(c * g0 - b * g1) / det, step1 = -(a * g1 - b * g0) / det;
    const bool outXi = std::abs(xi + step0) > 1.0, outEta = std::abs(eta + step1) > 1.0;
    if (outXi && !outEta) {
      step0 = std::clamp(xi + step0, -1.0, 1.0) - xi;
      step1 = std::clamp(eta - (g1 + b * step0) / c, -1.0, 1.0) - eta;
    } else if (outEta && !outXi) {
      step1 = std::clamp(eta + step1, -1.0, 1.0) - eta;
      step0 = std::clamp(xi - (g0 + b * step1) / a, -1.0, 1.0) - xi;
    } else if (outXi && outEta) {
      step0 = std::clamp(xi + step0, -1.0, 1.0) - xi;
      step1 = std::clamp(eta + step1, -1.0, 1.0) - eta;
    }
    xi += step0;
    eta += step1;
    if (std::abs(step0) + std::abs(step1) < 1e-15) return;
  }
}
}  // namespace

MasterSurface::MasterSurface(const Mesh& mesh, const std::string& masterSideSet)
    : name_(masterSideSet) {
  const SideSet& set = mesh.sideSet(masterSideSet);
  std::vector<std::array<Vec3, 3>> triangles;
  faceNodes_.resize(set.elements.size());
  faceCoords_.resize(set.elements.size());
  for (size_t f = 0; f < set.elements.size(); ++f) {
    faceNodes_[f] = mesh.faceNodes(set.elements[f], set.sides[f]);
    for (int v = 0; v < faceNodes_[f].numNodes; ++v) faceCoords_[f][v] = mesh.coords[faceNodes_[f].node[v]];
    pieceDeviation_ = std::max(pieceDeviation_, deviationFromPieces(faceNodes_[f], faceCoords_[f]));
    const FacePieces& pieces = facePieces(faceNodes_[f]);
    for (int piece = 0; piece < pieces.count; ++piece) {
      std::array<Vec3, 3> t;
      for (int v = 0; v < 3; ++v) t[v] = faceCoords_[f][pieces.node[piece][v]];
      triangles.push_back(t);
      searchTriangles_.push_back({static_cast<LO>(f), piece});
    }
  }
  tree_ = std::make_unique<Tree>(std::move(triangles));
  nodalNormal_ = unitNodalNormals(mesh, set);
}

MasterSurface::~MasterSurface() = default;

MasterSurface::Projection MasterSurface::project(const Vec3& x, double radius, long long* facesTested) const {
  Projection best;
  LO bestTriangle = -1;
  std::array<double, 3> bestBarycentric{};
  const double reach = radius + pieceDeviation_;
  double best2 = reach * reach;
  tree_->query(x, best2, [&](LO triangle, double& bound2) {
    if (facesTested) ++*facesTested;
    const auto& t = tree_->triangle(triangle);
    const auto w = closestPointOnTriangle(x, t[0], t[1], t[2]);
    Vec3 p{};
    for (int d = 0; d < 3; ++d) p[d] = w[0] * t[0][d] + w[1] * t[1][d] + w[2] * t[2][d];
    const Vec3 diff = minus(p, x);
    const double d2 = dot(diff, diff);
    if (d2 < bound2 || (d2 == bound2 && (bestTriangle < 0 || triangle < bestTriangle))) {
      bestTriangle = triangle;
      bestBarycentric = w;
      best.point = p;
      bound2 = d2;
    }
  });
  if (bestTriangle < 0) return best;
  const SearchTriangle& found = searchTriangles_[bestTriangle];
  const FaceNodes& face = faceNodes_[found.face];
  best.face = found.face;
  for (int v = 0; v < face.numNodes; ++v) best.nodes[v] = face.node[v];
  if (face.numNodes == 3) {
    for (int v = 0; v < 3; ++v) best.weights[v] = bestBarycentric[v];
    best.distance = std::sqrt(best2);
    return best2 <= radius * radius ? best : Projection{};
  }
  // A quadrilateral or a 6-node triangle: its reference point from the piece's barycentric
  // weights; a node of the face (a weight of exactly 1: matching meshes) stays exact, as on
  // a triangle.
  const int* piece = facePieces(face).node[found.piece];
  for (int v = 0; v < 3; ++v)
    if (bestBarycentric[v] == 1.0) {
      best.weights[piece[v]] = 1.0;
      best.distance = std::sqrt(best2);
      return best2 <= radius * radius ? best : Projection{};
    }
  const auto& coords = faceCoords_[found.face];
  const bool quad = face.numVertices == 4;
  double ref[2] = {0.0, 0.0};
  for (int v = 0; v < 3; ++v)
    for (int i = 0; i < 2; ++i) ref[i] += bestBarycentric[v] * (quad ? kQuadCorners : kTri6Nodes)[piece[v]][i];
  Vec3 d0, d1;
  if (quad) {
    closestOnBilinear(coords, x, ref[0], ref[1]);
    bilinear(coords, ref[0], ref[1], best.point, d0, d1, best.weights);
  } else {
    closestOnQuadraticTriangle(coords, x, ref[0], ref[1]);
    quadraticTriangle(coords, ref[0], ref[1], best.point, d0, d1, best.weights);
  }
  best.distance = norm(minus(best.point, x));
  return best.distance <= radius ? best : Projection{};
}

Vec3 MasterSurface::normalAt(const Projection& p) const {
  Vec3 n{0.0, 0.0, 0.0};
  for (int v = 0; v < kMaxMasterFaceNodes; ++v)
    if (p.nodes[v] >= 0)
      for (int d = 0; d < 3; ++d) n[d] += p.weights[v] * nodalNormal_[p.nodes[v]][d];
  const double length = norm(n);
  if (length > 0.0)
    for (double& c : n) c /= length;
  return n;
}

ContactSearchResult searchContactPairs(const Mesh& mesh, const std::string& slaveSideSet,
                                       const std::string& masterSideSet, double searchDistance) {
  core::requireInput(std::isfinite(searchDistance) && searchDistance >= 0.0,
                     "Contact/Search Distance must be finite and >= 0, got " + str(searchDistance));
  const SideSet& slaveSet = mesh.sideSet(slaveSideSet);
  const auto slaves = sideSetNodes(mesh, slaveSet);
  const auto masterNodes = sideSetNodes(mesh, mesh.sideSet(masterSideSet));
  const MasterSurface master(mesh, masterSideSet);
  const auto slaveNormal = unitNodalNormals(mesh, slaveSet);
  const double zeroGap = 1e-12 * coordinateScale(mesh);

  ContactSearchResult result;
  std::string firstFacingAway;
  for (LO slave : slaves) {
    const Vec3& xs = mesh.coords[slave];
    if (std::binary_search(masterNodes.begin(), masterNodes.end(), slave))
      throw core::InputError("contact: node " + std::to_string(slave + 1) + " belongs to both side sets \"" +
                             slaveSideSet + "\" and \"" + masterSideSet +
                             "\": the bodies share their interface nodes; give each body its own nodes "
                             "(gmsh meshes: tribos-msh2exo --split-bodies)");
    core::requireInput(norm(slaveNormal[slave]) > 0.0,
                       "contact: the faces of side set \"" + slaveSideSet + "\" at slave node " +
                           std::to_string(slave + 1) + " at " + str(xs) +
                           " have a zero summed normal (degenerate or folded surface)");
    // Nearest face within the search distance; ties go to the lower face index.
    const auto projection = master.project(xs, searchDistance, &result.facesTested);
    if (projection.face < 0) {
      result.unpaired.push_back(slave);
      continue;
    }
    ContactPair pair;
    pair.slaveNode = slave;
    pair.masterFace = projection.face;
    pair.masterNodes = projection.nodes;
    pair.weights = projection.weights;
    // nu = -(interpolated master normal) (header: the smoothed normal).
    Vec3 n = master.normalAt(projection);
    core::requireInput(norm(n) > 0.0, "contact: the master surface \"" + masterSideSet + "\" is folded at " +
                                          str(projection.point) + " (its nodal normals cancel), the projection of slave node " +
                                          std::to_string(slave + 1));
    for (double& c : n) c = -c;
    // Where the master surface faces away from the slave surface the node cannot touch it
    // (it found the back or the side of the master body): no rows, like a node out of reach.
    if (!(dot(n, slaveNormal[slave]) > 0.0)) {
      result.unpaired.push_back(slave);
      ++result.facingAway;
      if (result.facingAway == 1) firstFacingAway = "slave node " + std::to_string(slave + 1) + " at " + str(xs) +
                                                    " projects on face " + std::to_string(projection.face + 1) +
                                                    " at " + str(projection.point);
      continue;
    }
    pair.normal = n;
    pair.distance = projection.distance;
    pair.gap = dot(minus(projection.point, xs), n);
    if (std::abs(pair.gap) <= zeroGap) pair.gap = 0.0;
    if (pair.gap < 0.0) {
      ++result.overlapping;
      result.largestOverlap = std::max(result.largestOverlap, -pair.gap);
    }
    result.pairs.push_back(pair);
  }
  // Every reachable node facing away: the sets are swapped or name the wrong surfaces.
  core::requireInput(!result.pairs.empty() || result.facingAway == 0,
                     "contact: the master surface \"" + masterSideSet + "\" faces away from the slave surface \"" +
                         slaveSideSet + "\" wherever it is within the Search Distance (e.g. " + firstFacingAway +
                         "); check the side sets (outer faces of the two bodies, facing each other)");
  return result;
}

}  // namespace tribos::mesh
