#pragma once
/// \file Mpgp.hpp
/// MPGP: modified proportioning with (reduced) gradient projections for
///     min 1/2 x^T A x - b^T x   s.t.  x in Omega (separable: bounds and ellipses),
/// ALGORITHMS.md 5 (Dostal & Kozubek; the paper's ref. [17]). CG steps on the free set,
/// expansion steps by the reduced free gradient, proportioning steps by gradient projection.
#include <functional>
#include <string>

#include "tribos/qp/DualTypes.hpp"
#include "tribos/qp/SeparableSet.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::qp {

struct MpgpCounters;

struct MpgpSettings {
  double stepScale = 1.9;   ///< alpha_bar = stepScale / ||A||, in (0, 2)
  double gamma = 1.0;       ///< Gamma > 0: proportioning test ||beta||^2 <= Gamma^2 phi~^T phi
  int maxIterations = 100000;  ///< per inner solve
  /// Expansion steps: try the exact minimiser along the free gradient (projected, with a
  /// monotonicity safeguard) before the fixed alpha_bar step (ALGORITHMS.md 5: adapted step).
  bool optimalExpansion = false;
  /// A proportioning step right after another goes along the chopped gradient with the
  /// exact step length on the boundary arc (MPRGP's step; beta^T A beta plus the ellipses'
  /// curvature term), projected on Omega and kept if f decreases, instead of the gradient
  /// projection step with alpha_bar.
  bool choppedProportioning = true;
  /// Tangent CG: active ellipse blocks are free along their tangent in CG steps (linearised
  /// face, projected back onto the boundary; one more product with A when that moves x, and
  /// the step kept only if f decreases), instead of fixed until a proportioning step.
  bool tangentCg = true;
  /// Tangent CG from this many proportioning steps of an inner solve on (0: from the start):
  /// the crawl it is for shows as a run of proportioning steps; on the paper's bricks every
  /// inner solve takes fewer, and tangent CG from the start doubled their F applications.
  int tangentCgAfter = 10;
  /// Preconditioning in face: CG steps use z = chi_F M^-1 phi (M^-1 applied to the free
  /// gradient, then restricted to the free set F of the current face) instead of phi. Must be
  /// symmetric positive definite on the free set; null: no preconditioner (z = phi).
  /// Expansion and proportioning steps are not preconditioned.
  const SymmetricOperator* preconditioner = nullptr;
  /// Progress of long solves: called after every `progressEvery` iterations with the
  /// counters so far (projectedGradientNorm: ||g^P|| of the current iterate). The iterations
  /// are collective, so every rank that sets it calls it at the same iteration; it must do no
  /// communication unless every rank sets it. May be empty.
  std::function<void(const MpgpCounters&)> progress;
  int progressEvery = 10;
  /// Called right after each CG step x := x - alpha p (before p changes), for quantities of
  /// x that follow such steps linearly (SMALSE-M's ||Q x||). Other steps are not reported:
  /// between two stop tests there is one iteration, so no call means x moved otherwise.
  /// May be empty.
  std::function<void(double alpha, const Vector& p)> cgStep;
  /// Called right after g = A x - b was computed by a product with the iterate x itself, so
  /// that the last product's input is x (SMALSE-M then takes the coordinates of Q x from
  /// that product: EqualityNorm). May be empty.
  std::function<void()> gradientFromProduct;
};

struct MpgpCounters {
  int iterations = 0, cgSteps = 0, expansionSteps = 0, proportioningSteps = 0;
  long long operatorApplications = 0;  ///< products with A
  long long preconditionerApplications = 0;  ///< products with the preconditioner M^-1
  double projectedGradientNorm = 0.0;  ///< ||g^P|| at return
  bool converged = false;
  bool nonFinite = false;              ///< stopped: ||g^P|| was NaN or infinite (never "converged")
};

class Mpgp {
 public:
  explicit Mpgp(MpgpSettings settings = {}) : settings_(settings) {}
  /// Minimises from x (projected onto Omega first) until stop(||g^P||, x) returns true
  /// (tested at the start too: converged, 0 iterations) or maxIterations (converged =
  /// false). `normA` >= ||A|| (the power method's estimate, slightly enlarged);
  /// alpha_bar = stepScale / normA. On return x is the iterate and g = A x - b. Every
  /// product with A is counted; iterations = cgSteps + expansionSteps + proportioningSteps.
  /// `gradientGiven`: g already holds A x - b for the x passed in (SMALSE-M's next outer
  /// iteration: the same x, b moved by a known vector); it is used as it stands when the
  /// projection onto Omega leaves x in place (bit for bit on every rank), which saves a product.
  MpgpCounters solve(const SymmetricOperator& A, const Vector& b, const SeparableSet& omega, double normA,
                     Vector& x, Vector& g, const std::function<bool(double, const Vector&)>& stop,
                     bool gradientGiven = false) const;

 private:
  MpgpSettings settings_;
};

/// ||A|| by the power method from a deterministic start (a function of the global index, so
/// the estimate does not depend on the number of ranks): `iterations` products with A (or
/// fewer when the estimate changes by less than `tolerance`, relative). Returns the norm
/// ratio ||A x|| / ||x|| of the last iterate, a lower bound of ||A|| (callers that need an
/// upper bound for the MPGP step enlarge it; SmalseM uses 1.02 times it), and adds the
/// products made to *applications (may be null).
double powerMethod(const SymmetricOperator& A, const Map& map, int iterations, double tolerance,
                   long long* applications);

/// ||A|| (A symmetric positive semidefinite) as the largest Ritz value of at most `maxSteps`
/// Lanczos steps from the same deterministic start, stopping when it changes by at most
/// `tolerance` (relative) or the Krylov space is invariant. A lower bound of ||A||, like the
/// power method's, reached in far fewer products; NaN when A produced a non-finite value.
double lanczosNorm(const SymmetricOperator& A, const Map& map, int maxSteps, double tolerance,
                   long long* applications);

}  // namespace tribos::qp
