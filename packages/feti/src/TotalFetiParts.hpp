#pragma once
// Internal to feti/: what the parts of TotalFeti share (doc/design.md, "T-FETI operators"):
// the blocks of B and of K as the operators read them, the compact G (CoarseRows), one owned
// subdomain (Local), the sums over the overlap rows (applyBlockwise) and small helpers.
// One component per source file: TotalFeti.cpp (set-up, F), TotalFetiPreconditioners.cpp,
// TotalFetiCoarseSpace.cpp (G), CoarseProblem.{hpp,cpp} (G G^T and its solves),
// TotalFetiProjector.cpp (P), TotalFetiRecovery.cpp (alpha, u, residuals).
#include "tribos/feti/TotalFeti.hpp"


#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Import.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>

#include "tribos/core/Deadline.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/PhaseTimer.hpp"
#include "tribos/core/ReproducibleSum.hpp"
#include "EliminatedComponents.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/feti/DistributedCoarseSolve.hpp"
#include "tribos/fem/SubdomainSystem.hpp"


namespace tribos::feti {

namespace detail {
// x = B_s^T lambda_s (x has n entries, zeroed here). A dof in several rows sums them in
// `order` (the rows by their global id, B.rowId): B's own row order follows the number of
// ranks, and with it the rounding of these sums.
inline void applyBlockTranspose(const SubdomainBlock& b, const std::vector<LO>& order, const double* lambda, double* x,
                         LO n) {
  std::fill(x, x + n, 0.0);
  for (LO i : order)
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) x[b.dof[k]] += b.value[k] * lambda[i];
}

// out = B_s y.
inline void applyBlock(const SubdomainBlock& b, const double* y, double* out) {
  for (size_t i = 0; i + 1 < b.rowPtr.size(); ++i) {
    double s = 0.0;
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) s += b.value[k] * y[b.dof[k]];
    out[i] = s;
  }
}

/// One term of B_s: its row (index into the block's rows), its dof (renumbered) and value.
/// A subdomain keeps its terms in the order applyBlockTranspose adds them (rows in `order`,
/// each row's terms in B's order), one array that F and the preconditioners stream through
/// instead of four (row order, row pointers, values and renumbered dofs:
/// doc/measurements/performance.md, "G x and B_s each in one stream").
struct BlockTerm {
  LO row, dof;
  double value;
};
static_assert(sizeof(BlockTerm) == 16, "one term of B_s in 16 bytes");

inline std::vector<BlockTerm> blockTerms(const SubdomainBlock& b, const std::vector<LO>& order, const std::vector<LO>& dof) {
  std::vector<BlockTerm> terms;
  terms.reserve(b.value.size());
  for (LO i : order)
    for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k) terms.push_back({i, dof[k], b.value[k]});
  return terms;
}

// x = B_s^T lambda_s from the terms: the bits of applyBlockTranspose (same terms, same order).
inline void scatterTerms(const std::vector<BlockTerm>& terms, const double* lambda, double* x, LO n) {
  std::fill(x, x + n, 0.0);
  for (const BlockTerm& t : terms) x[t.dof] += t.value * lambda[t.row];
}

// out = B_s y from the terms: each row's sum takes its terms in B's order from zero, the bits
// of applyBlock (the rows are visited in another order, each sum by itself).
inline void gatherTerms(const std::vector<BlockTerm>& terms, const double* y, double* out, LO m) {
  std::fill(out, out + m, 0.0);
  for (const BlockTerm& t : terms) out[t.row] += t.value * y[t.dof];
}

// The explicit F_s (ALGORITHMS.md 3) as the lower triangle of (F + F^T)/2 packed by rows, rows
// and columns in `order` (the block's rows by global id: the same matrix on every rank layout).
// `full`: m x m, column-major, in the block's own row order.
inline std::vector<double> packLowerInRowOrder(const std::vector<double>& full, const std::vector<LO>& order) {
  const size_t m = order.size();
  std::vector<double> packed;
  packed.reserve(m * (m + 1) / 2);
  for (size_t a = 0; a < m; ++a)
    for (size_t b = 0; b <= a; ++b)
      packed.push_back(0.5 * (full[order[a] * m + order[b]] + full[order[b] * m + order[a]]));
  return packed;
}

