#include "tribos/qp/SeparableSet.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "tribos/qp/Reductions.hpp"

namespace tribos::qp {

namespace {
constexpr double kInfinity = std::numeric_limits<double>::infinity();
/// Relative tolerance for "on the boundary" (active). MPGP's iterates reach a boundary only
/// through a projection (max(x, l) is exact; the ellipse projection is normalised onto
/// ||E y|| = 1 to round-off) or a feasible step (x - alpha_f p, exact to a few ulps), so
/// only round-off needs absorbing; a larger tolerance would freeze blocks that are still
/// strictly inside and let CG steps leave Omega by that much. Bounds: x - l <= tol (|l| + |x|)
/// (relative to the size of the numbers subtracted, so independent of the units of x; for
/// l = 0 only x = 0 is active, which projections produce exactly). Ellipses:
/// ||E (x - c)|| >= 1 - tol. A block missed by round-off is caught at the next step: its
/// feasible step is then ~0 and the expansion's projection lands on the boundary exactly.
constexpr double kActiveTolerance = 1e-12;

/// The "on the boundary" tolerance of an ellipse block, in units of ||E y||: kActiveTolerance,
/// or what doubles resolve. MPGP stores x = c + y, so y is known to ~eps |c| only; with a
/// small slip bound next to a larger centre a block a few ulps of c inside its boundary
/// cannot be moved onto it (x - alpha p rounds back to x). Measured at 20x10x10 per brick,
/// H/h 2: a disc of radius 5.9e-5 with ||E y|| = 1 - 2.1e-12 stayed "free", its feasible step
/// was 5.8e-18 in every iteration, and MPGP crawled on expansion steps for hundreds of
/// iterations (doc/measurements/coarse_problem.md). Such a block counts as on the boundary.
double ellipseActiveTolerance(const std::array<double, 2>& center, double smallestAxis) {
  const double resolution = std::numeric_limits<double>::epsilon() * std::max(std::abs(center[0]), std::abs(center[1]));
  return std::max(kActiveTolerance, 16.0 * resolution / smallestAxis);
}

/// Entry i of a vector view; 0 for an absent ellipse row (index -1).
template <class View>
double at(const View& v, int i) {
  return i >= 0 ? v(i, 0) : 0.0;
}

bool boundActive(double x, double lower) {
  return x - lower <= kActiveTolerance * (std::abs(lower) + std::abs(x) + std::numeric_limits<double>::min());
}

/// ||diag(1/a) y||, with a_j > 0.
double ellipseNorm(const std::array<double, 2>& y, const std::array<double, 2>& a) {
  return std::hypot(y[0] / a[0], y[1] / a[1]);
}

/// Projection of -g onto the tangent cone of a 1D interval [lo, hi] at y; returns g^P.
double intervalProjectedGradient(double y, double lo, double hi, double g) {
  const bool atLower = y <= lo + kActiveTolerance * (std::abs(lo) + std::abs(y));
  const bool atUpper = y >= hi - kActiveTolerance * (std::abs(hi) + std::abs(y));
  if (atLower && atUpper) return 0.0;  // a point
  if (atLower) return std::min(g, 0.0);
  if (atUpper) return std::max(g, 0.0);
  return g;
}
/// The boundary arc of an ellipse block at y = x - c (on its boundary): its curvature and its
/// outward normal n, unnormalised, with |n|. Curvature of (y1/a1)^2 + (y2/a2)^2 = 1 at y:
/// 1 / (a1^2 a2^2 (y1^2/a1^4 + y2^2/a2^4)^(3/2)).
struct Arc {
  double kappa;
  std::array<double, 2> n;
  double nn;
};
Arc arcAt(const std::array<double, 2>& y, const std::array<double, 2>& a) {
  const double q = y[0] * y[0] / (a[0] * a[0] * a[0] * a[0]) + y[1] * y[1] / (a[1] * a[1] * a[1] * a[1]);
  const std::array<double, 2> n{y[0] / (a[0] * a[0]), y[1] / (a[1] * a[1])};
  return {1.0 / (a[0] * a[0] * a[1] * a[1] * q * std::sqrt(q)), n, std::hypot(n[0], n[1])};
}
}  // namespace

std::array<double, 2> projectOntoEllipse(std::array<double, 2> w, std::array<double, 2> a) {
  // Work in units of t = max(a_1, a_2, |w_1|, |w_2|) so that the squares in the secular
  // equation neither overflow nor underflow for any axis ratio. A semi-axis below 1e-150 t
  // counts as zero: its square would underflow, and the error made is below 1e-150 t.
  const double t = std::max({a[0], a[1], std::abs(w[0]), std::abs(w[1])});
  if (!(t > 0.0)) return {0.0, 0.0};
  for (double& ai : a)
    if (!(ai > 1e-150 * t)) ai = 0.0;
  // Degenerate sets (ALGORITHMS.md 5: g = 0 projects onto the centre): the centre point, or
  // a segment along the axis that is not zero; both are exact.
  if (!(a[0] > 0.0) && !(a[1] > 0.0)) return {0.0, 0.0};
  if (!(a[0] > 0.0)) return {0.0, std::clamp(w[1], -a[1], a[1])};
  if (!(a[1] > 0.0)) return {std::clamp(w[0], -a[0], a[0]), 0.0};
  if (ellipseNorm(w, a) <= 1.0) return w;
  // A disc (isotropic friction, F1 = F2): radial scaling, exact up to one rounding.
  if (a[0] == a[1]) {
    const double r = std::hypot(w[0], w[1]);
    return {a[0] * (w[0] / r), a[0] * (w[1] / r)};
  }
  // Outside an ellipse: the KKT condition w - y = h diag(1/a^2) y gives
  // y_i = a_i^2 w_i / (a_i^2 + h) with h > 0 the root of
  //   s(h) = sum (a_i w_i / (a_i^2 + h))^2 - 1.
  // s is convex and decreasing with s(0) > 0, so Newton from h = 0 increases monotonically
  // to the root (ALGORITHMS.md 5); the bracket [lo, hi] (s(hi) <= 0 at hi = ||diag(a) w||)
  // guards it against round-off with bisection. w_i = 0 gives y_i = 0 exactly.
  const double as[2] = {a[0] / t, a[1] / t}, ws[2] = {w[0] / t, w[1] / t};
  const double aw[2] = {as[0] * ws[0], as[1] * ws[1]};
  double lo = 0.0, hi = std::hypot(aw[0], aw[1]);
  double h = 0.0;
  for (int it = 0; it < 300; ++it) {
    double s = -1.0, ds = 0.0;
    for (int i = 0; i < 2; ++i) {
      const double d = as[i] * as[i] + h, q = aw[i] / d;
      s += q * q;
      ds -= 2.0 * q * q / d;
    }
    if (s > 0.0) lo = h;
    else hi = h;
    double next = ds < 0.0 ? h - s / ds : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    // Relative 1e-15 in h: Newton converges quadratically there, so y is exact to round-off.
    const bool done = std::abs(next - h) <= 1e-15 * next;
    h = next;
    if (done || !(hi > lo)) break;
  }
  std::array<double, 2> y{t * (as[0] * as[0] * ws[0] / (as[0] * as[0] + h)),
                          t * (as[1] * as[1] * ws[1] / (as[1] * as[1] + h))};
  // Land exactly on the boundary: the residual of h leaves y off it by round-off, and MPGP
  // classifies blocks as active by ||E y|| >= 1 - 1e-12.
  const double norm = ellipseNorm(y, a);
  if (norm > 0.0) {
    y[0] /= norm;
    y[1] /= norm;
  }
  return y;
}

std::array<double, 2> SeparableSet::effectiveAxes(size_t k) const {
  // Semi-axes below what doubles can resolve around the centre (~1e-16 |c|) would leave
  // projected points off the boundary and stall MPGP; below 1e-10 |c| they count as zero
  // (a node whose slip bound is round-off is out of contact).
  const double floor = 1e-10 * std::max(std::abs(center_[k][0]), std::abs(center_[k][1]));
  std::array<double, 2> a = semiAxes_[k];
  for (int j = 0; j < 2; ++j)
    if (a[j] <= floor || ellipseIndex_[k][j] < 0) a[j] = 0.0;  // an absent row is a zero axis
  return a;
}

void SeparableSet::addBound(int localIndex, double lower) {
  boundIndex_.push_back(localIndex);
  lower_.push_back(lower);
}

void SeparableSet::addEllipse(std::array<int, 2> localIndex, std::array<double, 2> center,
                              std::array<double, 2> semiAxes) {
  ellipseIndex_.push_back(localIndex);
  center_.push_back(center);
  semiAxes_.push_back(semiAxes);
}

void SeparableSet::setSemiAxes(int k, std::array<double, 2> semiAxes) { semiAxes_.at(k) = semiAxes; }
int SeparableSet::numBounds() const { return static_cast<int>(boundIndex_.size()); }
int SeparableSet::numEllipses() const { return static_cast<int>(ellipseIndex_.size()); }

void SeparableSet::project(Vector& x) const {
  auto v = x.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (size_t k = 0; k < boundIndex_.size(); ++k) v(boundIndex_[k], 0) = std::max(v(boundIndex_[k], 0), lower_[k]);
  for (size_t k = 0; k < ellipseIndex_.size(); ++k) {
    const auto [i, j] = ellipseIndex_[k];
    const std::array<double, 2> d{at(v, i) - center_[k][0], at(v, j) - center_[k][1]};
    const auto y = projectOntoEllipse(d, effectiveAxes(k));
    // A point inside stays as it is: centre + (x - centre) would round it in its last bit, so a
    // feasible x would not be a fixed point of the projection (Mpgp's gradientGiven).
    if (y == d) continue;
    if (i >= 0) v(i, 0) = center_[k][0] + y[0];
    if (j >= 0) v(j, 0) = center_[k][1] + y[1];
  }
}

bool SeparableSet::contains(const Vector& x, double tolerance) const {
  auto v = x.getLocalViewHost(Tpetra::Access::ReadOnly);
  int ok = 1;
  for (size_t k = 0; k < boundIndex_.size() && ok; ++k)
    if (v(boundIndex_[k], 0) < lower_[k] - tolerance * std::max(1.0, std::abs(lower_[k]))) ok = 0;
  for (size_t k = 0; k < ellipseIndex_.size() && ok; ++k) {
    const auto [i, j] = ellipseIndex_[k];
    const std::array<double, 2> y{at(v, i) - center_[k][0], at(v, j) - center_[k][1]};
    const auto p = projectOntoEllipse(y, effectiveAxes(k));
    const double scale = std::max({1.0, semiAxes_[k][0], semiAxes_[k][1]});
    if (std::hypot(y[0] - p[0], y[1] - p[1]) > tolerance * scale) ok = 0;
  }
  int all = 0;
  Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MIN, 1, &ok, &all);
  return all == 1;
}

