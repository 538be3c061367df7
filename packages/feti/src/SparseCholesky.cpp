#include "tribos/feti/SparseCholesky.hpp"

#include "SparseCholeskyImpl.hpp"
#include "tribos/core/Errors.hpp"

namespace tribos::feti {

std::mutex& blasMutex() {
  static std::mutex m;
  return m;
}

std::vector<std::string> sparseCholeskyNames() { return {"CHOLMOD", "Tacho"}; }

std::unique_ptr<SparseCholesky> makeSparseCholesky(const std::string& name, const SparseCholeskyOptions& options) {
  if (name == "CHOLMOD") return makeCholmodCholesky(options);
  if (name == "Tacho") return makeTachoCholesky();
  std::string valid;
  for (const auto& n : sparseCholeskyNames()) valid += " \"" + n + "\"";
  throw core::InputError("FETI/Factorization: \"" + name + "\" is not a sparse Cholesky; valid:" + valid);
}

}  // namespace tribos::feti
