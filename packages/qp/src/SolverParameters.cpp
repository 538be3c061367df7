// The parameters of SMALSE-M and MPGP: one table line each (STYLE.md 3). The defaults are
// the member initialisers of SmalseSettings / MpgpSettings; doc/parameters.md says why they
// were chosen (measured).
#include "tribos/qp/SolverParameters.hpp"

#include "tribos/core/ParameterTable.hpp"
#include "tribos/core/Parameters.hpp"

namespace tribos::qp {

namespace {
constexpr int kMaxCount = 1000000000;  // iteration caps: any int a run could reach

// "Tolerance" and "Max Outer Iterations": the stopping test, at the level of the scene's
// "Solver" list (the linear T-FETI solve shares the tolerance).
const core::ParameterTable<SmalseSettings>& stoppingTable() {
  static const auto table =
      core::ParameterTable<SmalseSettings>()
          .add("Tolerance", &SmalseSettings::tolerance,
               "the paper's epsilon: SMALSE-M stops when ||g^P|| <= epsilon ||c|| and the equality test holds "
               "(c = P h in T-FETI; Coulomb: and the slip bound moved by <= epsilon); linear T-FETI solves stop at "
               "||P r|| <= epsilon ||P h||",
               core::openInterval(0.0, 1.0))
          .add("Max Outer Iterations", &SmalseSettings::maxOuterIterations,
               "cap on SMALSE-M outer iterations per SMALSE-M run; reaching it ends the solve as not converged "
               "(exit 3, the message names the cap)",
               core::intRange(1, kMaxCount));
  return table;
}

const core::ParameterTable<SmalseSettings>& smalseTable() {
  static const auto table =
      core::ParameterTable<SmalseSettings>()
          .add("eta", &SmalseSettings::eta,
               "eta, relative to ||c|| (= ||P h||): cap of the inner stopping bound min(M_k ||G mu||, eta)",
               core::greaterThan(0.0))
          .add("rho", &SmalseSettings::rho,
               "rho, relative to ||A|| (= ||PFP||): penalty of A_rho = A + rho Q (the paper: 1; 10 needs far fewer "
               "outer iterations here, doc/parameters.md)",
               core::greaterThan(0.0))
          .add("initial M", &SmalseSettings::M0,
               "M_0, relative to ||A||: inner precision control M_k ||G mu|| (the paper: 1e-6, which runs every "
               "inner solve to round-off; doc/parameters.md)",
               core::greaterThan(0.0))
          .add("beta", &SmalseSettings::betaM,
               "beta_M: M_{k+1} = beta_M M_k when the Lagrangian grew by less than rho/2 ||G mu||^2 (the paper: "
               "0.1; PERMON: 0.5; ESPRESO: 0.8). With Coulomb's moving slip bound the test fails in most outer "
               "iterations, so beta_M sets how fast the inner solves tighten: 0.9 needs 5-12 % fewer F "
               "applications than 0.5 (doc/parameters.md)",
               core::openInterval(0.0, 1.0))
          .add("equality test", &SmalseSettings::equalityTest,
               "outer test on ||G mu|| = ||Q mu||: \"Conventional\" (||A|| ||Q mu|| <= epsilon ||c||) or \"Paper\" "
               "(||Q mu|| <= epsilon M_0 ||mu||)",
               kEqualityTestNames)
          .add("stall window", &SmalseSettings::stallWindow,
               "stop, not converged, when ||G mu|| has not halved over this many outer iterations while above 100 "
               "epsilon and, with friction, the load along some interface exceeds its friction capacity F N: the "
               "bodies' balance G lambda = e cannot be met inside the constraints (loads beyond what contact and "
               "friction carry; a joint below its capacity may approach equilibrium with ||G mu|| flat for a while, "
               "and goes on); 0: never",
               core::intRange(0, kMaxCount))
          .add("rho growth", &SmalseSettings::rhoGrowth,
               "rho is multiplied by it (rho update Ratio; Model: by at most it) after more than rho growth "
               "patience outer iterations in a row reduced ||G mu|| by less than the rho target ratio (1: fixed "
               "rho, the paper's algorithm)",
               core::atLeast(1.0))
          .add("rho target ratio", &SmalseSettings::rhoTargetRatio,
               "the reduction of ||G mu|| per outer iteration that rho growth asks for",
               Teuchos::rcp(new core::RealRangeValidator(0.0, /*lowIncluded=*/false, 1.0, /*highIncluded=*/true)))
          .add("rho growth patience", &SmalseSettings::rhoGrowthPatience,
               "rho grows (rho growth > 1) only after this many outer iterations in a row reduced ||G mu|| by less "
               "than the rho target ratio: a solve at the fixed rate keeps rho, one whose ||G mu|| crawls (a body "
               "held only by friction at capacity on two faces) gets the growth (0: from the first such iteration)",
               core::intRange(0, kMaxCount))
          .add("rho update", &SmalseSettings::rhoUpdate,
               "how rho grows after an outer iteration that reduced ||G mu|| by a ratio r above the rho target "
               "ratio t (rho growth > 1 only): \"Ratio\" multiplies it by rho growth; \"Model\" by (1/t - 1) / "
               "(1/r - 1), at most rho growth, while the equality test fails (the augmented-Lagrangian rate r = 1 / "
               "(1 + rho s) solved for the rho that gives t; doc/parameters.md)",
               kRhoUpdateNames)
          .add("multiplier step", &SmalseSettings::multiplierStep,
               "Step 3, beta += omega rho G mu: \"Fixed\" omega = 1 (the paper's); \"Relaxed\" omega = 2 / (2 - r0) "
               "in [1, 5/3], r0 the contraction of ||G mu|| per outer iteration that omega = 1 would give, measured "
               "(omega = 1 while r0 <= 0.3 or G mu turns; doc/parameters.md)",
               kMultiplierStepNames)
          .add("norm estimate steps", &SmalseSettings::normEstimateSteps,
               "cap on the Lanczos steps (products with A, counted in the PFP applications) that estimate ||A|| "
               "(8-15 on Table 1 at the default tolerance, 9-25 at 1e-4; the power method needed about 25 for 1e-4)",
               core::intRange(1, 100000))
          .add("norm estimate tolerance", &SmalseSettings::normEstimateTolerance,
               "Lanczos stops when its estimate of ||A|| moves by at most this (relative) in a step. For rho >= 2 the "
               "estimate only scales rho, M_0 and the equality test (alpha_bar = 1.9 / (1.02 rho ||A||) is safe for "
               "any estimate above ||A|| / rho); below rho = 2 at most 1e-4 is used (doc/parameters.md)",
               Teuchos::rcp(new core::RealRangeValidator(0.0, /*lowIncluded=*/false, 1.0, /*highIncluded=*/false)))
          .add("inner floor", &SmalseSettings::innerFloor,
               "inner solves stop at ||g^P|| <= (inner floor) epsilon ||c|| at the latest (M_k may shrink without "
               "limit when the Coulomb slip bound moves)",
               core::closedInterval(0.0, 1.0));
  return table;
}

const core::ParameterTable<MpgpSettings>& mpgpTable() {
  static const auto table =
      core::ParameterTable<MpgpSettings>()
          .add("step scale", &MpgpSettings::stepScale,
               "alpha_bar = (step scale) / ||A_rho||: the fixed expansion step, convergent for 0 < alpha_bar < "
               "2 / ||A_rho||",
               core::openInterval(0.0, 2.0))
          .add("Gamma", &MpgpSettings::gamma,
               "Gamma: proportioning test ||beta||^2 <= Gamma^2 phi~^T phi", core::greaterThan(0.0))
          .add("max iterations", &MpgpSettings::maxIterations,
               "cap on MPGP iterations per inner solve (an inner solve that reaches it hands its iterate to the "
               "next outer iteration; the final message counts them)",
               core::intRange(1, kMaxCount))
          .add("optimal expansion", &MpgpSettings::optimalExpansion,
               "expansion steps try the exact minimiser along the free gradient (projected, monotone safeguard) "
               "before the fixed alpha_bar step")
          .add("chopped proportioning", &MpgpSettings::choppedProportioning,
               "a proportioning step that follows another goes along the chopped gradient with the exact step "
               "length on the constraint boundary (MPRGP's step, the ellipses' curvature included, projected; kept "
               "with a sufficient decrease, else the gradient projection step with alpha_bar)")
          .add("tangent CG", &MpgpSettings::tangentCg,
               "CG steps also move the friction multipliers on the boundary of their ellipse, along its tangent "
               "(projected back; one more product with A when that moves them; kept if f decreases, else the "
               "gradient projection step)")
          .add("tangent CG after", &MpgpSettings::tangentCgAfter,
               "tangent CG: switched on in an inner solve once it has taken this many proportioning steps "
               "(0: from the start)",
               core::intRange(0, kMaxCount));
  return table;
}
}  // namespace

void declareSolverParameters(Teuchos::ParameterList& solver) {
  stoppingTable().declare(solver);
  smalseTable().declare(
      solver.sublist("SMALSE-M", false, "semi-monotonic augmented Lagrangian (paper Section 5, ALGORITHMS.md 4)"));
  mpgpTable().declare(solver.sublist(
      "MPGP", false, "inner solver for the bound and elliptic-cone constraints (ALGORITHMS.md 5)"));
}

SmalseSettings readSolverParameters(const Teuchos::ParameterList& solver) {
  SmalseSettings s;
  stoppingTable().read(solver, s);
  if (solver.isSublist("SMALSE-M")) smalseTable().read(solver.sublist("SMALSE-M"), s);
  if (solver.isSublist("MPGP")) mpgpTable().read(solver.sublist("MPGP"), s.mpgp);
  return s;
}

Teuchos::RCP<const Teuchos::ParameterList> SmalseM::getValidParameters() {
  static const auto valid = [] {
    auto pl = Teuchos::rcp(new Teuchos::ParameterList("Solver"));
    declareSolverParameters(*pl);
    return Teuchos::rcp_const_cast<const Teuchos::ParameterList>(pl);
  }();
  return valid;
}

SmalseSettings SmalseM::settingsFromParameters(Teuchos::ParameterList& pl) {
  core::validateAndSetDefaults(pl, *getValidParameters(), "tribos::qp::SmalseM parameters");
  return readSolverParameters(pl);
}

}  // namespace tribos::qp