double SeparableSet::maxFeasibleStep(const Vector& x, const Vector& p, bool slideOnEllipses) const {
  auto xv = x.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto pv = p.getLocalViewHost(Tpetra::Access::ReadOnly);
  double step = kInfinity;
  for (size_t k = 0; k < boundIndex_.size(); ++k) {
    const double pk = pv(boundIndex_[k], 0);
    if (pk > 0.0) step = std::min(step, std::max(0.0, (xv(boundIndex_[k], 0) - lower_[k]) / pk));
  }
  for (size_t k = 0; k < ellipseIndex_.size(); ++k) {
    const auto [i, j] = ellipseIndex_[k];
    const auto a = effectiveAxes(k);
    const double y[2] = {at(xv, i) - center_[k][0], at(xv, j) - center_[k][1]};
    const double d[2] = {at(pv, i), at(pv, j)};
    if (!(a[0] > 0.0) || !(a[1] > 0.0)) {
      // Degenerate: no motion across a zero axis; along the other axis an interval.
      for (int ax = 0; ax < 2; ++ax) {
        if (!(a[ax] > 0.0)) {
          if (d[ax] != 0.0) step = 0.0;
        } else if (d[ax] > 0.0) {
          step = std::min(step, std::max(0.0, (y[ax] + a[ax]) / d[ax]));
        } else if (d[ax] < 0.0) {
          step = std::min(step, std::max(0.0, (y[ax] - a[ax]) / d[ax]));
        }
      }
      continue;
    }
    if (slideOnEllipses && ellipseNorm({y[0], y[1]}, a) >= 1.0 - ellipseActiveTolerance(center_[k], std::min(a[0], a[1])))
      continue;  // active: slides along its tangent, projected back afterwards
    // ||E (y - alpha d)||^2 = 1 with E = diag(1/a): the positive root.
    const double Ey[2] = {y[0] / a[0], y[1] / a[1]}, Ed[2] = {d[0] / a[0], d[1] / a[1]};
    const double qa = Ed[0] * Ed[0] + Ed[1] * Ed[1];
    if (!(qa > 0.0)) continue;
    const double qb = Ey[0] * Ed[0] + Ey[1] * Ed[1];
    const double qc = std::min(Ey[0] * Ey[0] + Ey[1] * Ey[1] - 1.0, 0.0);
    const double disc = std::sqrt(std::max(qb * qb - qa * qc, 0.0));
    // alpha = (qb + disc) / qa, computed without cancellation when qb < 0.
    const double alpha = qb >= 0.0 ? (qb + disc) / qa : (qc == 0.0 ? 0.0 : -qc / (disc - qb));
    step = std::min(step, std::max(alpha, 0.0));
  }
  double global = kInfinity;
  Teuchos::reduceAll(*x.getMap()->getComm(), Teuchos::REDUCE_MIN, 1, &step, &global);
  return global;
}

