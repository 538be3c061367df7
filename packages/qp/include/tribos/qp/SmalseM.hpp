#pragma once
/// \file SmalseM.hpp
/// SMALSE-M (paper Section 5; ALGORITHMS.md 4): semi-monotonic augmented Lagrangian for
///     min 1/2 mu^T A mu - mu^T c   s.t.  mu in Omega,  G mu = 0,
/// with the penalised Hessian A_rho = A + rho Q (A = P F P, Q = I - P in T-FETI), the inner
/// problems solved by MPGP to ||g^P|| <= min(M_k ||G mu||, eta), multipliers beta kept as
/// the dual vector G^T beta (updated by rho Q mu), and M_k divided by beta_M when the
/// Lagrangian does not grow enough. A hook after each outer iteration lets the Coulomb
/// fixed point update the slip bounds (inexact successive approximations, eq. (20)).
#include <functional>
#include <string>
#include <vector>

#include <Teuchos_RCP.hpp>

#include "tribos/core/EnumNames.hpp"
#include "tribos/qp/Mpgp.hpp"

namespace tribos::qp {

/// What SMALSE-M reports after each outer iteration (for progress lines and studies).
struct SmalseProgress {
  int outerIteration = 0;
  int innerIterations = 0;          ///< MPGP iterations of this outer iteration
  double projectedGradient = 0.0;   ///< ||g^P|| / ||c||
  double equalityResidual = 0.0;    ///< ||A|| ||Q mu|| / ||c|| (the scale-free ||G mu||)
  double M = 0.0;                   ///< M_k relative to ||A||
  long long operatorApplications = 0;  ///< products with A so far
  double innerTarget = 0.0;         ///< the inner stopping bound / ||c|| (innerMonitor only)
};

/// SMALSE-M's options (their names: the parameter list's, SolverParameters.cpp).
enum class EqualityTest { Conventional, Paper };
inline constexpr core::EnumNames<EqualityTest, 2> kEqualityTestNames{
    {{"Conventional", EqualityTest::Conventional}, {"Paper", EqualityTest::Paper}}};
enum class RhoUpdate { Ratio, Model };
inline constexpr core::EnumNames<RhoUpdate, 2> kRhoUpdateNames{{{"Ratio", RhoUpdate::Ratio}, {"Model", RhoUpdate::Model}}};
enum class MultiplierStep { Relaxed, Fixed };
inline constexpr core::EnumNames<MultiplierStep, 2> kMultiplierStepNames{
    {{"Relaxed", MultiplierStep::Relaxed}, {"Fixed", MultiplierStep::Fixed}}};

/// The defaults are the solver stack's (measured, doc/parameters.md), not the paper's (rho 1,
/// M0 1e-6, betaM 0.1); src/SolverParameters.cpp declares each value below (not the
/// callbacks) as a parameter.
struct SmalseSettings {
  /// epsilon: stop when ||g^P|| <= eps ||c|| and the equality test holds. ||G mu|| is
  /// measured as ||Q mu|| (rows of G orthonormal) and, to be scale-free, enters the
  /// Conventional test and the reports multiplied by ||A||: the paper's tests hold for the
  /// problem scaled to ||PFP|| = 1.
  double tolerance = 1e-5;
  double eta = 1.0;            ///< eta, relative to ||c|| (the paper: eta = ||P h||)
  double rho = 10.0;           ///< rho, relative to ||A|| (the paper: rho = ||P F P||, i.e. 1)
  double M0 = 1.0;             ///< M_0 > 0, relative to ||A|| (M has the units of A); paper: 1e-6
  double betaM = 0.9;          ///< M_{k+1} = betaM M_k when the Lagrangian does not grow enough (paper: 0.1)
  int maxOuterIterations = 100;
  /// Stop (not converged, SmalseCounters::stalled) when ||G mu|| has not halved over this many
  /// outer iterations while above 100 epsilon: the equality G lambda = e (every body's
  /// balance) cannot be met inside Omega, e.g. loads beyond what friction can carry; where
  /// stallConfirmed is given, only when it confirms. 0: never.
  int stallWindow = 20;
  /// Conventional: ||A|| ||Q mu|| <= eps ||c||;  Paper: ||Q mu|| <= eps M_0 ||mu||
  /// (M_0 relative, so the paper's eps M_0 = 1e-11 needs a tolerance above round-off).
  EqualityTest equalityTest = EqualityTest::Conventional;
  MpgpSettings mpgp;
  /// Preconditioning in face for the inner CG steps: M^-1 ~ A^+ on Ker G (T-FETI: P D P with
  /// the lumped or Dirichlet D). SMALSE-M preconditions A_rho = A + rho Q by M^-1 + Q / rho
  /// (exact on Im G^T, where A_rho = rho I). Null: none. Overrides mpgp.preconditioner.
  const SymmetricOperator* preconditioner = nullptr;
  int normEstimateSteps = 50;  ///< cap on the Lanczos steps for ||A||
  /// Lanczos stops when its estimate of ||A|| moves by at most this (relative) in a step; at
  /// most 1e-4 when rho < 2 (normEstimateToleranceFor).
  double normEstimateTolerance = 1e-3;
  /// > 1: rho *= rhoGrowth when ||G mu|| fell by less than rhoTargetRatio in more than
  /// rhoGrowthPatience outer iterations in a row (1: the paper's fixed rho).
  double rhoGrowth = 2.0;
  double rhoTargetRatio = 0.5;
  /// rho grows only after this many outer iterations in a row missed rhoTargetRatio (0: at
  /// the first): a solve that converges at the fixed rate keeps rho (and its counts), one whose
  /// ||G mu|| crawls (a body held by friction at capacity on two faces: issue 43, the bolted
  /// joint at eps 1e-6) gets the growth. Measured: doc/parameters.md, "rho growth".
  int rhoGrowthPatience = 10;
  /// Ratio: rho *= rhoGrowth; Model: rho *= min(rhoGrowth, (1/t - 1)/(1/r - 1)) for the
  /// measured ratio r and the target t, while the equality test fails (SmalseM.cpp, rhoFactor).
  RhoUpdate rhoUpdate = RhoUpdate::Ratio;
  /// Step 3, beta += omega rho G mu: Fixed omega = 1 (the paper's); Relaxed omega in [1, 5/3]
  /// from the measured contraction of ||G mu|| (src/MultiplierRelaxation.hpp).
  MultiplierStep multiplierStep = MultiplierStep::Relaxed;
  double innerFloor = 0.1;     ///< inner solves stop at ||g^P|| <= innerFloor eps ||c|| at the latest
  /// > 0: the scale of epsilon and eta (and of the reported relative residuals) in place of
  /// ||c||, for a c inflated by what drives no solution (open contact gaps: the caller's
  /// DualContactProblem::stoppingScale), at least 1e3 DBL_EPSILON ||c|| / tolerance (round-off); 0:
  /// ||c||. Not a parameter: set by the caller per problem.
  double rightHandSideScale = 0.0;
  /// Called on every rank after each outer iteration (after the hook, so that it sees what
  /// the hook changed; not when the hook throws); may be empty.
  std::function<void(const SmalseProgress&)> monitor;
  /// Called during the inner solves, after every mpgp.progressEvery MPGP iterations, with the
  /// outer iteration in progress and its MPGP iterations so far (M, ||G mu|| and the products
  /// with A as they stand); collective-safe under the rule of MpgpSettings::progress, which it
  /// replaces. May be empty.
  std::function<void(const SmalseProgress&)> innerMonitor;
  /// A budget (wall clock, ...): asked at every inner stopping test and after every outer
  /// iteration; true ends the inner solve and then the outer loop (not converged). Called on
  /// every rank at the same points, so it may communicate to reach one verdict; once true it
  /// must stay true. May be empty.
  std::function<bool()> stopRequested;
  /// Asked, with the current iterate mu, when ||G mu|| stalled (stallWindow) before SMALSE-M
  /// stops on it: a caller that can tell loads beyond what Omega admits from a slow approach
  /// answers (the contact solver: the friction capacity against the load). Called on every
  /// rank at the same points (collective-safe). Empty: every stall stops.
  std::function<bool(const Vector&)> stallConfirmed;
};

struct SmalseCounters {
  int outerIterations = 0, innerIterations = 0, cgSteps = 0, expansionSteps = 0, proportioningSteps = 0;
  long long operatorApplications = 0;  ///< products with A (each = one F application in T-FETI), incl. power method
  long long preconditionerApplications = 0;  ///< products with the inner preconditioner
  double projectedGradient = 0.0;      ///< ||g^P|| / ||c|| at return
  double equalityResidual = 0.0;       ///< ||A|| ||Q mu|| / ||c|| at return
  double normA = 0.0;
  /// Wall seconds of solve(), and of them those spent inside A (products with A_rho and the
  /// norm estimate's), the preconditioner, Q and the hook: seconds - operatorSeconds is
  /// SMALSE-M's and MPGP's own work (vector updates, projections onto Omega, reductions).
  double seconds = 0.0, operatorSeconds = 0.0;
  /// Of operatorSeconds: the products with A_rho and the norm estimate's products with A (what
  /// operatorApplications counts), and the applications of the inner preconditioner M^-1 + Q/rho
  /// (what preconditionerApplications counts), each with its projections (issue 9's time per
  /// PFP application measured on the product alone).
  double productSeconds = 0.0, preconditionerSeconds = 0.0;
  bool converged = false;
  bool nonFinite = false;  ///< stopped on a NaN or infinite norm (||PFP||, ||g^P||, ||G mu||)
  bool stalled = false;    ///< stopped because ||G mu|| stalled (SmalseSettings::stallWindow)
};

/// Called after every outer iteration with (k, mu, ||g^P||/||c||, ||A|| ||Q mu||/||c||,
/// M_k/||A||), after the multiplier and M updates (the multiplier is not updated at an
/// iteration that met SMALSE-M's criteria). It may change Omega (the Coulomb slip bound update g := lambda_nu).
/// It returns true to veto convergence at this iteration (the slip bound moved by more than
/// epsilon): SMALSE-M stops only when its own criteria hold and the hook returned false.
using OuterHook = std::function<bool(int, const Vector&, double, double, double)>;

/// The Lanczos tolerance for ||A|| that SmalseM::solve uses: the setting, at most 1e-4 when rho < 2.
double normEstimateToleranceFor(const SmalseSettings& s);

class SmalseM {
 public:
  explicit SmalseM(SmalseSettings settings = {}) : settings_(settings) {}
  /// Solves from mu (projected on Omega first). A = P F P must map into Ker G; Q projects
  /// onto Im G^T. Omega may be changed by the hook between outer iterations; the next inner
  /// solve starts from mu projected onto the new Omega. Scale-free parameters: rho and M_0
  /// are relative to ||A|| (power method, its products counted), eta and epsilon to ||c||
  /// (or SmalseSettings::rightHandSideScale)
  /// (when c = 0, ||A|| ||P_Omega(0)|| is the scale, and mu = 0 is returned at once if 0 is in
  /// Omega). A = 0 returns converged = false unless c = 0. `knownNormA` > 0: ||A|| as an
  /// earlier solve with the same A estimated it (its counters.normA), used instead of a new
  /// estimate, which would repeat the same products to the same bits (the exact Coulomb fixed
  /// point solves one Tresca problem after another with the same A).
  SmalseCounters solve(const SymmetricOperator& A, const EqualityProjector& Q, const Vector& c, SeparableSet& omega,
                       Vector& mu, const OuterHook& hook = nullptr, double knownNormA = 0.0) const;

  /// The valid parameters (STYLE.md 3), a list shaped like the scene's "Solver":
  /// "Tolerance", "Max Outer Iterations", sublist "SMALSE-M" (eta, rho, initial M, beta,
  /// equality test, rho growth, rho target ratio, rho update, multiplier step, norm estimate steps, inner floor) and sublist
  /// "MPGP" (step scale, Gamma, max iterations, optimal expansion), each with a doc string
  /// and its validated range. The defaults are those of SmalseSettings / MpgpSettings.
  /// Declared in src/SolverParameters.cpp (qp/SolverParameters.hpp).
  static Teuchos::RCP<const Teuchos::ParameterList> getValidParameters();
  /// Validates `pl` against getValidParameters() (unknown or mistyped names and values out
  /// of range throw core::InputError), fills in the defaults and returns the settings. The
  /// monitors are left empty.
  static SmalseSettings settingsFromParameters(Teuchos::ParameterList& pl);

 private:
  SmalseSettings settings_;
};

}  // namespace tribos::qp
