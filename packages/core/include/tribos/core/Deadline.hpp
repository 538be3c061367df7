#pragma once
/// \file Deadline.hpp
/// Solver/Max Seconds as one deadline for the whole run, counted from its start: checked
/// between the set-up's phases, inside the factorisation (between subdomains) and at every
/// iteration of the solve, so that a run stops within a fraction of a second of it.
#include <mpi.h>

#include <string>

#include "tribos/core/Timer.hpp"

namespace tribos::core {

class Deadline {
 public:
  /// No deadline.
  Deadline() = default;
  /// `maxSeconds` after `start` (the start of the run); 0: none.
  Deadline(double maxSeconds, Stopwatch start) : maxSeconds_(maxSeconds), clock_(start) {}

  bool limited() const { return maxSeconds_ > 0.0; }
  double maxSeconds() const { return maxSeconds_; }
  double elapsed() const { return clock_.seconds(); }
  /// This rank's clock only (no communication; safe on threads).
  bool passed() const { return limited() && elapsed() >= maxSeconds_; }

  /// Collective over `comm`: throws LimitReached on every rank when rank 0's clock has passed
  /// the deadline (one clock decides, so every rank throws or none).
  void check(const std::string& phase, MPI_Comm comm) const;
  /// Collective over `comm`, after a loop that each rank left early when passed() (then
  /// `stoppedHere`): throws LimitReached on every rank when any rank stopped.
  void agree(bool stoppedHere, const std::string& phase, MPI_Comm comm) const;

  /// "stopped: Solver/Max Seconds = 10 reached after 10.02 s".
  std::string message(double after) const;

 private:
  [[noreturn]] void stop(double after, const std::string& phase) const;

  double maxSeconds_ = 0.0;
  Stopwatch clock_;
};

}  // namespace tribos::core