void SeparableSet::splitGradient(const Vector& x, const Vector& g, Vector& phi, Vector& beta,
                                 bool slideOnEllipses) const {
  // g^P = -P_T(-g) with T the tangent cone of Omega at x; phi = g on blocks where x is
  // interior (0 on active blocks), beta = g^P - phi (ALGORITHMS.md 5). Per block type:
  //  - bound at x = l: T = {d >= 0}, g^P = min(g, 0) (n = -e_i);
  //  - smooth ellipse boundary: T = {d : n^T d <= 0}, g^P = g - min(n^T g, 0) n;
  //  - point (a = 0): T = {0}, g^P = 0 (any g is balanced by the constraint);
  //  - segment (one a_j = 0): fixed along the zero axis (g^P = 0 there) and an interval
  //    along the other, free inside it and a bound at either end.
  // A degenerate block is never "free": phi = 0 on its fixed axis, so CG and expansion
  // steps never move it off its segment/point, and only its interval axis can be free.
  phi.assign(g);
  beta.putScalar(0.0);
  auto xv = x.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto fv = phi.getLocalViewHost(Tpetra::Access::ReadWrite);
  auto bv = beta.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (size_t k = 0; k < boundIndex_.size(); ++k) {
    const int i = boundIndex_[k];
    if (boundActive(xv(i, 0), lower_[k])) {
      fv(i, 0) = 0.0;
      bv(i, 0) = std::min(gv(i, 0), 0.0);
    }
  }
  for (size_t k = 0; k < ellipseIndex_.size(); ++k) {
    const auto [i, j] = ellipseIndex_[k];
    const auto a = effectiveAxes(k);
    const std::array<double, 2> y{at(xv, i) - center_[k][0], at(xv, j) - center_[k][1]};
    const double gi = at(gv, i), gj = at(gv, j);
    if (!(a[0] > 0.0) || !(a[1] > 0.0)) {
      // Degenerate ellipse: fixed along zero axes; an interval along a positive one.
      const int idx[2] = {i, j};
      const double gg[2] = {gi, gj};
      for (int ax = 0; ax < 2; ++ax) {
        if (idx[ax] < 0) continue;  // an absent row
        if (!(a[ax] > 0.0)) {
          fv(idx[ax], 0) = 0.0;
          bv(idx[ax], 0) = 0.0;
          continue;
        }
        const double gp = intervalProjectedGradient(y[ax], -a[ax], a[ax], gg[ax]);
        const bool interior = std::abs(y[ax]) < a[ax] * (1.0 - ellipseActiveTolerance(center_[k], a[ax]));
        fv(idx[ax], 0) = interior ? gg[ax] : 0.0;
        bv(idx[ax], 0) = interior ? 0.0 : gp;
      }
      continue;
    }
    if (ellipseNorm(y, a) < 1.0 - ellipseActiveTolerance(center_[k], std::min(a[0], a[1]))) continue;  // interior: free
    // Active: outer unit normal n ~ (y_1/a_1^2, y_2/a_2^2); beta = g - min(n^T g, 0) n.
    std::array<double, 2> n{y[0] / (a[0] * a[0]), y[1] / (a[1] * a[1])};
    const double nn = std::hypot(n[0], n[1]);
    n = {n[0] / nn, n[1] / nn};
    if (slideOnEllipses) {
      // Linearised face: the tangential part is free, only a normal part pointing inwards is chopped.
      const double ngFull = n[0] * gi + n[1] * gj, released = std::max(ngFull, 0.0);
      fv(i, 0) = gi - ngFull * n[0];
      fv(j, 0) = gj - ngFull * n[1];
      bv(i, 0) = released * n[0];
      bv(j, 0) = released * n[1];
      continue;
    }
    const double ng = std::min(n[0] * gi + n[1] * gj, 0.0);
    fv(i, 0) = 0.0;
    fv(j, 0) = 0.0;
    bv(i, 0) = gi - ng * n[0];
    bv(j, 0) = gj - ng * n[1];
  }
}

