// "Tacho" (Trilinos's Tacho::Driver) behind SparseCholesky is not wired in this version:
// CHOLMOD is the measured default (doc/factorization.md). Asking for it is a clear error,
// not a silent fallback.
#include <stdexcept>

#include "SparseCholeskyImpl.hpp"
#include "tribos/core/Errors.hpp"

namespace tribos::feti {

std::unique_ptr<SparseCholesky> makeTachoCholesky() {
  throw core::InputError(
      "FETI/Factorization: \"Tacho\" is not available in this build of Tribos (the Tacho::Driver "
      "adapter is not implemented yet); use \"CHOLMOD\"");
}

}  // namespace tribos::feti
