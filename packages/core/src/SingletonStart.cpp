#include "tribos/core/SingletonStart.hpp"

#include <cstdlib>
#include <utility>

namespace tribos::core {

bool chooseQuickSingletonStart() {
  for (const char* launcher : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(launcher) != nullptr) return false;
  bool changed = false;
  for (const auto& [name, value] : {std::pair<const char*, const char*>{"OMPI_MCA_ess_singleton_isolated", "1"},
                                    std::pair<const char*, const char*>{"OMPI_MCA_pml", "ob1"}})
    if (std::getenv(name) == nullptr) changed = setenv(name, value, 0) == 0 || changed;
  return changed;
}

}  // namespace tribos::core
