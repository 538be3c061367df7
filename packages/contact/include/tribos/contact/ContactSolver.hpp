#pragma once
/// \file ContactSolver.hpp
/// The contact problem on top of T-FETI (paper Sections 2, 5; ALGORITHMS.md 4-7):
///  - friction models: None (frictionless: only normal rows), Tresca (given slip bound g),
///    Coulomb (successive approximations on g, eq. (20)), each isotropic or orthotropic
///    (F = diag(F1, F2) in the frame (t1, t2));
///  - the dual QP  min 1/2 mu^T (PFP + rho Q) mu - mu^T (P h - G^T beta)  s.t.
///    mu + lambda_Im in Lambda(g), solved by SMALSE-M with MPGP inner iterations;
///  - Coulomb: the inexact fixed point updates g := mu_nu + lambda_Im,nu after every
///    SMALSE-M outer iteration (the paper's choice); the exact variant solves every Tresca
///    problem to epsilon before updating g. Stagnation / divergence of the fixed point is
///    detected and reported, never returned as converged;
///  - recovery of alpha over the rows where the dual constraints are inactive, of u, of the
///    contact status (no contact / stick / slip) and the KKT residuals of the discrete problem.
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "tribos/contact/FrictionModel.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/qp/SmalseM.hpp"

namespace tribos::contact {

struct FrictionSettings {
  /// The law of each contact interface, indexed by feti::ContactNode::interface. Bonded
  /// interfaces keep their rows as equalities (tied) beside the others' inequalities.
  std::vector<FrictionLaw> laws{FrictionLaw{}};
  /// True when some interface's bound follows its normal force (Coulomb): the solve then runs
  /// successive approximations of the slip bound.
  bool successiveApproximations() const;
  FixedPoint fixedPoint = FixedPoint::Inexact;
  /// Coulomb, Inexact: Epsilon stops only once an update moved g by at most eps (relative);
  /// Paper on SMALSE-M's criteria alone, as the paper's Section 5 (its Table 1 counts).
  SlipBoundTest slipBoundTest = SlipBoundTest::Epsilon;
  int maxFixedPointIterations = 50;    ///< Exact variant: cap on Tresca solves
  /// Divergence: the fixed-point change grew in this many consecutive updates (after the
  /// first few) -> stop and report "fixed point diverges".
  int divergenceWindow = 8;
  /// Called on every rank after each outer iteration with the progress and the relative
  /// slip-bound change ||g_{k+1} - g_k|| / ||g_k|| (Coulomb: of this iteration's update when
  /// inexact, of the last Tresca solve when exact; infinite after an update from g = 0; 0
  /// without Coulomb); may be empty.
  std::function<void(const qp::SmalseProgress&, double)> progress;
  /// Given the normal force of each interface (ConstraintMatrix::interfaces' order) of the
  /// current iterate: whether the loads exceed what friction can carry at some interface.
  /// SMALSE-M stops on a stall only then (qp::SmalseSettings::stallConfirmed): a joint near
  /// its capacity approaches equilibrium slowly, with ||G mu|| flat for a while (issue 42).
  /// Called on every rank at the same points; empty: every stall stops.
  std::function<bool(const std::vector<double>&)> overloaded;
};

enum class ContactStatus : int { NoContact = 0, Stick = 1, Slip = 2 };

/// Normalised residuals of the KKT conditions of the discrete problem (ALGORITHMS.md 7).
struct KktReport {
  double equilibrium = 0.0;       ///< max ||K_s u_s - f_s + B_s^T lambda_s||_inf / ||f||_inf
  double equality = 0.0;          ///< ||B_E u - c_E|| / ||u|| (gluing, prescribed displacements)
  double nonPenetration = 0.0;    ///< max(N u - c, 0) / ||u||_inf
  double complementarity = 0.0;   ///< |lambda_nu^T (N u - c)| / (||lambda_nu|| ||u||_inf)
  double normalSign = 0.0;        ///< max(-lambda_nu, 0) / ||lambda_nu||_inf
  double frictionAdmissibility = 0.0;  ///< max(||F^-1 lambda_t|| - g, 0) / ||lambda_nu||_inf
                                       ///< (|lambda_t| itself along a zero coefficient F_j)
  double slipRule = 0.0;          ///< max over slip nodes of (max over the friction ellipse of
                                  ///< lambda_t^T v - lambda_t^T v) / (||lambda_nu||_inf ||u||_inf)
  double stickRule = 0.0;         ///< max over stick nodes of ||v|| / ||u||_inf
};

/// One contact node owned by this rank, as the user sees it.
struct ContactNodeResult {
  LO slaveNode = -1;
  std::array<double, 3> force{};  ///< physical nodal force of slave on master in (nu, t1, t2)
  std::array<double, 3> relativeDisplacement{};  ///< (u_slave - u_master) in (nu, t1, t2)
  /// The gap after deformation: d minus the normal relative displacement, prescribed
  /// components included, (c_r - (B u)_r) / rowScale; >= 0 up to the tolerance, 0 in contact.
  double opening = 0.0;
  double slipBound = 0.0;         ///< g (force units) of the last Tresca problem
  ContactStatus status = ContactStatus::NoContact;
};

struct ContactResult {
  bool converged = false;
  std::string message;            ///< why it stopped
  std::string note;               ///< a finding about the result, also appended to message
  qp::SmalseCounters counters;    ///< summed over all SMALSE-M runs
  int fixedPointIterations = 0;   ///< updates of g (Coulomb)
  double fixedPointChange = 0.0;  ///< ||g_{k+1} - g_k|| / ||g_k|| at the end
  /// The Coulomb fixed point diverged (FixedPointWatch): the run stopped there, its counts kept.
  bool fixedPointDiverged = false;
  KktReport kkt;
  double kktTolerance = 0.0;      ///< every KKT residual must be <= this for "converged"
  std::array<int, 3> statusCounts{0, 0, 0};  ///< no contact, stick, slip (global)
  double energy = 0.0;            ///< 1/2 u^T K u - f^T u (global)
  std::vector<std::vector<double>> displacement;  ///< u_s of the owned subdomains
  std::vector<ContactNodeResult> nodes;           ///< contact nodes whose rows this rank owns
  /// lambda of the rows this rank owns, [B.firstRowOfRank[rank], B.firstRowOfRank[rank + 1]):
  /// the reactions of the prescribed displacements are read from it.
  std::vector<double> lambda;
};

/// Solves the contact problem. B's contact rows must have tangential rows unless their
/// interface's model is None; some interface must be None, Tresca or Coulomb (a scene of
/// Bonded interfaces only is linear). `preconditioner` other than None (then feti must have been built with its blocks):
/// MPGP's preconditioning in face by P D P. Collective.
/// A start from an earlier solve on the same operators (a load step from the last).
struct WarmStart {
  /// lambda on this rank's rows (empty: mu = 0): the first iterate is mu = lambda - lambda_Im
  /// (projected on Omega), and Coulomb's slip bound starts from its normal components.
  std::vector<double> lambda;
  double normA = 0.0;  ///< > 0: ||PFP|| as estimated before (qp::SmalseCounters::normA), not again
};

ContactResult solveContact(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                           const FrictionSettings& friction, const qp::SmalseSettings& smalse,
                           feti::DualPreconditioner preconditioner = feti::DualPreconditioner::None,
                           const WarmStart& warm = {});

}  // namespace tribos::contact
