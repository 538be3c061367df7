#pragma once
/// \file SolveBudget.hpp
/// Solver/Max Seconds: a wall-clock budget of the solve that every rank sees run out at the
/// same iteration, and the words that say which limit (budget or iteration cap) ended a solve.
#include <mpi.h>

#include <functional>
#include <string>

#include "tribos/core/Deadline.hpp"

namespace tribos::stack {

class WallClockBudget {
 public:
  /// The run's deadline (Solver/Max Seconds from the start of the run; none: no budget).
  WallClockBudget(const core::Deadline& deadline, MPI_Comm comm) : deadline_(deadline), comm_(comm) {}

  /// For SmalseSettings / ProjectedCgSettings::stopRequested: empty without a budget;
  /// otherwise collective (rank 0's clock, broadcast, so that every rank stops at the same
  /// iteration) and true from the first check at or past the budget on. The budget must
  /// outlive the solve that uses it.
  std::function<bool()> stopRequest();

  bool ranOut() const { return ranOut_; }
  /// "stopped: Solver/Max Seconds = 10 reached after 10.02 s".
  std::string message() const;

 private:
  bool spent();

  core::Deadline deadline_;
  MPI_Comm comm_;
  bool ranOut_ = false;
  double ranOutAfter_ = 0.0;
};

/// "stopped: <path> = <cap> reached" and what it adds (`detail`, may be empty).
std::string capMessage(const std::string& parameterPath, long long cap, const std::string& detail);

}  // namespace tribos::stack
