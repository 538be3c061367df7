#pragma once
/// \file TotalFeti.hpp
/// The dual (T-FETI) operators of one MPI rank (paper Section 4.2, ALGORITHMS.md 3):
///   F = B K^dagger B^T, d~ = B K^dagger f - c, G = R^T B^T, e = R^T f,
///   lambda_Im = G^T (G G^T)^{-1} e, P = I - G^T (G G^T)^{-1} G,
/// and the recovery u = K^dagger (f - B^T lambda) + R alpha.
///
/// Distribution: dual vectors live on `dualMap()` (each row of B owned by one rank, local
/// index = row - B.firstRowOfRank[rank], global id = B.rowId[row], so that a vector defined
/// by its global ids is the same on every number of ranks); an
/// application of F imports lambda to the rows that touch this rank's subdomains, applies
/// B_s K_s^dagger B_s^T per subdomain on threads, and export-adds the result. Coarse
/// vectors (length l = 6 x subdomains) are replicated on every rank; G G^T is assembled and
/// factorised on rank 0, and its solves run there (small factors) or over the ranks, each
/// rank solving subtrees of its elimination tree (DistributedCoarseSolve.hpp); either way
/// with the serial solve's bits. G itself is stored once, on the rows each
/// rank owns (g_{s,r} = R_s^T b_{s,r}^T per row r and subdomain s it touches, in the compact
/// geometric form of CoarseRows: 16 bytes per entry), so the projector reads no R_s, no
/// n_s-sized vector and moves no dual vector between ranks.
#include <Teuchos_Comm.hpp>
#include <Tpetra_Import_decl.hpp>
#include <Tpetra_Map_decl.hpp>
#include <Tpetra_Vector_decl.hpp>

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "tribos/core/EnumNames.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/SparseCholesky.hpp"
#include "tribos/feti/SubdomainSolver.hpp"

namespace tribos::core {
class Deadline;
}

