#include "ProcessStart.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <string>

#include "tribos/core/Errors.hpp"

namespace tribos::driver {
namespace {
// Issue 44: under `ulimit -s` 16-64 KiB the run ended in MPI_Init (exit 1, Open MPI's report of a
// daemon that could not start) before any of tribos's code. The soft limit is raised where the
// hard limit allows; a hard limit too small is said as such (sayStackTooSmall).
enum class StackLimit { Unchanged, Raised, TooSmall };
StackLimit raiseStackLimit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_STACK, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return StackLimit::Unchanged;
  const rlim_t wanted = static_cast<rlim_t>(kWantedStackKiB) * 1024;
  if (limit.rlim_cur >= wanted) return StackLimit::Unchanged;
  const rlim_t raised = limit.rlim_max == RLIM_INFINITY ? wanted : std::min(wanted, limit.rlim_max);
  if (raised < static_cast<rlim_t>(kMinStackKiB) * 1024) return StackLimit::TooSmall;
  if (raised <= limit.rlim_cur) return StackLimit::Unchanged;
  limit.rlim_cur = raised;
  return setrlimit(RLIMIT_STACK, &limit) == 0 ? StackLimit::Raised : StackLimit::Unchanged;
}

void sayStackTooSmall() {
  rlimit limit{};
  getrlimit(RLIMIT_STACK, &limit);
  std::cerr << "tribos: error: the stack limit (ulimit -s) is " << limit.rlim_max / 1024
            << " KiB at most; tribos needs at least " << kMinStackKiB << " KiB (Open MPI cannot start below about "
            << "256 KiB): run it under ulimit -s " << kWantedStackKiB << " or more\n";
}

// Issue 44's kin: under ulimit -f 4000 (KiB) Open MPI's PMIx could not create its lock file and
// the run ended in MPI_Init, exit 1, with "PMIX ERROR" lines only (4500 KiB starts). Said as such.
bool fileSizeLimitLetsMpiStart() {
  rlimit limit{};
  if (getrlimit(RLIMIT_FSIZE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return true;
  if (limit.rlim_cur >= static_cast<rlim_t>(kMinFileSizeKiB) * 1024) return true;
  std::cerr << "tribos: error: the file size limit (ulimit -f) is " << limit.rlim_cur / 1024 << " KiB; Open MPI "
            << "creates files of about 4 MiB as it starts: run tribos under a limit of at least " << kMinFileSizeKiB
            << " KiB\n";
  return false;
}

// Idle OpenMP threads must sleep, not spin: with more ranks x threads than free cores the
// spinning threads starve the working ones (input/two_bricks.xml, 2 threads, the other core
// busy: 3.1 s median, up to 20 s, against 0.7 s when they sleep). libgomp reads
// OMP_WAIT_POLICY once, in its load-time constructor, before main runs; so when the user has
// not chosen a policy, set PASSIVE for the next image. One thread never waits, so
// OMP_NUM_THREADS=1 needs none. Returns whether the environment changed.
bool chooseSleepingThreads() {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr) return false;
  if (const char* threads = std::getenv("OMP_NUM_THREADS"); threads && std::string(threads) == "1") return false;
  return setenv("OMP_WAIT_POLICY", "PASSIVE", 0) == 0;
}
}  // namespace

bool prepareEnvironment() {
  const bool stackRaised = raiseStackLimit() == StackLimit::Raised;
  const bool policyChosen = chooseSleepingThreads();
  return stackRaised || policyChosen;
}

int prepareProcess(char** argv) {
  if (!fileSizeLimitLetsMpiStart()) return core::kExitBadInput;
  const StackLimit stack = raiseStackLimit();
  if (stack == StackLimit::TooSmall) {
    sayStackTooSmall();
    return core::kExitBadInput;
  }
  const bool policyChosen = chooseSleepingThreads();
  // Before MPI_Init, so mpirun sees one process; it costs about 0.03 s (a run started by the
  // tribos launcher, drivers/Launcher.cpp, finds both done and does not execute again).
  if (stack == StackLimit::Raised || policyChosen) execv("/proc/self/exe", argv);
  return 0;
}

}  // namespace tribos::driver
