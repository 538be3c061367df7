#pragma once
/// \file SparseCholesky.hpp
/// One interface for the sparse Cholesky factorisations of SPD matrices (the regularised
/// subdomain stiffness K_reg, G G^T, K_ii). Implementations: "CHOLMOD" (SuiteSparse for the
/// factorisation, tribos's packed factor for the solves; the default) and "Tacho"
/// (Trilinos's Tacho::Driver), both with a METIS fill-reducing ordering. See
/// doc/factorization.md for the measurements behind the default.
///
/// Thread safety: different objects may factorize and solve concurrently from the threads
/// of core::forEachSubdomain (each object used by one thread at a time). "CHOLMOD" gives
/// the same bits on any thread and for any number of threads.
#include <memory>
#include <string>
#include <vector>

#include "tribos/core/EnumNames.hpp"
#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::feti {

class PackedFactor;  // src/PackedFactor.hpp (internal)

class SparseCholesky {
 public:
  virtual ~SparseCholesky() = default;
  /// Symbolic analysis + numeric factorisation of the SPD matrix A (full symmetric CSR:
  /// both triangles stored). Throws std::runtime_error if A is not positive definite.
  virtual void factorize(const fem::CsrMatrix& A) = 0;
  /// factorize(A) for a matrix the caller gives up: an implementation may free it as soon as
  /// the numeric factorisation no longer reads it (CHOLMOD: before its packed copy of the
  /// factor is made), so that A, the factor and the copy are never alive together (the
  /// replicated G G^T, doc/measurements/scalability.md). A is left empty.
  virtual void factorizeConsuming(fem::CsrMatrix&& A) {
    factorize(A);
    A = fem::CsrMatrix{};
  }
  /// Solves A X = B for `nrhs` right-hand sides stored column-major (leading dimension n);
  /// x and b may not alias.
  virtual void solve(const double* b, double* x, int nrhs = 1) const = 0;
  /// The order of the unknowns of solveInPlace: its entry k is row permutation()[k] of A
  /// (the fill-reducing order, so that the solve needs no permutation pass of its own).
  virtual const std::vector<LO>& permutation() const = 0;
  /// An estimate of the reciprocal condition number of the factorised matrix: (min / max of
  /// the factor's diagonal)^2 (CHOLMOD's cholmod_rcond); 1 where the factorisation keeps none.
  virtual double reciprocalCondition() const { return 1.0; }
  /// v := A^{-1} v for one vector in the order of permutation(); no allocation.
  virtual void solveInPlace(double* v) const = 0;
  /// For right-hand sides that vanish outside `columns` (in the order of permutation()) and
  /// solutions read at `columns` only (F = B_s K^+ B_s^T: the dofs of B_s): the backward
  /// substitution of solveInPlaceOnColumns then visits only the part of the factor they reach,
  /// with the bits solveInPlace gives there ("CHOLMOD"; others solve whole). Set once, before
  /// the solves.
  virtual void setSparseColumns(const std::vector<LO>& columns) { (void)columns; }
  /// v := A^{-1} v at the columns of setSparseColumns, for v zero elsewhere on entry; v is
  /// not meaningful elsewhere on return. No allocation.
  virtual void solveInPlaceOnColumns(double* v) const { solveInPlace(v); }
  /// Bytes one solveInPlaceOnColumns reads from the factor.
  virtual long long solveBytesOnColumns() const { return solveBytes(); }
  virtual LO size() const = 0;
  /// Stored entries of the factor (for memory reports).
  virtual long long factorNonzeros() const = 0;
  /// Bytes one solve with one right-hand side reads from the factor (both triangular
  /// substitutions): the numerator of the bandwidth bound of doc/measurements/performance.md.
  virtual long long solveBytes() const = 0;
  virtual std::string name() const = 0;
  /// For a factor solved alone on the main thread (G G^T on rank 0): set before
  /// factorize(), lets its solves run the independent subtrees of the elimination tree on
  /// the threads of core::forEachSubdomain when the factor is large enough to pay
  /// (doc/measurements/coarse_problem.md). The solves then give the same bits for any number of threads,
  /// though not those of the serial solve. Such a factor must not be solved from inside
  /// forEachSubdomain. Implementations without it ignore it ("Tacho").
  virtual void setSubtreeSolve(bool enabled) { (void)enabled; }
  /// Subtrees the solves run concurrently (0: serial solves).
  virtual int subtreeCount() const { return 0; }
  /// Rounds the stored factor L to single precision (PackedFactor::roundToSingle): later
  /// solves apply (L~ L~^T)^{-1}, L~ = fl32(L), reading half the bytes. Returns false, and
  /// keeps the factor as it is, where the implementation cannot ("Tacho").
  virtual bool roundToSingle() { return false; }
  /// The factor in tribos's packed form ("CHOLMOD"), for DistributedCoarseSolve; null when
  /// the implementation has none ("Tacho").
  virtual const PackedFactor* packedFactor() const { return nullptr; }
};

/// How CHOLMOD factorises a matrix (FETI/CHOLMOD Mode): by its size (Auto: supernodal from
/// 4000 rows, CholmodCholesky.cpp), or always one way (for measurements, doc/factorization.md).
enum class CholmodMode { Auto, Simplicial, Supernodal };
inline constexpr core::EnumNames<CholmodMode, 3> kCholmodModeNames{
    {{"Auto", CholmodMode::Auto}, {"Simplicial", CholmodMode::Simplicial}, {"Supernodal", CholmodMode::Supernodal}}};

/// The tuning of a factorisation, validated parameters of the FETI list (one declaration:
/// stack/SceneParameters.cpp). Each depends on the matrix alone, never on the layout.
struct SparseCholeskyOptions {
  CholmodMode cholmodMode = CholmodMode::Auto;
  /// With setSubtreeSolve: factors of at least this many stored values split their
  /// elimination tree for concurrent solves (FETI/Subtree Solve From).
  long long subtreeSolveFromValues = 500000;
};

/// FETI/Factorization: the implementations of SparseCholesky.
enum class Factorization { Cholmod, Tacho };
inline constexpr core::EnumNames<Factorization, 2> kFactorizationNames{
    {{"CHOLMOD", Factorization::Cholmod}, {"Tacho", Factorization::Tacho}}};

/// Names accepted by makeSparseCholesky.
std::vector<std::string> sparseCholeskyNames();
/// Creates a factorisation (Tacho ignores `options`).
std::unique_ptr<SparseCholesky> makeSparseCholesky(Factorization kind, const SparseCholeskyOptions& options = {});
/// The same by name ("CHOLMOD" or "Tacho"); throws core::InputError naming the parameter
/// "FETI/Factorization" and the valid names otherwise.
std::unique_ptr<SparseCholesky> makeSparseCholesky(const std::string& name, const SparseCholeskyOptions& options = {});

}  // namespace tribos::feti
