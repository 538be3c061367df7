#include "tribos/stack/SolveBudget.hpp"

#include <cstdio>

#include "tribos/core/Format.hpp"

namespace tribos::stack {

std::function<bool()> WallClockBudget::stopRequest() {
  if (!deadline_.limited()) return nullptr;
  return [this] { return spent(); };
}

bool WallClockBudget::spent() {
  if (ranOut_) return true;
  // Clocks differ between ranks: rank 0's decides.
  double elapsed = deadline_.elapsed();
  MPI_Bcast(&elapsed, 1, MPI_DOUBLE, 0, comm_);
  if (elapsed >= deadline_.maxSeconds()) {
    ranOut_ = true;
    ranOutAfter_ = elapsed;
  }
  return ranOut_;
}

std::string WallClockBudget::message() const { return deadline_.message(ranOutAfter_); }

std::string capMessage(const std::string& parameterPath, long long cap, const std::string& detail) {
  return "stopped: " + parameterPath + " = " + std::to_string(cap) + " reached" + (detail.empty() ? "" : " " + detail);
}

}  // namespace tribos::stack
