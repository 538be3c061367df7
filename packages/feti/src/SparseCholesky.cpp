#include "tribos/feti/SparseCholesky.hpp"

#include "SparseCholeskyImpl.hpp"
#include "tribos/core/Errors.hpp"

namespace tribos::feti {

std::vector<std::string> sparseCholeskyNames() { return {"CHOLMOD"}; }

std::unique_ptr<SparseCholesky> makeSparseCholesky(const std::string& name) {
  if (name == "CHOLMOD") return makeCholmodCholesky();
  std::string valid;
  for (const auto& n : sparseCholeskyNames()) valid += " \"" + n + "\"";
  throw core::InputError("FETI/Factorization: \"" + name + "\" is not a sparse Cholesky; valid:" + valid);
}

}  // namespace tribos::feti
