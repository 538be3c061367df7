#pragma once
// Internal to feti/: a component of T-FETI (BlockKernels.hpp lists them): the dual
// preconditioners, lumped B K B^T and Dirichlet B S B^T (ALGORITHMS.md 9), with the blocks of
// each owned subdomain's K they read.
#include <memory>
#include <vector>

#include "SubdomainSet.hpp"

namespace tribos::feti {

/// A block of K in CSR (rows and columns renumbered), kept with K's column order inside each
/// row. Column indices take 2 bytes when the block has at most 65 536 columns (a subdomain's
/// boundary or interior unknowns: always at the H/h of Table 1): 10 bytes per entry instead
/// of 12; the preconditioner reads these blocks once per application (doc/measurements/performance.md).
/// Three products: with the block (rows), with its transpose (K_bi = K_ib^T read from K_ib),
/// and, for a symmetric block stored as its upper triangle (K_bb), with the whole of it.
struct KBlock {
  std::vector<LO> rowPtr, colInd;      ///< colInd: only when the columns need 4 bytes
  std::vector<std::uint16_t> colShort;  ///< otherwise
  std::vector<double> values;
  /// y = A x
  void apply(const double* x, double* y) const {
    withColumns([&](const auto* col) { applyWith(col, x, y); });
  }
  /// y -= A^T x, rows in order: y_j gets its terms in the order of A's rows.
  void subtractTransposed(const double* x, double* y) const {
    withColumns([&](const auto* col) { subtractTransposedWith(col, x, y); });
  }
  /// y = (U + U^T - diag U) x for A = U, the upper triangle of a symmetric matrix with the
  /// diagonal first in each row. Row i's sum gets its terms in ascending column order, as the
  /// row of the whole matrix would: j < i from the rows before (U_ji = A_ij), then its own.
  void applySymmetric(const double* x, double* y) const {
    withColumns([&](const auto* col) { applySymmetricWith(col, x, y); });
  }
  double bytes() const {
    return 8.0 * values.size() + 4.0 * (colInd.size() + rowPtr.size()) + 2.0 * colShort.size();
  }
  LO rows() const { return static_cast<LO>(rowPtr.size()) - 1; }

 private:
  template <class Op>
  void withColumns(Op op) const {
    if (colInd.empty())
      op(colShort.data());
    else
      op(colInd.data());
  }
  template <class Index>
  void applyWith(const Index* __restrict col, const double* __restrict x, double* __restrict y) const {
    const double* __restrict v = values.data();
    const LO* __restrict start = rowPtr.data();
    for (LO i = 0; i < rows(); ++i) {
      double s = 0.0;
      for (LO k = start[i]; k < start[i + 1]; ++k) s += v[k] * x[col[k]];
      y[i] = s;
    }
  }
  template <class Index>
  void subtractTransposedWith(const Index* __restrict col, const double* __restrict x, double* __restrict y) const {
    const double* __restrict v = values.data();
    const LO* __restrict start = rowPtr.data();
    for (LO i = 0; i < rows(); ++i) {
      const double xi = x[i];
      for (LO k = start[i]; k < start[i + 1]; ++k) y[col[k]] -= v[k] * xi;
    }
  }
  template <class Index>
  void applySymmetricWith(const Index* __restrict col, const double* __restrict x, double* __restrict y) const {
    const double* __restrict v = values.data();
    const LO* __restrict start = rowPtr.data();
    const LO n = rows();
    std::fill(y, y + n, 0.0);
    for (LO i = 0; i < n; ++i) {
      const double xi = x[i];
      double s = y[i] + v[start[i]] * xi;  // the lower part's terms so far, then the diagonal
      for (LO k = start[i] + 1; k < start[i + 1]; ++k) {
        s += v[k] * x[col[k]];
        y[col[k]] += v[k] * xi;
      }
      y[i] = s;
    }
  }
};

/// The dual preconditioners' blocks of one subdomain's K, b = the dofs that B touches, i = the
/// others. Lumped, B K B^T = B K_bb B^T (B^T x vanishes off b and B reads b only): K_bb.
/// Dirichlet, S = K_bb - K_bi K_ii^{-1} K_ib: the same K_bb (one copy serves both) and K_ib,
/// read a second time for K_bi = K_ib^T (K_ii is only factorised, so an application reads
/// neither K_ii nor K's other entries), interior unknowns in the order of K_ii's factor. K_bb
/// is kept as its upper triangle: half the bytes, the product exactly symmetric (K's own
/// entries K_ij and K_ji can differ in the last bit, as the element matrices do). Work vectors.
struct DirichletBlocks {
  std::vector<BlockTerm> terms;  ///< B_s with the dofs numbered among b (blockTerms)
  KBlock Kbb;                   ///< upper triangle, diagonal first in each row
  KBlock Kib;                   ///< rows of i in the factor's order (Dirichlet only)
  std::unique_ptr<SparseCholesky> interiorFactor;  ///< K_ii (none when i is empty)
  std::vector<double> xb, yb, t;
};

class Preconditioners {
 public:
  /// Blocks for `numOwned` subdomains: K_bb for both, with `dirichlet` K_ii's factor and K_ib.
  Preconditioners(int numOwned, bool dirichlet, Factorization factorization, const SparseCholeskyOptions& options);
  ~Preconditioners();
  /// The blocks of owned subdomain i (its factor computed: SubdomainSet::factorize's loop;
  /// each i writes only its own).
  void build(const OwnedSubdomain& L, int i);
  /// y = B K_bb B^T x (lumped), y = B S B^T x (Dirichlet).
  void applyLumped(const SubdomainSet& set, const DualVector& x, DualVector& y) const;
  void applyDirichlet(const SubdomainSet& set, const DualVector& x, DualVector& y) const;
  const DirichletBlocks& blocks(int i) const { return blocks_[i]; }

 private:
  mutable std::vector<DirichletBlocks> blocks_;  ///< per owned subdomain (their work vectors change)
  bool dirichlet_;
  Factorization factorization_;
  SparseCholeskyOptions options_;
};

}  // namespace tribos::feti
