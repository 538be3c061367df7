#pragma once
// Internal to contact/: the homogenised dual contact problem of one solve (paper (19),
// ALGORITHMS.md 4-6) — the right-hand side c = P h, the separable set Omega(g) of the friction
// law, the slip bound g per contact node and what the Coulomb fixed point asks of them — and
// the friction geometry the recovery and the KKT report share.
#include <Teuchos_Comm.hpp>

#include <array>
#include <vector>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/qp/SeparableSet.hpp"

namespace tribos::contact {

/// The contact nodes whose rows this rank owns, with local row indices.
struct LocalContact {
  std::vector<int> node;                    ///< index into B.contact
  std::vector<LO> normalRow;                ///< local index of N_r
  std::vector<std::array<LO, 2>> tangentialRow;  ///< local indices of T1_r, T2_r (-1: absent)
  /// Multiplier of T_j per unit multiplier of N_r at equal physical force: rowScale_N /
  /// rowScale_Tj (rows are scaled to unit norm separately; 1 unless prescribed components
  /// were dropped from some rows).
  std::vector<std::array<double, 2>> axisScale;
  std::vector<int> ellipse;                 ///< index of the node's friction block, -1 if none
  std::vector<FrictionModel> model;         ///< the friction law of the node's interface
  std::vector<std::array<double, 2>> F;     ///< its coefficients (F1, F2)
};

/// Where lambda_t of one node stands against its friction bound g (N-multiplier units):
/// semi-axes a_j = F_j axisScale_j g on the present tangential rows.
struct FrictionState {
  bool degenerate = false;  ///< a present axis has a = 0: the node slides freely along it
  double normalised = 0.0;  ///< ||diag(1/a) lambda_t|| over the non-degenerate axes
  double excess = 0.0;      ///< max(||F^-1 lambda_t|| - g, 0) + |lambda_t| on zero axes (N units)
  std::array<double, 2> axes{0.0, 0.0};
};

FrictionState frictionState(const std::array<double, 2>& lambdaT, const std::array<LO, 2>& rows,
                            const std::array<double, 2>& axisScale, const std::array<double, 2>& F, double g,
                            double tinyForce);

/// The sum of every rank's terms, the same bits on any layout (core/ReproducibleSum.hpp);
/// `count` bounds the number of terms over all ranks and is the same on every rank.
double globalSum(const Teuchos::Comm<int>& comm, const std::vector<double>& terms, long long count);
double globalMax(const Teuchos::Comm<int>& comm, double v);

class DualContactProblem {
 public:
  /// Steps (1) and (2) of solveContact: c = P h and Omega with g = 0 (Coulomb) or the given
  /// Tresca bound. Collective.
  DualContactProblem(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B, const FrictionSettings& friction);

  const feti::DualVector& rightHandSide() const { return *c_; }
  /// The scale of SMALSE-M's tolerances (qp::SmalseSettings::rightHandSideScale): ||P h_d||,
  /// h_d = h without the open gaps of the contact rows; 0 (||P h|| then) where no gap is open.
  double stoppingScale() const { return stoppingScale_; }
  /// Some rank holds a contact node of a Coulomb interface (the same on every rank).
  bool hasCoulombNodes() const { return coulombNodes_; }
  qp::SeparableSet& omega() { return omega_; }
  const LocalContact& contact() const { return lc_; }
  /// g per local contact node, N-multiplier units.
  const std::vector<double>& slipBounds() const { return slip_; }
  /// g := `g`, and Omega's ellipses with it.
  void setSlipBounds(const std::vector<double>& g);
  /// The slip bound the current mu implies: g = max(mu_nu + lambda_Im,nu, 0) (paper (20)) on
  /// Coulomb's nodes; the others keep theirs.
  std::vector<double> impliedSlip(const qp::Vector& mu) const;
  /// Per interface (B.interfaces' order), the sum of the normal nodal forces
  /// rowScale max(mu_nu + lambda_Im,nu, 0) of `mu` (global, every rank the same). Collective.
  std::vector<double> interfaceNormalForces(const qp::Vector& mu) const;
  /// ||g_new - g_old|| / ||g_old|| over Coulomb's nodes (global; infinite from g_old = 0 to
  /// g_new != 0).
  double relativeChange(const std::vector<double>& gNew, const std::vector<double>& gOld) const;
  /// max over Coulomb's contact nodes of (||F^-1 lambda_t|| - lambda_nu)_+ / max lambda_nu for
  /// lambda = current + lambda_Im: how far the multipliers are from Coulomb's law (global).
  double coulombExcess(const qp::Vector& current) const;

 private:
  std::array<double, 2> semiAxes(size_t k, double g) const;
  void buildRightHandSide();
  void buildStoppingScale();
  void buildOmega(const FrictionSettings& friction);

  const feti::TotalFeti& feti_;
  const feti::ConstraintMatrix& B_;
  const Teuchos::Comm<int>& comm_;
  LocalContact lc_;
  Teuchos::RCP<feti::DualVector> c_;
  qp::SeparableSet omega_;
  std::vector<double> slip_;
  double stoppingScale_ = 0.0;
  bool coulombNodes_ = false;
};

}  // namespace tribos::contact