bool SeparableSet::onSmoothBoundary(size_t k, double xi, double xj, std::array<double, 2>& y,
                                    std::array<double, 2>& a) const {
  a = effectiveAxes(k);
  if (!(a[0] > 0.0) || !(a[1] > 0.0)) return false;  // intervals and points: flat
  y = {xi - center_[k][0], xj - center_[k][1]};
  return !(ellipseNorm(y, a) < 1.0 - ellipseActiveTolerance(center_[k], std::min(a[0], a[1])));
}

double SeparableSet::boundaryCurvature(const Vector& x, const Vector& g, const Vector& d) const {
  auto xv = x.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto dv = d.getLocalViewHost(Tpetra::Access::ReadOnly);
  std::vector<double> terms;  // one per active ellipse, summed independently of the layout
  for (size_t k = 0; k < ellipseIndex_.size(); ++k) {
    const auto [i, j] = ellipseIndex_[k];
    std::array<double, 2> y, a;
    if (!onSmoothBoundary(k, at(xv, i), at(xv, j), y, a)) continue;
    const auto [kappa, n, nn] = arcAt(y, a);
    const double pressing = std::max(-(n[0] * at(gv, i) + n[1] * at(gv, j)) / nn, 0.0);
    terms.push_back(kappa * pressing * (at(dv, i) * at(dv, i) + at(dv, j) * at(dv, j)));
  }
  // At most one term per two entries of x.
  return sumOver(x, terms.data(), terms.size(), static_cast<long long>(x.getGlobalLength()));
}