namespace tribos::feti {

class DistributedCoarseSolve;
class SubdomainSet;
class Preconditioners;
class CoarseSpace;
class PrimalRecovery;

/// The rows I leave a rigid body mode free (G_I G_I^T singular): no constraint active at the
/// end holds some body, e.g. a load beyond what contact and friction can carry.
struct RigidMotionsUndetermined : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using DualMap = Tpetra::Map<LO, GO>;
using DualVector = Tpetra::Vector<Scalar, LO, GO>;

/// FETI/Dual Operator: F applied by two solves per subdomain, or as dense local blocks.
enum class DualOperator { Implicit, Explicit };
inline constexpr core::EnumNames<DualOperator, 2> kDualOperatorNames{
    {{"Implicit", DualOperator::Implicit}, {"Explicit", DualOperator::Explicit}}};
/// FETI/Preconditioner: the dual preconditioner D of P D P.
enum class DualPreconditioner { None, Lumped, Dirichlet };
inline constexpr core::EnumNames<DualPreconditioner, 3> kDualPreconditionerNames{
    {{"None", DualPreconditioner::None}, {"Lumped", DualPreconditioner::Lumped},
     {"Dirichlet", DualPreconditioner::Dirichlet}}};
/// FETI/Coarse Factor Precision (TotalFetiSettings::coarsePrecision).
enum class CoarsePrecision { Auto, Single, Double };
inline constexpr core::EnumNames<CoarsePrecision, 3> kCoarsePrecisionNames{
    {{"Auto", CoarsePrecision::Auto}, {"Single", CoarsePrecision::Single}, {"Double", CoarsePrecision::Double}}};

struct TotalFetiSettings {
  /// Solver/Max Seconds: the factorisation stops between subdomains once it has passed, and
  /// the constructor then throws core::LimitReached on every rank; checked again after the
  /// coarse factorisation. Read by the constructor only. Null: no deadline.
  const core::Deadline* deadline = nullptr;
  Factorization factorization = Factorization::Cholmod;  ///< SparseCholesky for K_reg and G G^T
  bool explicitF = false;                 ///< dense local F_s assembled once vs two solves per apply
  bool dirichletPreconditioner = false;   ///< factorise K_ii per subdomain for applyDirichlet
  bool lumpedPreconditioner = false;      ///< keep K_bb per subdomain for applyLumped (also kept with Dirichlet)
  /// Precision of G G^T's factor for project(), coarseCoordinates() and solveCoarse():
  /// Double; Single (rounded: half the bytes per coarse solve) where it is accurate
  /// enough (singleCoarseGate), lambda_Im and rigidBodyCoefficients(lambda) then
  /// refined to double; Auto: single where two coarse solves read at least as many bytes
  /// as the subdomain solves of one F application. Single only for callers that enforce
  /// G x = 0 themselves (SMALSE-M's penalty): P is then I - G^T C~^{-1} G, the identity on
  /// Ker G but not an exact projector (doc/measurements/coarse_problem.md, "The coarse factor in single
  /// precision"); projected CG needs the exact one.
  CoarsePrecision coarsePrecision = CoarsePrecision::Double;
  /// The subdomain factors' and G G^T's tuning (FETI/CHOLMOD Mode, FETI/Subtree Solve From).
  SparseCholeskyOptions factorOptions;
  /// The single-precision coarse factor is kept when one solve with it differs from the double
  /// one by at most this (relative; FETI/Single Coarse Gate).
  double singleCoarseGate = 1e-3;
  /// Coarse factors with at least this many stored values are solved over the ranks when
  /// there are several (FETI/Distributed Coarse From).
  long long distributedCoarseFromValues = 200000;
};

/// Where the time of the dual operators goes (cumulative over the object's life, this rank;
/// doc/measurements/coarse_problem.md): counts and wall seconds of each operator, read by the summary.
struct OperatorProfile {
  long long fApplications = 0, projections = 0, coarseSolves = 0, preconditionerApplications = 0;
  /// coarseCoordinates calls: SMALSE-M's ||Q x|| where no product gave the coordinates of x
  long long coarseCoordinates = 0;
  double fSeconds = 0.0;               ///< B K^+ B^T (imports, subdomain solves, export-add)
  double gSeconds = 0.0;               ///< G x and G^T a of the projections (owned rows)
  double coarseReduceSeconds = 0.0;    ///< the all-reduce of G x (length l)
  double coarseSolveSeconds = 0.0;     ///< (G G^T)^{-1} a
  double preconditionerSeconds = 0.0;  ///< B K B^T or B S B^T
  double coarseFactorSeconds = 0.0;    ///< assembly + factorisation of G G^T
  int coarseFactorizations = 0;        ///< factorisations of G G^T (a released factor is made again)
  /// rigidBodyCoefficients: F lambda, G_I (F lambda - d~)_I, G_I G_I^T assembled, factorised and
  /// solved (contact), or the exact coarse solve (all rows active)
  double rigidCoefficientsSeconds = 0.0;
  long long coarseFactorNonzeros = 0;  ///< stored entries of the factor of G G^T
  int coarseSubtrees = 0;  ///< subtrees its solves run concurrently (0: serial solves)
  /// Leaves (subtrees solved by one rank) of its solves spread over the ranks (0: solved on
  /// rank 0 and broadcast), and the splits from the whole factor to the deepest leaf.
  int coarseRankSubtrees = 0, coarseSplitDepth = 0;
  /// Stored values of the coarse factor that this rank reads per solve (rank 0: the whole
  /// factor, or with coarseRankSubtrees its subtrees and the top).
  long long coarseValuesPerSolve = 0;
  /// Whether the coarse factor is in single precision (TotalFetiSettings::coarsePrecision
  /// and the gate passed), the gate's relative error ||x~ - x|| / ||x|| (0: not rounded; > 0
  /// with coarseSingle false: the gate sent it back to double) and the refinement steps of
  /// the exact coarse solves.
  bool coarseSingle = false;
  double coarseSingleError = 0.0;
  long long coarseRefinementSteps = 0;
  /// Bytes two solves with the double coarse factor read, over those of the subdomain solves
  /// of one F application (layout-independent): "Auto" rounds from 1; from 2 the driver
  /// advises fewer, larger subdomains.
  double coarseToFBytes = 0.0;
  long long gEntries = 0, gRows = 0;   ///< entries (row, subdomain) of G on this rank's rows, rows
  /// The least bytes one projection (G x and G^T a) and one preconditioner application
  /// (B S B^T or B K_bb B^T; 0 without one) move, summed over the ranks (measureTraffic).
  double projectionBytes = 0.0, preconditionerBytes = 0.0;
};

/// The coordinates of Q x = G^T a of a dual vector x: gx = G x and a = (G G^T)^{-1} G x
/// (length l, replicated), ||Q x||^2 = gx^T a.
struct CoarseCoordinates {
  std::vector<double> gx, a;
};

class TotalFeti {
 public:
  /// `owned[i]` is the assembled system of subdomain firstOwned + i (mesh::firstSubdomain).
  /// B may be the whole of B or this rank's part of it (feti::keepRankRows): the blocks of
  /// the owned subdomains and, of the others, the rows this rank owns.
  /// Factorises every owned K_reg (threads over subdomains), builds the maps, G G^T, e,
  /// d~ and lambda_Im. Collective over `comm`.
  TotalFeti(const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
            std::vector<fem::SubdomainSystem> owned, const ConstraintMatrix& B,
            const Teuchos::RCP<const Teuchos::Comm<int>>& comm, const TotalFetiSettings& settings);
  ~TotalFeti();

