#pragma once
/// \file FixedPointWatch.hpp
/// Watches the relative slip-bound changes ||g_{k+1} - g_k|| / ||g_k|| of the Coulomb
/// successive approximations (paper (20)) and decides when they diverge: the change grew in
/// `window` consecutive updates, after a warm-up of a few updates (the first update comes
/// from g = 0 and is infinite; the next ones may rise while the contact zone settles). A NaN
/// change is divergence at once. No Trilinos here: the unit test feeds it sequences.
#include <cmath>
#include <string>
#include <vector>

namespace tribos::contact {

class FixedPointWatch {
 public:
  /// `window`: consecutive growths that mean divergence; `warmUp`: updates before the first
  /// verdict besides the window itself.
  explicit FixedPointWatch(int window, int warmUp = 3) : window_(window), warmUp_(warmUp) {}

  /// Records one change; returns true when the sequence diverges (then message() says why).
  bool diverges(double change) {
    changes_.push_back(change);
    if (std::isnan(change)) {
      message_ = "diverged: the slip bound became NaN";
      return true;
    }
    const int n = static_cast<int>(changes_.size());
    if (n <= window_ + warmUp_) return false;
    for (int i = 0; i < window_; ++i)
      if (!(changes_[n - 1 - i] > changes_[n - 2 - i])) return false;
    message_ = "the Coulomb fixed point diverges: the slip bound change grew in " + std::to_string(window_) +
               " consecutive updates (last " + std::to_string(change) + ")";
    return true;
  }
  const std::string& message() const { return message_; }

 private:
  int window_, warmUp_;
  std::vector<double> changes_;
  std::string message_;
};

}  // namespace tribos::contact
