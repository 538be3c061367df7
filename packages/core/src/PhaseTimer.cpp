// The run's phase timers on Teuchos::StackedTimer (PhaseTimer.hpp).
#include "tribos/core/PhaseTimer.hpp"

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_StackedTimer.hpp>

#include <algorithm>
#include <functional>
#include <memory>

namespace tribos::core {

namespace {
/// The timers of the run in progress, and the paths of the phases in the order they first
/// started (StackedTimer has no public walk of its tree).
struct RunTimers {
  std::unique_ptr<Teuchos::StackedTimer> timer;
  std::vector<std::string> stack, paths;
};
RunTimers& runTimers() {
  static RunTimers timers;
  return timers;
}
}  // namespace

ScopedPhase::ScopedPhase(std::string name) : name_(std::move(name)), active_(runTimers().timer != nullptr) {
  if (!active_) return;
  RunTimers& t = runTimers();
  t.stack.push_back(t.stack.back() + "@" + name_);
  if (std::find(t.paths.begin(), t.paths.end(), t.stack.back()) == t.paths.end()) t.paths.push_back(t.stack.back());
  t.timer->start(name_, false);
}

ScopedPhase::~ScopedPhase() {
  RunTimers& t = runTimers();
  if (!active_ || !t.timer) return;
  t.timer->stop(name_, false);
  t.stack.pop_back();
}

void startPhaseTimers(const std::string& root) {
  RunTimers& t = runTimers();
  t.timer = std::make_unique<Teuchos::StackedTimer>(root.c_str());
  t.stack = {root};
  t.paths = {root};
}

std::vector<PhaseTime> finishPhaseTimers(const Teuchos::Comm<int>& comm, bool* sameOnEveryRank) {
  RunTimers& t = runTimers();
  std::vector<PhaseTime> phases;
  if (!t.timer) return phases;
  t.timer->stopBaseTimer();
  for (const std::string& path : t.paths) {
    const auto info = t.timer->findTimer(path);
    phases.push_back({path, info.time, info.time, static_cast<long long>(info.count)});
  }
  t.timer.reset();
  // The same phases on every rank: the same number and the same hash of their paths.
  std::size_t hash = phases.size();
  for (const auto& p : phases) hash = hash * 31 + std::hash<std::string>{}(p.path);
  long long mine[2] = {static_cast<long long>(hash % 1000000007), -static_cast<long long>(hash % 1000000007)};
  long long all[2] = {0, 0};
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, 2, mine, all);
  const bool same = all[0] == -all[1];
  if (sameOnEveryRank) *sameOnEveryRank = same;
  if (!same || comm.getSize() == 1) return phases;
  std::vector<double> seconds(phases.size()), slowest(phases.size()), fastest(phases.size());
  for (size_t i = 0; i < phases.size(); ++i) seconds[i] = phases[i].maxSeconds;
  const int n = static_cast<int>(seconds.size());
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, n, seconds.data(), slowest.data());
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MIN, n, seconds.data(), fastest.data());
  for (size_t i = 0; i < phases.size(); ++i) {
    phases[i].maxSeconds = slowest[i];
    phases[i].minSeconds = fastest[i];
  }
  return phases;
}

}  // namespace tribos::core
