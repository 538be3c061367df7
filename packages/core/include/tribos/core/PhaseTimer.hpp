#pragma once
/// \file PhaseTimer.hpp
/// The run's phase timers through Teuchos::StackedTimer: a phase is named "Phase" or
/// "Phase: subphase" and nests by scope (a phase started inside another is its child, the
/// path "tribos@assembly"). The driver starts them once per run (startPhaseTimers) and reads
/// them at the end (finishPhaseTimers: the JSON summary's "timers"); without a start (library
/// use, tests) ScopedPhase does nothing. Main thread only (StackedTimer is not thread-safe);
/// the phases are collective steps, timed on every rank.
#include <string>
#include <vector>

namespace Teuchos {
template <class Ordinal>
class Comm;
}

namespace tribos::core {

/// Times its scope as the phase `name` below the phase that encloses it.
class ScopedPhase {
 public:
  explicit ScopedPhase(std::string name);
  ~ScopedPhase();
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  std::string name_;
  bool active_;
};

/// One phase of the run: its path (root@phase@subphase), wall seconds (the slowest and the
/// fastest rank) and how often it ran.
struct PhaseTime {
  std::string path;
  double maxSeconds = 0.0, minSeconds = 0.0;
  long long calls = 0;
};

/// Starts the run's timers (the root phase `root`), replacing any earlier ones.
void startPhaseTimers(const std::string& root);
/// Stops them and returns every phase that ran, the root first, then in the order of first
/// start. Seconds are reduced over the ranks when every rank ran the same phases (else rank
/// 0's, and `sameOnEveryRank` false). Collective; empty without startPhaseTimers.
std::vector<PhaseTime> finishPhaseTimers(const Teuchos::Comm<int>& comm, bool* sameOnEveryRank = nullptr);

}  // namespace tribos::core