  Teuchos::RCP<const DualMap> dualMap() const;
  Teuchos::RCP<DualVector> createDualVector() const;
  GO numDual() const { return B_.numRows; }
  int numCoarse() const { return 6 * numSubdomains_; }  ///< l

  /// y = F x. Counts one F application.
  void applyF(const DualVector& x, DualVector& y) const;
  /// y = P F x for x in Ker G (G x = 0 to round-off, e.g. x = P z): computed as P B K^+ B^T x,
  /// which is the same there and skips the kernel projections of K^dagger (one pass over
  /// R_s on either side of every solve). P F P z = applyPF(P z). Counts one F application.
  void applyPF(const DualVector& x, DualVector& y) const;
  /// gx = G x (length l, replicated).
  void applyG(const DualVector& x, std::vector<double>& gx) const;
  /// y = G^T a (a of length l, replicated).
  void applyGt(const std::vector<double>& a, DualVector& y) const;
  /// a := (G G^T)^{-1} a, with the single-precision factor where it is in use
  /// (TotalFetiSettings::singleCoarseFactor): then (L~ L~^T)^{-1} a.
  void solveCoarse(std::vector<double>& a) const;
  /// a := (G G^T)^{-1} a to double precision whatever the factor's: with a single-precision
  /// one, solveCoarse refined by iterative refinement (products G G^T x as G (G^T x)).
  void solveCoarseExactly(std::vector<double>& a) const;
  /// Frees the factor of G G^T (the largest replicated data at
  /// thousands of subdomains: doc/measurements/scalability.md), for a caller done with projections,
  /// before the factor of G_I G_I^T of rigidBodyCoefficients(lambda, mask). A later coarse
  /// solve factorises G G^T again (the same bits; collective, as every coarse solve is).
  /// A no-op while keepCoarseFactor(true): a load history, whose next step projects again.
  void releaseCoarseFactor() const;
  /// Keep the factor of G G^T through releaseCoarseFactor (a history: G G^T does not change
  /// between its steps, so it is factorised once, at the cost of holding it beside
  /// G_I G_I^T's during each step's recovery).
  void keepCoarseFactor(bool keep);
  /// y = P x = x - G^T (G G^T)^{-1} G x (y may be x). With `ofX`, also the coordinates
  /// of Q x = x - P x it computes on the way: G x and (G G^T)^{-1} G x (the bits of
  /// coarseCoordinates(x)), so that a caller who needs them does not compute them again.
  void project(const DualVector& x, DualVector& y, CoarseCoordinates* ofX = nullptr) const;
  /// y = P x with the exact projector whatever the coarse factor's precision
  /// (solveCoarseExactly; y may be x): for a vector whose part in Im G^T is large against its
  /// part in Ker G (SMALSE-M's c = P h), where the single-precision factor would leave a
  /// visible residue of that part.
  void projectExactly(const DualVector& x, DualVector& y) const;
  /// gx = G x and a = (G G^T)^{-1} G x (replicated; ||Q x||^2 = gx^T a). Collective.
  void coarseCoordinates(const DualVector& x, std::vector<double>& gx, std::vector<double>& a) const;
  /// y = B K B^T x (the lumped preconditioner, before projection), from K_bb only (b = the
  /// dofs that B touches). Requires settings.lumpedPreconditioner or dirichletPreconditioner.
  void applyLumped(const DualVector& x, DualVector& y) const;
  /// y = B S B^T x with S_s = K_bb - K_bi K_ii^{-1} K_ib the Schur complement of each
  /// subdomain on the dofs that B touches (the Dirichlet preconditioner, before projection).
  /// Requires settings.dirichletPreconditioner.
  void applyDirichlet(const DualVector& x, DualVector& y) const;

