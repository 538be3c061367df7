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

void EqualityNorm::cgStep(double alpha, const Vector& p) {
  // Only the first step after a norm() can follow it (one iteration between stop tests);
  // the coordinates of p come from the product A p of this step.
  if (++stepsSinceNorm_ != 1 || !valid_ || trackedInARow_ >= refreshEvery_ || !Q_.coordinates(p, up_, wp_)) {
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
  stepsSinceNorm_ = 0;
  if (follows) {
    ++trackedInARow_;
    ++tracked_;
    return std::sqrt(std::max(innerProduct(u_, w_), 0.0));
  }
  trackedInARow_ = 0;
  valid_ = Q_.coordinates(x, u_, w_);
  if (!valid_) return Q_.normQ(x, scratch);
  return std::sqrt(std::max(innerProduct(u_, w_), 0.0));
}

}  // namespace tribos::qp
