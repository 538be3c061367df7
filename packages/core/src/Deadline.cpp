#include "tribos/core/Deadline.hpp"

#include <cstdio>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"

namespace tribos::core {

std::string Deadline::message(double after) const {
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.2f", after);
  return "stopped: Solver/Max Seconds = " + formatNumber(maxSeconds_) + " reached after " + seconds + " s";
}

void Deadline::stop(double after, const std::string& phase) const {
  throw LimitReached(message(after) + ", during " + phase + " (nothing solved, no results written)");
}

void Deadline::check(const std::string& phase, MPI_Comm comm) const {
  if (!limited()) return;
  double after = elapsed();
  MPI_Bcast(&after, 1, MPI_DOUBLE, 0, comm);
  if (after >= maxSeconds_) stop(after, phase);
}

void Deadline::agree(bool stoppedHere, const std::string& phase, MPI_Comm comm) const {
  if (!limited()) return;
  int mine = stoppedHere ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm);
  double after = elapsed();
  MPI_Bcast(&after, 1, MPI_DOUBLE, 0, comm);
  if (any) stop(after, phase);
}

}  // namespace tribos::core
