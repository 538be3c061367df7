// tribos: the command users run. It sets up what the solver must find when its image loads and
// runs the solver (tribos-solver, beside this program) in this same process:
//  - a soft stack limit of 8 MiB where the hard limit allows (glibc sizes thread stacks at load
//    time), and
//  - OMP_WAIT_POLICY=PASSIVE where the user chose none (libgomp reads it once, at load time:
//    ProcessStart.hpp says why idle threads must sleep).
// The solver can do both itself by executing itself again, but then it loads its shared
// libraries twice: a one-rank run of a 645-node scene took 0.158 s that way and 0.126 s with the
// environment set before it started (issue 46; doc/measurements/performance.md). This program
// loads nothing but libc. The solver still checks every limit and reports it (exit 2), so this
// one says nothing unless the solver cannot be run.
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <iostream>
#include <string>

#include "ProcessStart.hpp"

int main(int argc, char** argv) {
  (void)argc;
  tribos::driver::prepareEnvironment();
  char self[PATH_MAX];
  const ssize_t length = readlink("/proc/self/exe", self, sizeof(self) - 1);
  std::string solver = "tribos-solver";
  if (length > 0) {
    const std::string path(self, static_cast<size_t>(length));
    solver = path.substr(0, path.rfind('/') + 1) + solver;
  }
  execv(solver.c_str(), argv);
  std::cerr << "tribos: error: cannot run the solver " << solver << ": " << std::strerror(errno)
            << " (tribos-solver is installed beside tribos; copy both)\n";
  return 1;  // core::kExitInternal: the installation is broken
}
