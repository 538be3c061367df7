#pragma once
// Internal to contact/: steps (4)-(6) of solveContact (ALGORITHMS.md 7): lambda, alpha and u
// from the dual solution; the KKT residuals of the discrete problem and the status of every
// contact node; the gate that accepts "converged" only where they hold.
#include "DualContactProblem.hpp"

namespace tribos::contact {

/// What the recovery leaves for the KKT report.
struct RecoveredLambda {
  Teuchos::RCP<feti::DualVector> lambda;  ///< mu + lambda_Im (this rank's owned rows)
  double lambdaNuMax = 0.0;  ///< max |lambda_nu| over all contact nodes
  double tau = 0.0;          ///< relative tolerance of the status tests
  double tinyForce = 0.0;    ///< tau times the force scale: multipliers below it count as zero
};

/// Step (4): lambda = mu + lambda_Im; alpha over the rows where the dual constraints are
/// inactive (all rows, with the result flagged, when those hold no body); u = K^dagger (f -
/// B^T lambda) + R alpha; result.lambda, displacement and energy. Collective.
RecoveredLambda recoverPrimal(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
                              const DualContactProblem& problem, const qp::Vector& mu, double kktTolerance,
                              ContactResult& result);

/// Step (5): result.kkt, result.nodes and result.statusCounts. Collective.
void reportKkt(const feti::TotalFeti& feti, const feti::ConstraintMatrix& B,
               const DualContactProblem& problem, const RecoveredLambda& recovered, ContactResult& result);

/// Step (6): "converged" only if every KKT residual is at most `kktTolerance` too (SMALSE-M's
/// own tests are on the dual QP); the message names the first that is not.
void gateOnKkt(double kktTolerance, ContactResult& result);

}  // namespace tribos::contact
