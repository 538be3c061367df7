/// \file MasterSurface.cpp
/// The master surface's search tree and closest points (header).
#include "tribos/geometry/MasterSurface.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "SurfaceBoundary.hpp"
#include "TriangleTree.hpp"
#include "VectorMath.hpp"
#include "tribos/geometry/SurfaceNormals.hpp"

namespace tribos::geometry {

namespace {
/// The face catalogue's entry of a face (mesh/ShapeFunctions.hpp: its search triangles and
/// reference nodes).
const mesh::FaceTypeShape& shapeOf(const mesh::FaceNodes& face) {
  return mesh::faceTypeShape(mesh::faceType(face.numVertices, face.numNodes));
}

/// A bound on the distance between a face and its pieces: a quadrilateral's twist |x0 - x1 +
/// x2 - x3| / 4 (the bilinear term at the centre), a 6-node triangle's largest bow of a
/// mid-edge node off its edge's chord; 0 for a 3-node triangle.
double deviationFromPieces(const mesh::FaceNodes& face, const FaceCoordinates& x) {
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

/// Per face, the other faces that share a node with it (ascending).
std::vector<std::vector<LO>> faceNeighbours(const std::vector<mesh::FaceNodes>& faces) {
  std::map<LO, std::vector<LO>> facesAt;
  for (size_t f = 0; f < faces.size(); ++f)
    for (LO n : faces[f]) facesAt[n].push_back(static_cast<LO>(f));
  std::vector<std::vector<LO>> neighbours(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    for (LO n : faces[f])
      for (LO g : facesAt[n])
        if (g != static_cast<LO>(f)) neighbours[f].push_back(g);
    std::sort(neighbours[f].begin(), neighbours[f].end());
    neighbours[f].erase(std::unique(neighbours[f].begin(), neighbours[f].end()), neighbours[f].end());
  }
  return neighbours;
}
}  // namespace

MasterSurface::MasterSurface(const mesh::Mesh& mesh, const std::string& masterSideSet, const HeldAxes& held)
    : name_(masterSideSet) {
  const mesh::SideSet& set = mesh.sideSet(masterSideSet);
  std::vector<std::array<Vec3, 3>> triangles;
  faceNodes_.resize(set.elements.size());
  faceCoords_.resize(set.elements.size());
  for (size_t f = 0; f < set.elements.size(); ++f) {
    faceNodes_[f] = mesh.faceNodes(set.elements[f], set.sides[f]);
    for (int v = 0; v < faceNodes_[f].numNodes; ++v) faceCoords_[f][v] = mesh.coords[faceNodes_[f].node[v]];
    pieceDeviation_ = std::max(pieceDeviation_, deviationFromPieces(faceNodes_[f], faceCoords_[f]));
    const mesh::FaceTypeShape& shape = shapeOf(faceNodes_[f]);
    for (int piece = 0; piece < shape.numSearchTriangles; ++piece) {
      std::array<Vec3, 3> t;
      for (int v = 0; v < 3; ++v) t[v] = faceCoords_[f][shape.searchTriangles[piece][v]];
      triangles.push_back(t);
      searchTriangles_.push_back({static_cast<LO>(f), piece});
    }
  }
  tree_ = std::make_unique<TriangleTree>(std::move(triangles));
  nodalNormal_ = unitNodalNormals(mesh, set, held);
  neighbours_ = faceNeighbours(faceNodes_);
  boundaryEdges_ = boundaryEdges(faceNodes_);
  faceSize_.resize(faceNodes_.size());
  for (size_t f = 0; f < faceNodes_.size(); ++f) {
    for (int a = 0; a < faceNodes_[f].numNodes; ++a)
      for (int b = 0; b < a; ++b)
        faceSize_[f] = std::max(faceSize_[f], norm(minus(faceCoords_[f][a], faceCoords_[f][b])));
    largestFaceSize_ = std::max(largestFaceSize_, faceSize_[f]);
  }
}

MasterSurface::~MasterSurface() = default;

MasterSurface::Projection MasterSurface::project(const Vec3& x, double radius, long long* facesTested) const {
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
      bound2 = d2;
    }
  });
  if (bestTriangle < 0) return Projection{};
  return onFace(bestTriangle, bestBarycentric, x, radius);
}

MasterSurface::Projection MasterSurface::onFace(LO triangle, const std::array<double, 3>& barycentric,
                                                const Vec3& x, double radius) const {
  Projection none;  // beyond the radius: no face (how a curved face's projection ended is kept)
  const SearchTriangle& found = searchTriangles_[triangle];
  const mesh::FaceNodes& face = faceNodes_[found.face];
  const auto& t = tree_->triangle(triangle);
  Projection best;
  best.face = found.face;
  for (int v = 0; v < face.numNodes; ++v) best.nodes[v] = face.node[v];
  for (int d = 0; d < 3; ++d)
    best.point[d] = barycentric[0] * t[0][d] + barycentric[1] * t[1][d] + barycentric[2] * t[2][d];
  const Vec3 diff = minus(best.point, x);
  const double distance2 = dot(diff, diff);
  best.distance = std::sqrt(distance2);
  const mesh::FaceTypeShape& shape = shapeOf(face);
  if (!shape.curved) {  // a 3-node triangle is its own search triangle: the point is exact
    for (int v = 0; v < 3; ++v) best.weights[v] = barycentric[v];
    return distance2 <= radius * radius ? best : none;
  }
  // A quadrilateral or a 6-node triangle: its reference point from the piece's barycentric
  // weights; a node of the face (a weight of exactly 1: matching meshes) stays exact, as on
  // a triangle.
  const int* piece = shape.searchTriangles[found.piece];
  for (int v = 0; v < 3; ++v)
    if (barycentric[v] == 1.0) {
      best.weights[piece[v]] = 1.0;
      return distance2 <= radius * radius ? best : none;
    }
  double ref[2] = {0.0, 0.0};
  for (int v = 0; v < 3; ++v)
    for (int i = 0; i < 2; ++i) ref[i] += barycentric[v] * shape.referenceNodes[piece[v]][i];
  const mesh::FaceType type = mesh::faceType(face.numVertices, face.numNodes);
  const auto& coords = faceCoords_[found.face];
  best.outcome = closestPointOnCurvedFace(type, coords, x, ref[0], ref[1]);
  const mesh::FaceGeometry g = mesh::faceGeometry(type, coords.data(), ref[0], ref[1]);
  best.point = g.point;
  std::copy(g.N.begin(), g.N.end(), best.weights.begin());
  best.distance = norm(minus(best.point, x));
  none.outcome = best.outcome;
  return best.distance <= radius ? best : none;
}

MasterSurface::Projection MasterSurface::pairingProjection(const Vec3& x, double searchDistance,
                                                           long long* facesTested) const {
  const Projection p = project(x, std::max(searchDistance, largestFaceSize_), facesTested);
  Projection none;
  none.outcome = p.outcome;
  if (p.face < 0) return p;
  const Vec3 n = normalAt(p);  // outward of the master body
  const double beside =
      besideTheSurface(faceNodes_[p.face], faceCoords_[p.face], boundaryEdges_[p.face], p.weights, p.point, n, x);
  const double along = std::abs(dot(minus(x, p.point), n));
  if (beside > kBesideTheSurface * faceSize_[p.face] + kBesideSlope * along) return none;
  if (p.distance <= searchDistance) return p;
  if (p.distance > faceSize_[p.face]) return none;
  const double depth = -dot(minus(x, p.point), n);
  return depth >= kInsideAlongNormal * p.distance ? p : none;
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

}  // namespace tribos::geometry
