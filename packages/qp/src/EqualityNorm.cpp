#include "EqualityNorm.hpp"

#include <algorithm>
#include <cmath>

namespace tribos::qp {

bool EqualityProjector::coordinates(const Vector&, std::vector<double>&, std::vector<double>&) const {
  return false;
}

namespace {
double innerProduct(const std::vector<double>& u, const std::vector<double>& w) {
  double q = 0.0;
  for (size_t i = 0; i < u.size(); ++i) q += u[i] * w[i];
  return q;
}
}  // namespace

bool EqualityNorm::coordinatesOf(const Vector& x, bool fromProduct, std::vector<double>& u,
                                 std::vector<double>& w) const {
  const EqualityCoordinates* given = fromProduct && lastProduct_ ? lastProduct_() : nullptr;
  if (!given) return Q_.coordinates(x, u, w);
  u = given->u;
  w = given->w;
  return true;
}

void EqualityNorm::cgStep(double alpha, const Vector& p) {
  // Only the first step after a norm() can follow it (one iteration between stop tests);
  // the coordinates of p come from the product A p of this step.
  fromProduct_ = false;
  if (++stepsSinceNorm_ != 1 || !valid_ || trackedInARow_ >= refreshEvery_ || !coordinatesOf(p, true, up_, wp_)) {
    valid_ = false;
    return;
  }
  for (size_t i = 0; i < u_.size(); ++i) {
    u_[i] -= alpha * up_[i];
    w_[i] -= alpha * wp_[i];
  }
}

double EqualityNorm::norm(const Vector& x, Vector& scratch) {
  const bool follows = valid_ && stepsSinceNorm_ == 1;
  const bool fromProduct = fromProduct_;
  stepsSinceNorm_ = 0;
  fromProduct_ = false;
  if (follows) {
    ++trackedInARow_;
    ++tracked_;
    return std::sqrt(std::max(innerProduct(u_, w_), 0.0));
  }
  trackedInARow_ = 0;
  valid_ = coordinatesOf(x, fromProduct, u_, w_);
  if (!valid_) return Q_.normQ(x, scratch);
  return std::sqrt(std::max(innerProduct(u_, w_), 0.0));
}

}  // namespace tribos::qp