// out = F_s in with F_s from packLowerInRowOrder: `in` gathered into `order` (t), row a of the
// triangle read once for both its dot with t (entry a of F t) and its axpy into y (the upper
// triangle's share, F_ba = F_ab), the dot in eight interleaved lanes: a fixed order of every
// sum that the compiler may vectorise. One pass over m(m+1)/2 contiguous values.
inline void applyPackedLower(const std::vector<double>& packed, const std::vector<LO>& order, const double* in,
                      double* __restrict t, double* __restrict y, double* out) {
  const LO m = static_cast<LO>(order.size());
  for (LO a = 0; a < m; ++a) t[a] = in[order[a]], y[a] = 0.0;
  const double* __restrict row = packed.data();
  for (LO a = 0; a < m; row += a + 1, ++a) {
    const double ta = t[a];
    double lane[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    LO b = 0;
    for (; b + 8 <= a; b += 8)
      for (int k = 0; k < 8; ++k) {
        lane[k] += row[b + k] * t[b + k];
        y[b + k] += row[b + k] * ta;
      }
    for (; b < a; ++b) {
      lane[0] += row[b] * t[b];
      y[b] += row[b] * ta;
    }
    y[a] += (((lane[0] + lane[1]) + (lane[2] + lane[3])) + ((lane[4] + lane[5]) + (lane[6] + lane[7]))) + row[a] * ta;
  }
  for (LO a = 0; a < m; ++a) out[order[a]] = y[a];
}

// Extracts K_ii (rows and columns `interior`, ascending) from K.
inline fem::CsrMatrix principalSubmatrix(const fem::CsrMatrix& K, const std::vector<LO>& keep) {
  std::vector<LO> position(K.n, -1);
  for (size_t i = 0; i < keep.size(); ++i) position[keep[i]] = static_cast<LO>(i);
  fem::CsrMatrix S;
  S.n = static_cast<LO>(keep.size());
  S.rowPtr.assign(S.n + 1, 0);
  for (LO i = 0; i < S.n; ++i) {
    for (LO k = K.rowPtr[keep[i]]; k < K.rowPtr[keep[i] + 1]; ++k)
      if (position[K.colInd[k]] >= 0) {
        S.colInd.push_back(position[K.colInd[k]]);
        S.values.push_back(K.values[k]);
      }
    S.rowPtr[i + 1] = static_cast<LO>(S.colInd.size());
  }
  return S;
}

inline MPI_Comm rawComm(const Teuchos::Comm<int>& comm) {
  const auto* mpi = dynamic_cast<const Teuchos::MpiComm<int>*>(&comm);
  TEUCHOS_TEST_FOR_EXCEPTION(!mpi, std::logic_error, "tribos::feti: collectives need an MPI communicator");
  return (*mpi->getRawMpiComm())();
}

/// Iterative refinement steps of solveCoarseExactly at most (about 3 at the gate's 1e-3,
/// TotalFetiSettings::singleCoarseGate).
constexpr int kMaxCoarseRefinements = 20;

// Every rank's `mine`, concatenated in rank order (all ranks get the whole list).
inline std::vector<long long> allGather(const Teuchos::Comm<int>& comm, const std::vector<long long>& mine) {
  const MPI_Comm raw = rawComm(comm);
  const int size = comm.getSize(), count = static_cast<int>(mine.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, raw);
  for (int p = 0; p < size; ++p) offsets[p + 1] = offsets[p] + counts[p];
  std::vector<long long> all(offsets[size]);
  MPI_Allgatherv(mine.data(), count, MPI_LONG_LONG, all.data(), counts.data(), offsets.data(), MPI_LONG_LONG, raw);
  return all;
}

inline const double* readOnly(const DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadOnly).data(); }
inline double* readWrite(DualVector& v) { return v.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }

/// Builds the lumped (K_bb) and, with `interiorToo`, the Dirichlet (K_ib, K_ii factor) blocks of
/// an owned subdomain (TotalFetiPreconditioners.cpp).
void buildPreconditionerBlocks(TotalFeti::Local& L, bool interiorToo, Factorization factorization,
                               const SparseCholeskyOptions& options);
/// y := x - G^T a on the owned rows (TotalFetiCoarseSpace.cpp): the G^T pass of a projection.
void subtractGt(const TotalFeti::CoarseRows& G, const double* a, const double* x, double* y);
}  // namespace detail
using namespace detail;


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

