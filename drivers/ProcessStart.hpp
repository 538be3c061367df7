#pragma once
// What the process fixes in its own environment before MPI_Init: a stack limit large enough
// for Open MPI and the solver, and idle OpenMP threads that sleep; limits Open MPI cannot start
// under are said as such. The stack and the wait policy take effect only in a fresh image of the
// program (glibc sizes thread stacks and libgomp reads its wait policy at load time), so the
// binary executes itself again, once, when either changes.

namespace tribos::driver {

/// The smallest stack limit (ulimit -s) tribos runs under. Open MPI cannot start its daemon
/// below about 256 KiB (measured: 128 KiB ends in MPI_Init, exit 1, with orte_init's report;
/// 256 KiB solves the bricks and the Hertz cylinder on 2 threads); 1 MiB leaves a margin.
constexpr long kMinStackKiB = 1024;
/// The stack limit a lower soft limit is raised to, where the hard limit allows (Linux's usual).
constexpr long kWantedStackKiB = 8192;

/// The smallest file size limit (ulimit -f) tribos starts under: Open MPI's PMIx creates a
/// lock file of about 4 MiB in MPI_Init (measured: 4000 KiB ends there, exit 1; 4500 starts).
constexpr long kMinFileSizeKiB = 8192;

/// What the tribos launcher (drivers/Launcher.cpp) sets before it runs the solver's image: the
/// soft stack limit raised as prepareProcess raises it (where the hard limit allows) and
/// OMP_WAIT_POLICY=PASSIVE as prepareProcess sets it. Says nothing: the solver checks and
/// reports the limits itself. Returns whether either changed.
bool prepareEnvironment();

/// Refuses a file size limit below kMinFileSizeKiB. Raises a soft stack limit below kWantedStackKiB (up to the hard limit) and sets
/// OMP_WAIT_POLICY=PASSIVE when the user chose no policy and runs more than one thread; then, if
/// either changed, executes this binary again with the same arguments. Returns the exit status
/// core::kExitBadInput, after saying so on stderr, when the hard stack limit is below kMinStackKiB
/// or the file size limit below kMinFileSizeKiB;
/// otherwise 0 (also when the exec fails: then the run goes on as it is).
int prepareProcess(char** argv);

}  // namespace tribos::driver
