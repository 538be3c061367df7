#include "tribos/core/SingletonStart.hpp"

#include <unistd.h>

#include <cstdlib>
#include <string>
#include <utility>

namespace tribos::core {

namespace {
bool setIfUnset(const char* name, const std::string& value) {
  if (std::getenv(name) != nullptr) return false;
  return setenv(name, value.c_str(), 0) == 0;
}
}  // namespace

bool chooseQuickSingletonStart() {
  for (const char* launcher : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(launcher) != nullptr) return false;
  bool changed = false;
  if (std::getenv("OMPI_MCA_ess_singleton_isolated") == nullptr) {
    // Isolated singletons all take job family 0, so their session directories would be one
    // (<tmp>/ompi.<host>.<uid>/jf.0/1), which the first to finish removes under the others: 1 of
    // 20 concurrent runs failed in MPI_Init ("orte_session_dir failed"). A directory of its
    // own per process (Open MPI creates it and removes it at MPI_Finalize): 0 of 20.
    const char* tmp = std::getenv("TMPDIR");
    const std::string base = tmp && *tmp ? tmp : "/tmp";
    changed = setIfUnset("OMPI_MCA_orte_jobfam_session_dir",
                         base + "/ompi.tribos." + std::to_string(getuid()) + "." + std::to_string(getpid())) ||
              changed;
    changed = setIfUnset("OMPI_MCA_ess_singleton_isolated", "1") || changed;
  }
  changed = setIfUnset("OMPI_MCA_pml", "ob1") || changed;
  return changed;
}

}  // namespace tribos::core
