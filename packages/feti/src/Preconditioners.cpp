// The dual preconditioners (Preconditioners.hpp).
#include "Preconditioners.hpp"

namespace tribos::feti {

namespace {
// The rows `rows` and columns with position[col] >= 0 of K, columns renumbered by `position`;
// `upper`: only the columns at or after the row's own position (rows = the columns, ascending).
KBlock extractBlock(const fem::CsrMatrix& K, const std::vector<LO>& rows, const std::vector<LO>& position,
                    bool upper = false) {
  auto keep = [&](size_t row, LO col) { return position[col] >= (upper ? static_cast<LO>(row) : 0); };
  // Counted first, so that the blocks, kept for the whole solve, hold no spare capacity (with
  // push_back growth alone they held up to twice their entries: doc/measurements/scalability.md).
  size_t entries = 0;
  for (size_t r = 0; r < rows.size(); ++r)
    for (LO k = K.rowPtr[rows[r]]; k < K.rowPtr[rows[r] + 1]; ++k) entries += keep(r, K.colInd[k]);
  KBlock A;
  A.rowPtr.reserve(rows.size() + 1);
  A.colInd.reserve(entries);
  A.values.reserve(entries);
  A.rowPtr.push_back(0);
  for (size_t r = 0; r < rows.size(); ++r) {
    const LO i = rows[r];
    for (LO k = K.rowPtr[i]; k < K.rowPtr[i + 1]; ++k)
      if (keep(r, K.colInd[k])) {
        A.colInd.push_back(position[K.colInd[k]]);
        A.values.push_back(K.values[k]);
      }
    A.rowPtr.push_back(static_cast<LO>(A.colInd.size()));
    // applySymmetric takes each row's first entry for its diagonal (K stores every node's
    // diagonal block, so it is there).
    TEUCHOS_TEST_FOR_EXCEPTION(upper && (A.rowPtr[r + 1] == A.rowPtr[r] || A.colInd[A.rowPtr[r]] != static_cast<LO>(r)),
                               std::logic_error, "tribos::feti: K has no diagonal entry in row " << i);
  }
  const LO columns = static_cast<LO>(std::count_if(position.begin(), position.end(), [](LO p) { return p >= 0; }));
  if (columns <= 65536) {
    A.colShort.assign(A.colInd.begin(), A.colInd.end());
    std::vector<LO>().swap(A.colInd);
  }
  return A;
}

// K_bb (both preconditioners) and, for the Dirichlet one (`interiorToo`), K_ii's factor and K_ib.
void buildBlocks(const OwnedSubdomain& L, DirichletBlocks& D, bool interiorToo, Factorization factorization,
                 const SparseCholeskyOptions& options) {
  std::vector<char> touched(L.n(), 0);
  for (LO d : L.block->dof) touched[d] = 1;
  std::vector<LO> boundary, interior;
  for (LO d = 0; d < L.n(); ++d) (touched[d] ? boundary : interior).push_back(d);
  std::vector<LO> boundaryPosition(L.n(), -1);
  for (size_t k = 0; k < boundary.size(); ++k) boundaryPosition[boundary[k]] = static_cast<LO>(k);
  std::vector<LO> boundaryDof;  // per entry of B_s: the position of its dof among b
  for (LO d : L.block->dof) boundaryDof.push_back(boundaryPosition[d]);
  D.terms = blockTerms(*L.block, L.rowOrder, boundaryDof);
  D.Kbb = extractBlock(L.system.K, boundary, boundaryPosition, /*upper=*/true);
  D.xb.assign(boundary.size(), 0.0);
  D.yb.assign(boundary.size(), 0.0);
  if (!interiorToo || interior.empty()) return;
  D.interiorFactor = makeSparseCholesky(factorization, options);
  D.interiorFactor->factorize(principalSubmatrix(L.system.K, interior));
  // Interior unknowns in the factor's order: K_ib's rows follow it, so the solve runs in place.
  const std::vector<LO>& perm = D.interiorFactor->permutation();
  std::vector<LO> interiorOrdered(interior.size());
  for (size_t k = 0; k < interior.size(); ++k) interiorOrdered[k] = interior[perm[k]];
  D.Kib = extractBlock(L.system.K, interiorOrdered, boundaryPosition);
  D.t.assign(interior.size(), 0.0);
}
}  // namespace

Preconditioners::Preconditioners(int numOwned, bool dirichlet, Factorization factorization,
                                       const SparseCholeskyOptions& options)
    : blocks_(numOwned), dirichlet_(dirichlet), factorization_(factorization), options_(options) {}

Preconditioners::~Preconditioners() = default;

void Preconditioners::build(const OwnedSubdomain& L, int i) {
  buildBlocks(L, blocks_[i], dirichlet_, factorization_, options_);
}

void Preconditioners::applyLumped(const SubdomainSet& set, const DualVector& x, DualVector& y) const {
  const int first = set.firstOwned();
  set.applyBlockwise(x, y, [this, first](OwnedSubdomain& L, bool) {
    // out = B_s K_bb B_s^T in: B_s^T in is zero off b, and B_s reads b only. Each row of K_bb
    // adds its terms in K's column order less the ones that multiply those zeros, with K_ji
    // for K_ij below the diagonal (the stored triangle): B_s K B_s^T to rounding.
    DirichletBlocks& D = blocks_[L.subdomain - first];
    scatterTerms(D.terms, L.in.data(), D.xb.data(), static_cast<LO>(D.xb.size()));
    D.Kbb.applySymmetric(D.xb.data(), D.yb.data());
    gatherTerms(D.terms, D.yb.data(), L.out.data(), L.m());
  });
}

void Preconditioners::applyDirichlet(const SubdomainSet& set, const DualVector& x, DualVector& y) const {
  const int first = set.firstOwned();
  set.applyBlockwise(x, y, [this, first](OwnedSubdomain& L, bool) {
    // x_b = B_s^T in; y_b = K_bb x_b - K_ib^T K_ii^{-1} K_ib x_b; out = B_s y_b. Per subdomain,
    // in one fixed order: the same bits on every rank and thread layout.
    DirichletBlocks& D = blocks_[L.subdomain - first];
    scatterTerms(D.terms, L.in.data(), D.xb.data(), static_cast<LO>(D.xb.size()));
    D.Kbb.applySymmetric(D.xb.data(), D.yb.data());
    if (D.interiorFactor) {
      D.Kib.apply(D.xb.data(), D.t.data());
      D.interiorFactor->solveInPlace(D.t.data());
      D.Kib.subtractTransposed(D.t.data(), D.yb.data());
    }
    gatherTerms(D.terms, D.yb.data(), L.out.data(), L.m());
  });
}

}  // namespace tribos::feti
