/// \file MortarSegments.cpp
/// Segment-based integration of the mortar integrals on a slave face (header).
#include "MortarSegments.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>

#include "MortarNormalProjection.hpp"
#include "VectorMath.hpp"

namespace tribos::geometry {

namespace {
using Point2 = std::array<double, 2>;
using Polygon = std::vector<Point2>;

/// Master faces examined for one slave face at most: far more than a slave face meets on any
/// sensible pair of meshes (a slave element 10 times the master's meets ~150); beyond it the
/// element-based rule is kept.
constexpr size_t kMaxExaminedFaces = 400;
/// Pieces smaller than this fraction of the reference domain carry nothing worth a point.
constexpr double kNegligibleArea = 1e-14;
/// Images covering more than the domain by this fraction overlap (header).
constexpr double kOverlapTolerance = 1e-9;

double cross(const Point2& o, const Point2& a, const Point2& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

double signedArea(const Polygon& p) {
  double twice = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    const Point2& a = p[i];
    const Point2& b = p[(i + 1) % p.size()];
    twice += a[0] * b[1] - a[1] * b[0];
  }
  return 0.5 * twice;
}

/// The reference domain of a face type, counter-clockwise (its vertices).
Polygon referenceDomain(mesh::FaceType type) {
  const mesh::FaceTypeShape& shape = mesh::faceTypeShape(type);
  Polygon domain;
  for (int v = 0; v < shape.numVertices; ++v) domain.push_back({shape.referenceNodes[v][0], shape.referenceNodes[v][1]});
  return domain;
}

/// The reference point of the slave face, extended beyond its edges, closest to y: Gauss-Newton
/// steps from the centre (one step on an affine face). False where the tangents degenerate or
/// the steps do not settle.
bool referencePointOf(const SlaveBasis& basis, const Vec3& y, Point2& xi) {
  const mesh::FaceTypeShape& shape = mesh::faceTypeShape(basis.type());
  xi = {0.0, 0.0};  // the centre: the mean of the catalogue's reference vertices
  for (int v = 0; v < shape.numVertices; ++v)
    for (int c = 0; c < 2; ++c) xi[c] += shape.referenceNodes[v][c];
  for (int c = 0; c < 2; ++c) xi[c] /= shape.numVertices;
  for (int step = 0; step < kMaxProjectionSteps; ++step) {
    const mesh::FaceGeometry g = mesh::faceGeometry(basis.type(), basis.coordinates().data(), xi[0], xi[1]);
    const Vec3 r = minus(y, g.point);
    const double a00 = dot(g.tangent0, g.tangent0), a01 = dot(g.tangent0, g.tangent1), a11 = dot(g.tangent1, g.tangent1);
    const double det = a00 * a11 - a01 * a01;
    if (!(det > 1e-12 * a00 * a11)) return false;
    const double b0 = dot(g.tangent0, r), b1 = dot(g.tangent1, r);
    const Point2 d{(a11 * b0 - a01 * b1) / det, (a00 * b1 - a01 * b0) / det};
    xi = {xi[0] + d[0], xi[1] + d[1]};
    if (!(std::abs(xi[0]) + std::abs(xi[1]) < 1e3)) return false;
    if (std::abs(d[0]) + std::abs(d[1]) < 1e-13) return true;
  }
  return false;
}

/// The image of master face f in the slave face's reference domain: its outline (vertices, and
/// on a 6-node triangle the mid-edge nodes between them) mapped node by node, by closest points
/// or, where `field` is given, along the slave's normal field (MortarNormalProjection.hpp).
bool imageOf(const SlaveBasis& basis, const MasterSurface& master, LO f, const SlaveNormalField* field,
             Polygon& image) {
  const mesh::FaceNodes& face = master.faceNodes(f);
  const FaceCoordinates& x = master.faceCoordinates(f);
  image.clear();
  for (int v = 0; v < face.numVertices; ++v) {
    for (int k : {v, face.numNodes > face.numVertices ? face.numVertices + v : -1}) {  // the edge's mid node after it
      if (k < 0) continue;
      Point2 xi;
      if (!referencePointOf(basis, x[k], xi)) return false;
      if (field && !slavePointAlongNormal(basis, *field, x[k], xi)) return false;
      image.push_back(xi);
    }
  }
  return true;
}

/// Sutherland-Hodgman: the part of `subject` inside the convex, counter-clockwise `clipper`.
Polygon clip(Polygon subject, const Polygon& clipper) {
  for (size_t e = 0; e < clipper.size() && !subject.empty(); ++e) {
    const Point2& a = clipper[e];
    const Point2& b = clipper[(e + 1) % clipper.size()];
    Polygon kept;
    for (size_t i = 0; i < subject.size(); ++i) {
      const Point2& previous = subject[(i + subject.size() - 1) % subject.size()];
      const Point2& current = subject[i];
      const double sp = cross(a, b, previous), sc = cross(a, b, current);
      if ((sc >= 0.0) != (sp >= 0.0)) {
        const double t = sp / (sp - sc);
        kept.push_back({previous[0] + t * (current[0] - previous[0]), previous[1] + t * (current[1] - previous[1])});
      }
      if (sc >= 0.0) kept.push_back(current);
    }
    subject = std::move(kept);
  }
  return subject;
}

/// The quadrature points of a piece: triangles from its centre to each edge, the quartic rule
/// on each.
void addPiecePoints(const Polygon& piece, const SlaveBasis& basis, std::vector<SlavePoint>& points) {
  Point2 centre{0.0, 0.0};
  for (const Point2& p : piece)
    for (int i = 0; i < 2; ++i) centre[i] += p[i] / piece.size();
  for (size_t i = 0; i < piece.size(); ++i) {
    const Point2& a = piece[i];
    const Point2& b = piece[(i + 1) % piece.size()];
    const double area = 0.5 * cross(centre, a, b);
    if (!(area > 0.0)) continue;
    for (const TrianglePoint& q : quarticTriangleRule()) {
      const double xi0 = q.lambda[0] * centre[0] + q.lambda[1] * a[0] + q.lambda[2] * b[0];
      const double xi1 = q.lambda[0] * centre[1] + q.lambda[1] * a[1] + q.lambda[2] * b[1];
      points.push_back(basis.at(xi0, xi1, q.weight * area));
    }
  }
}
}  // namespace

bool SegmentPoints::covers(const std::array<double, 2>& xi) const {
  // Inside a counter-clockwise convex piece: left of (or on) every edge, to round-off (in
  // reference coordinates, of size 1; an edge of clipped length ~0 must not decide).
  constexpr double kOnEdge = 1e-12;
  for (const Polygon& piece : pieces) {
    bool inside = true;
    for (size_t i = 0; i < piece.size() && inside; ++i) {
      const Point2& a = piece[i];
      const Point2& b = piece[(i + 1) % piece.size()];
      inside = cross(a, b, xi) >= -kOnEdge;
    }
    if (inside) return true;
  }
  return false;
}

SegmentPoints segmentPoints(const SlaveBasis& basis, const MasterSurface& master, const std::vector<LO>& seeds,
                            const SlaveNormalField* field) {
  const Polygon domain = referenceDomain(basis.type());
  const double domainArea = signedArea(domain);
  SegmentPoints result;
  const std::set<LO> seedSet(seeds.begin(), seeds.end());
  std::set<LO> queued = seedSet;
  std::deque<LO> queue(seedSet.begin(), seedSet.end());
  double covered = 0.0;
  for (size_t examined = 0; !queue.empty(); ++examined) {
    if (examined == kMaxExaminedFaces) return SegmentPoints{};
    const LO f = queue.front();
    queue.pop_front();
    Polygon image;
    if (!imageOf(basis, master, f, field, image)) return SegmentPoints{};
    const bool seed = seedSet.count(f) > 0;
    // A facing master face's image turns the other way round (its outward normal is opposite).
    double area = 0.0;
    if (signedArea(image) < 0.0) {
      std::reverse(image.begin(), image.end());
      const Polygon piece = clip(image, domain);
      area = piece.size() >= 3 ? signedArea(piece) : 0.0;
      if (area > kNegligibleArea * domainArea) {
        covered += area;
        ++result.masterFaces;
        addPiecePoints(piece, basis, result.points);
        result.pointFace.resize(result.points.size(), f);
        result.pieces.push_back(piece);
      }
    }
    if (!(area > kNegligibleArea * domainArea) && !seed) continue;  // meets nothing: the walk ends here
    for (LO g : master.neighbours(f))
      if (queued.insert(g).second) queue.push_back(g);
  }
  if (covered > domainArea * (1.0 + kOverlapTolerance)) return SegmentPoints{};
  result.usable = true;
  return result;
}

}  // namespace tribos::geometry
