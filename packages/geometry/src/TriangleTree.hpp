#pragma once
/// \file TriangleTree.hpp
/// A bounding-volume tree over triangles (private to the package; MasterSurface searches its
/// faces with it). Cost: O(F log F) to build over F triangles, O(log F) expected per query; the
/// query prunes by the distance of the best triangle found so far, so a large search radius
/// costs no more than a small one.
#include <algorithm>
#include <array>
#include <cstddef>
#include <limits>
#include <numeric>
#include <vector>

#include "tribos/core/Types.hpp"

namespace tribos::geometry {

using Vec3 = std::array<double, 3>;

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
class TriangleTree {
 public:
  explicit TriangleTree(std::vector<std::array<Vec3, 3>> triangles)
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

}  // namespace tribos::geometry