  const DualVector& dTilde() const { return *dTilde_; }    ///< d~ = B K^dagger f - c
  /// c on this rank's rows [B.firstRowOfRank[rank], B.firstRowOfRank[rank + 1]): B.c's, or the
  /// last setRightHandSide's.
  const std::vector<double>& ownedC() const { return c_; }
  /// A new right-hand side on the same operators (a load step, ALGORITHMS.md 11): the loads f_s
  /// of the owned subdomains (each the size of its system's f) and c on the owned rows; e, d~
  /// and lambda_Im follow. The factors, G, G G^T and the maps stay. Collective.
  void setRightHandSide(const std::vector<std::vector<double>>& fOwned, const std::vector<double>& cOwned);
  const DualVector& lambdaIm() const { return *lambdaIm_; }  ///< G^T (G G^T)^{-1} e
  const std::vector<double>& e() const { return e_; }       ///< R^T f

  /// alpha = (G G^T)^{-1} G (F lambda - d~) over all rows (all constraints active: the
  /// linear case); returns alpha (length l).
  std::vector<double> rigidBodyCoefficients(const DualVector& lambda) const;
  /// alpha = (G_I G_I^T)^{-1} G_I (F lambda - d~)_I over the rows I where the mask is != 0:
  /// the rows where the dual constraints are not active, so that the dual gradient vanishes
  /// there (ALGORITHMS.md 7). `ownedRowMask` covers this rank's owned rows only (entry i: row
  /// B.firstRowOfRank[rank] + i; one entry per row of dualMap()): no rank needs the others'.
  /// Throws RigidMotionsUndetermined (on every rank) when G_I G_I^T is singular.
  std::vector<double> rigidBodyCoefficients(const DualVector& lambda, const std::vector<char>& ownedRowMask) const;
  /// Two owned rows (indices as in the mask) whose combination w_a row_a + w_b row_b (w a unit
  /// vector) holds as an equality at the solution: a sliding friction node's tangential rows,
  /// whose slip has no component across the friction force's direction.
  struct RowCombination {
    LO a = -1, b = -1;
    double wa = 0.0, wb = 0.0;
  };
  /// The same over the masked rows and these combinations (G_I' holds w_a g_a + w_b g_b for
  /// each): a body that slides holds its rigid motions through them. A combination whose two
  /// rows touch different subdomains is left out.
  std::vector<double> rigidBodyCoefficients(const DualVector& lambda, const std::vector<char>& ownedRowMask,
                                            const std::vector<RowCombination>& combinations) const;
  /// y = B u for displacements u of the owned subdomains (u[i] of subdomain firstOwned + i).
  void applyB(const std::vector<std::vector<double>>& u, DualVector& y) const;
  /// max over owned subdomains of ||K_s u_s - f_s + B_s^T lambda_s||_inf (equilibrium), all
  /// ranks. With `forceScale`: also the largest of |f_s|, |B_s^T lambda_s| and sum_j |K_kj u_j|
  /// over all dofs k of all subdomains, the forces the residual compares with; it is not zero
  /// when the loads are (a scene driven by prescribed displacements: the constraint forces carry
  /// it; a body moved rigidly, touching nothing: the terms of its K u, which cancel).
  double equilibriumResidual(const DualVector& lambda, const std::vector<std::vector<double>>& u,
                             double* forceScale = nullptr) const;
  /// u_s = K_s^dagger (f_s - B_s^T lambda) + R_s alpha_s for every owned subdomain.
  std::vector<std::vector<double>> recoverDisplacements(const DualVector& lambda,
                                                        const std::vector<double>& alpha) const;