/// One entry (row r, subdomain s) of G in the geometric basis of s (CoarseRows): g'_{s,r} =
/// c [e_d; e_k x p~] when row r of B_s has the single term c at component d of a node with
/// scaled coordinates p~ = coords[slot] (code = 4 slot + d), else the 6 numbers full[slot]
/// (code = 4 slot + 3; contact rows with several terms). `index`: the row (G^T a) or x's
/// index on the overlap (G x). 16 bytes instead of 6 doubles and an index.
struct CoarseTerm {
  double c;
  std::uint32_t code;
  LO index;
};
static_assert(sizeof(CoarseTerm) == 16, "one entry of G in 16 bytes");

/// One owned subdomain: its system, generalised inverse, rows of B and scratch buffers
/// (allocated before any threaded loop: TOOLCHAIN.md rule 1).
struct TotalFeti::Local {
  int subdomain = 0;
  const SubdomainBlock* block = nullptr;
  std::vector<LO> overlapIndex;  ///< local index in the overlap map of each block row
  std::vector<BlockTerm> factorTerms;  ///< B_s with the dofs in the factor's order (blockTerms)
  std::vector<LO> rowOrder;      ///< the block's rows by ascending global id (B.rowId)
  fem::SubdomainSystem system;
  SubdomainSolver solver;
  std::vector<double> denseF;    ///< explicit F_s when requested (packLowerInRowOrder)
  DirichletBlocks dirichlet;     ///< the Dirichlet preconditioner's blocks of K (when requested)
  EliminatedRows eliminated;     ///< the components eliminated from K_s (block->eliminated)
  int liveModes = 6;             ///< R's columns that are rigid modes (the rest are 0: eliminated)
  std::vector<double> in, out, x, y;
  LO m() const { return static_cast<LO>(block->rows.size()); }
  LO n() const { return system.K.n; }
};


/// G on this rank's owned rows of B: one entry = one row r and one subdomain s it touches.
/// Stored compactly (issue 9): R_s = R~_s M_s, with R~_s the geometric rigid modes of s
/// (translations e_d and rotations e_k x p~ at the scaled node coordinates p~ = (x - centre_s)
/// / scale_s, fem::rigidBodyModes before its Gram-Schmidt) and M_s (6 x 6) the change of
/// basis, so g_{s,r} = R_s^T b_{s,r}^T = M_s^T g'_{s,r} with g'_{s,r} = R~_s^T b_{s,r}^T. A
/// row of B_s with one term c at (node, d) has g'_{s,r} = c [e_d; (e_k x p~)_d]: a
/// CoarseTerm of 16 bytes (c, slot of p~ and d, row) instead of 6 doubles and an index; the
/// others (contact rows with several terms) keep their 6 numbers g' in `full`. G x applies
/// M_s^T once per subdomain to the sum of g' x_r, G^T a multiplies each g' by M_s a_s: the
/// same G in exact arithmetic, hence the same projector, e, alpha and G G^T; only the
/// rounding changes (doc/measurements/coarse_problem.md).
/// Threads work on fixed chunks of kRowChunk rows; inside a chunk the entries are stored by
/// subdomain ("runs"), then by kind (one loop without branches per kind), then by row, so
/// that G^T a adds each entry's g_{s,r} . a_s into its row's sum in a chunk-sized buffer,
/// runs in ascending subdomain order: every row sums its entries in ascending subdomain
/// order (the rows of one run are distinct, so there is no chain of dependent updates). G x
/// is summed by subdomain instead (ownedTerm, applyGOwnedSubdomains): a subdomain's rows are
/// owned by different ranks on different layouts, its owner has them all (its own block) and
/// reads the same coordinate slots.
/// The by-row view (rowStart, rowSubdomain, rowEntry) serves the set-up (G G^T).
struct TotalFeti::CoarseRows {
  GO firstRow = 0;
  LO numRows = 0;
  std::vector<LO> rowStart;       ///< numRows + 1; a row's entries in ascending subdomain order
  std::vector<int> rowSubdomain;  ///< per entry in row order
  std::vector<LO> rowEntry;       ///< per entry in row order: its index in the stored order
  // Stored order: chunk, subdomain, kind (d = 0, 1, 2, full), row.
  std::vector<CoarseTerm> term;   ///< per entry (index: the owned row)
  std::vector<double> coords;     ///< 3 per slot: p~ of a (subdomain, node) that a term reads
  std::vector<double> full;       ///< 6 per slot: g' of an entry with several terms
  std::vector<double> basis;      ///< M_s, 36 per subdomain (row-major: R_s = R~_s M_s)
  std::vector<LO> runStart;       ///< per run + 1: its entries
  std::vector<LO> runGroupStart;  ///< 4 per run + 1: the entries of kind g of run j from 4 j + g
  std::vector<int> runSubdomain;  ///< per run
  std::vector<int> chunkRunStart;  ///< per chunk + 1: its runs
  mutable std::vector<double> rowSum;  ///< numRows: G^T a's sums, each chunk its own rows
  /// G x's terms of the owned subdomains (index: x's index on the overlap; every row of the
  /// subdomain's own block, whichever rank owns the row), one subdomain after the other in
  /// one array, and per owned subdomain its id and where its kinds start
  /// (ownedStart[6 i .. 6 i + 4] into ownedTerm, ownedStart[6 i + 5] = s): G x streams
  /// through two arrays instead of starting a new allocation at every subdomain
  /// (doc/measurements/performance.md, "G x and B_s each in one stream").
  std::vector<CoarseTerm> ownedTerm;
  std::vector<LO> ownedStart;
  int numChunks() const { return static_cast<int>(chunkRunStart.size()) - 1; }
  const double* M(int s) const { return &basis[36 * static_cast<size_t>(s)]; }
  /// g'_{s,r} of a term (the geometric basis).
  void geometric(const CoarseTerm& t, double* g) const;
  /// g_{s,r} = M_s^T g'_{s,r} of the entry `rowOrderEntry` (row view), for G G^T.
  void rowG(LO rowOrderEntry, double* g) const;
};


