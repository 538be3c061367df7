#include "tribos/stack/SolveBudget.hpp"

#include <cstdio>

#include "tribos/core/Format.hpp"

namespace tribos::stack {

std::function<bool()> WallClockBudget::stopRequest() {
  if (maxSeconds_ <= 0.0) return nullptr;
  return [this] { return spent(); };
}

bool WallClockBudget::spent() {
  if (ranOut_) return true;
  // Clocks differ between ranks: rank 0's decides.
  double elapsed = clock_.seconds();
  MPI_Bcast(&elapsed, 1, MPI_DOUBLE, 0, comm_);
  if (elapsed >= maxSeconds_) {
    ranOut_ = true;
    ranOutAfter_ = elapsed;
  }
  return ranOut_;
}

std::string WallClockBudget::message() const {
  char after[32];
  std::snprintf(after, sizeof after, "%.2f", ranOutAfter_);
  return "stopped: Solver/Max Seconds = " + core::formatNumber(maxSeconds_) + " reached after " + after + " s";
}

std::string capMessage(const std::string& parameterPath, long long cap, const std::string& detail) {
  return "stopped: " + parameterPath + " = " + std::to_string(cap) + " reached" + (detail.empty() ? "" : " " + detail);
}

}  // namespace tribos::stack
