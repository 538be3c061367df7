#include "tribos/feti/SparseCholesky.hpp"

#include "SparseCholeskyImpl.hpp"
#include "tribos/core/Errors.hpp"

namespace tribos::feti {

std::mutex& blasMutex() {
  static std::mutex m;
  return m;
}

std::vector<std::string> sparseCholeskyNames() { return core::namesOf(kFactorizationNames); }

std::unique_ptr<SparseCholesky> makeSparseCholesky(Factorization kind, const SparseCholeskyOptions& options) {
  switch (kind) {
    case Factorization::Cholmod: return makeCholmodCholesky(options);
    case Factorization::Tacho: return makeTachoCholesky();
  }
  throw std::logic_error("tribos::feti::makeSparseCholesky: no such factorisation");
}

std::unique_ptr<SparseCholesky> makeSparseCholesky(const std::string& name, const SparseCholeskyOptions& options) {
  try {
    return makeSparseCholesky(core::valueOf(kFactorizationNames, name), options);
  } catch (const std::invalid_argument&) {
    std::string valid;
    for (const auto& n : sparseCholeskyNames()) valid += " \"" + n + "\"";
    throw core::InputError("FETI/Factorization: \"" + name + "\" is not a sparse Cholesky; valid:" + valid);
  }
}

}  // namespace tribos::feti