  /// The reactions at the components eliminated from K_s (FETI/Displacement Conditions =
  /// Eliminated): (K_s u_s - f_s) at each, for the owned subdomains' displacements u.
  std::vector<EliminatedReaction> eliminatedReactions(const std::vector<std::vector<double>>& u) const;

  /// 1/2 u^T K u - f^T u summed over all subdomains (collective).
  double energy(const std::vector<std::vector<double>>& u) const;
  /// ||f||_inf over all subdomains (collective).
  double loadNormInf() const;
  const Teuchos::RCP<const Teuchos::Comm<int>>& comm() const { return comm_; }
  const ConstraintMatrix& constraints() const { return B_; }
  /// The preconditioner built at set-up: Dirichlet where asked, else Lumped where asked, else None.
  DualPreconditioner preconditioner() const {
    return settings_.dirichletPreconditioner ? DualPreconditioner::Dirichlet
           : settings_.lumpedPreconditioner  ? DualPreconditioner::Lumped
                                             : DualPreconditioner::None;
  }

  long long fApplications() const { return fApplications_; }
  const OperatorProfile& profile() const { return profile_; }
  int firstOwnedSubdomain() const;
  int numOwnedSubdomains() const;
  const SubdomainSolver& subdomainSolver(int i) const;
  double factorizationSeconds() const { return factorizationSeconds_; }
  /// Stored entries of the subdomain factors, all ranks (the summary's factor_nonzeros).
  long long factorNonzeros() const { return factorNonzeros_; }
  /// Bytes one product with P F P moves at least (the summary's bytes_per_f_application,
  /// one F application per PFP product): the factors (both substitutions), R_s on either
  /// side of each solve, B_s^T and B_s, the dual entries in and out, and two projections
  /// (G read twice each). All ranks. Divided by the memory bandwidth it bounds
  /// the time of one product from below (doc/measurements/performance.md).
  double bytesPerFApplication() const { return bytesPerFApplication_; }
  /// sum of n_s over all subdomains (the same on every layout).
  long long primalDofs() const;

 private:
  // The constructor's steps (TotalFeti.cpp): (1)-(3) the owned subdomains, their maps and
  // factors (SubdomainSet); (4) G and G G^T (CoarseSpace), after the traffic of F is known;
  // (5) e, d~ and lambda_Im.
  void buildDualData();
  /// y = B K^dagger B^T x, or B K^+ B^T x without `removeKernel` (implicit F only).
  void applyF(const DualVector& x, DualVector& y, bool removeKernel) const;
  /// Sets factorNonzeros_ and bytesPerFApplication_ (collective).
  void measureTraffic();

  const ConstraintMatrix& B_;
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  TotalFetiSettings settings_;
  int numSubdomains_ = 0;
  // The components (feti/src/BlockKernels.hpp lists them); TotalFeti orders their set-up and
  // composes them (F, P F, d~, lambda_Im, alpha).
  std::unique_ptr<SubdomainSet> subdomains_;         ///< owned subdomains, dual layout, blockwise sums
  std::unique_ptr<Preconditioners> preconditioners_;  ///< lumped and Dirichlet blocks
  std::unique_ptr<CoarseSpace> coarse_;              ///< G, G G^T, the projector
  std::unique_ptr<PrimalRecovery> recovery_;         ///< alpha, u, residuals
  std::vector<double> e_;
  Teuchos::RCP<DualVector> dTilde_, lambdaIm_;
  std::vector<double> c_;  ///< c on the owned rows (ownedC)
  mutable long long fApplications_ = 0;
  mutable OperatorProfile profile_;
  double factorizationSeconds_ = 0.0;
  long long factorNonzeros_ = 0;
  double bytesPerFApplication_ = 0.0;
  /// Of bytesPerFApplication_: the subdomains' solves and rows of B alone (layout-independent;
  /// "Auto" of TotalFetiSettings::coarsePrecision compares the coarse solves with it).
  double subdomainBytesPerF_ = 0.0;
};

}  // namespace tribos::feti