namespace detail {
/// Rows per task of the row loops (G^T a, the sums of applyBlockwise): fixed, so that the
/// work split does not depend on the number of threads.
constexpr LO kRowChunk = 8192;
/// Subdomains per task of G x (applyGOwnedSubdomains).
constexpr int kGxSubdomains = 8;
/// Slots per entry of the reproducible sums of G G^T.
constexpr int kSlots = core::SumBins::kSlices;
/// A subdomain's frame as it travels: centre (3), scale, M_s (36).
constexpr int kFrame = 40;

/// Row d of the geometric modes at the scaled point p: [e_d; (e_0 x p)_d, (e_1 x p)_d,
/// (e_2 x p)_d] (fem::rigidBodyModes' order, before orthonormalisation).
inline void geometricRow(int d, const double* p, double* v) {
  for (int j = 0; j < 3; ++j) v[j] = j == d ? 1.0 : 0.0;
  const double rotation[3][3] = {{0.0, p[2], -p[1]}, {-p[2], 0.0, p[0]}, {p[1], -p[0], 0.0}};
  for (int k = 0; k < 3; ++k) v[3 + k] = rotation[d][k];
}

/// p~ = (x - centre) / scale: one function, so that every rank computes the same bits.
inline void scaledPoint(const double* frame, const std::array<double, 3>& x, double* p) {
  for (int j = 0; j < 3; ++j) p[j] = (x[j] - frame[j]) / frame[3];
}

/// The frame of a subdomain from its nodes and R (6 columns of n = 3 nodes): centroid, rms
/// radius (the scaled coordinates are O(1), so that R~ is well conditioned), and M with
/// R = R~ M, by the normal equations (R~^T R~) M = R~^T R (R lies in the span of R~ to
/// round-off; R~^T R~ is 6 x 6 and well conditioned after the scaling).
inline void subdomainFrame(const mesh::Mesh& mesh, const std::vector<LO>& nodes, const std::vector<double>& R, double* frame) {
  const size_t count = nodes.size(), n = 3 * count;
  for (int j = 0; j < 4; ++j) frame[j] = 0.0;
  for (LO node : nodes)
    for (int j = 0; j < 3; ++j) frame[j] += mesh.coords[node][j] / static_cast<double>(count);
  double sum = 0.0;
  for (LO node : nodes)
    for (int j = 0; j < 3; ++j) sum += std::pow(mesh.coords[node][j] - frame[j], 2);
  frame[3] = sum > 0.0 ? std::sqrt(sum / static_cast<double>(count)) : 1.0;
  double A[36] = {}, C[36] = {}, v[6], p[3];
  for (size_t k = 0; k < count; ++k) {
    scaledPoint(frame, mesh.coords[nodes[k]], p);
    for (int d = 0; d < 3; ++d) {
      geometricRow(d, p, v);
      for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 6; ++j) {
          A[6 * i + j] += v[i] * v[j];
          C[6 * i + j] += v[i] * R[j * n + 3 * k + d];
        }
    }
  }
  // Cholesky A = L L^T (lower, in place), then M = L^-T L^-1 C column by column.
  for (int j = 0; j < 6; ++j) {
    for (int k = 0; k < j; ++k) A[6 * j + j] -= A[6 * j + k] * A[6 * j + k];
    A[6 * j + j] = std::sqrt(A[6 * j + j]);
    for (int i = j + 1; i < 6; ++i) {
      for (int k = 0; k < j; ++k) A[6 * i + j] -= A[6 * i + k] * A[6 * j + k];
      A[6 * i + j] /= A[6 * j + j];
    }
  }
  double* M = frame + 4;
  for (int c = 0; c < 6; ++c) {
    double y[6];
    for (int i = 0; i < 6; ++i) {
      y[i] = C[6 * i + c];
      for (int k = 0; k < i; ++k) y[i] -= A[6 * i + k] * y[k];
      y[i] /= A[6 * i + i];
    }
    for (int i = 5; i >= 0; --i) {
      for (int k = i + 1; k < 6; ++k) y[i] -= A[6 * k + i] * y[k];
      y[i] /= A[6 * i + i];
    }
    for (int i = 0; i < 6; ++i) M[6 * i + c] = y[i];
  }
}

