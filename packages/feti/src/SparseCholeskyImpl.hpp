#pragma once
// Internal: the implementations behind makeSparseCholesky.
#include <memory>
#include <vector>

#include "tribos/feti/SparseCholesky.hpp"

namespace tribos::feti {
std::unique_ptr<SparseCholesky> makeCholmodCholesky();
/// Fill-reducing ordering (METIS_NodeND): perm[k] = the row eliminated k-th.
std::vector<LO> nestedDissection(const fem::CsrMatrix& A);
}  // namespace tribos::feti
