#pragma once
// Paths for tests: the source tree (input/, test data) and a scratch directory.
#include <cstdlib>
#include <string>

namespace tribos::test {
inline std::string sourceDir() {
  const char* dir = std::getenv("TRIBOS_SOURCE_DIR");
  return dir ? dir : TRIBOS_SOURCE_DIR_DEFAULT;
}
}  // namespace tribos::test