void SeparableSet::addCurvatureProduct(const Vector& x, const Vector& g, const Vector& d, Vector& out) const {
  auto xv = x.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto gv = g.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto dv = d.getLocalViewHost(Tpetra::Access::ReadOnly);
  auto ov = out.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (size_t k = 0; k < ellipseIndex_.size(); ++k) {
    const auto [i, j] = ellipseIndex_[k];
    std::array<double, 2> y, a;
    if (!onSmoothBoundary(k, at(xv, i), at(xv, j), y, a)) continue;
    // As in boundaryCurvature: kappa times the multiplier |n^T g|, on the tangential part of d.
    const auto [kappa, outward, nn] = arcAt(y, a);
    const std::array<double, 2> n{outward[0] / nn, outward[1] / nn};
    const double pressing = std::max(-(n[0] * at(gv, i) + n[1] * at(gv, j)), 0.0);
    const double di = at(dv, i), dj = at(dv, j), nd = n[0] * di + n[1] * dj;
    ov(i, 0) += kappa * pressing * (di - nd * n[0]);
    ov(j, 0) += kappa * pressing * (dj - nd * n[1]);
  }
}

void SeparableSet::reducedFreeGradient(const Vector& x, const Vector& phi, double alpha, Vector& out) const {
  // phi~ = (x - P(x - alpha phi)) / alpha.
  out.update(1.0, x, -alpha, phi, 0.0);
  project(out);
  out.update(1.0 / alpha, x, -1.0 / alpha);
}

}  // namespace tribos::qp