/// The kind of row i of block b: its component d when it has one term, else 3.
inline int termKind(const SubdomainBlock& b, LO i) { return b.rowPtr[i + 1] - b.rowPtr[i] == 1 ? b.dof[b.rowPtr[i]] % 3 : 3; }

/// y = M^T x (6 x 6, row-major M).
inline void transposedProduct(const double* M, const double* x, double* y) {
  for (int j = 0; j < 6; ++j) {
    double s = 0.0;
    for (int i = 0; i < 6; ++i) s += M[6 * i + j] * x[i];
    y[j] = s;
  }
}
}  // namespace detail

template <class LocalOp>
void TotalFeti::applyBlockwise(const DualVector& x, DualVector& y, LocalOp op) const {
  // Import (main thread), per-subdomain work on threads with raw pointers only, then each
  // row's sum over its subdomains in ascending subdomain order, on any layout: with several
  // ranks the entries travel to the row's owner one by one (a per-rank pre-sum, then an
  // export-add, would group three or more terms differently on different layouts). The
  // work vectors live as long as this object (no allocation per application); when the
  // overlap is the owned rows themselves (one rank), x serves as its own overlap vector.
  const double* xo = overlapValues(x);
  if (!overlapIsOwned_) {
    // Several ranks: each entry to the owner of its row, summed there in subdomain order.
    double* source = entrySource_->getLocalViewHost(Tpetra::Access::OverwriteAll).data();
    core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
      Local& L = *local_[i];
      for (LO r = 0; r < L.m(); ++r) L.in[r] = xo[L.overlapIndex[r]];
      op(L, true);
      std::copy(L.out.begin(), L.out.end(), source + entrySourceFirst_[i]);
    });
    entryTarget_->doImport(*entrySource_, *entryImport_, Tpetra::INSERT);
    const double* entry = readOnly(*entryTarget_);
    double* yo = y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
    const CoarseRows& G = *G_;
    core::forEachSubdomain((G.numRows + kRowChunk - 1) / kRowChunk, [&](int chunk) {
      const LO end = std::min<LO>(G.numRows, (chunk + 1) * kRowChunk);
      for (LO r = chunk * kRowChunk; r < end; ++r) {
        double total = 0.0;
        for (LO e = G.rowStart[r]; e < G.rowStart[r + 1]; ++e) total += entry[e];
        yo[r] = total;
      }
    });
    return;
  }
  core::forEachSubdomain(numOwnedSubdomains(), [&](int i) {
    Local& L = *local_[i];
    for (LO r = 0; r < L.m(); ++r) L.in[r] = xo[L.overlapIndex[r]];
    op(L, true);
  });
  // One rank (or no shared rows): the overlap is the owned rows; every one has a
  // contribution (that is what puts it in the overlap), so the gather overwrites y.
  double* yo = y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
  const LO numOverlap = static_cast<LO>(contributionStart_.size()) - 1;
  core::forEachSubdomain((numOverlap + kRowChunk - 1) / kRowChunk, [&](int chunk) {
    const LO end = std::min<LO>(numOverlap, (chunk + 1) * kRowChunk);
    for (LO o = chunk * kRowChunk; o < end; ++o) {
      double total = 0.0;
      for (LO k = contributionStart_[o]; k < contributionStart_[o + 1]; ++k) total += *contribution_[k];
      yo[o] = total;
    }
  });
}

}  // namespace tribos::feti
