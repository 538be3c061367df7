#pragma once
/// \file DualTpetraOperators.hpp
/// T-FETI's dual operators behind Trilinos's contract, Tpetra::Operator on TotalFeti::dualMap():
/// F, P F P, the projector P, and the projected preconditioners P D P (D lumped or Dirichlet),
/// so that Belos, Anasazi or a user's own Tpetra code can apply them (perf/prototypes/
/// belos_projected_cg.cpp runs Belos's CG on them). All are symmetric: the transpose is the
/// operator itself. apply(X, Y, mode, alpha, beta) computes Y = alpha op(X) + beta Y column by
/// column (beta = 0 ignores Y's old values), after checking that X and Y live on the dual map
/// (the same map, or one with the same global ids on every rank): a vector of another map is
/// std::invalid_argument, never a silent product. Each column counts as TotalFeti counts it.
#include <Tpetra_MultiVector_decl.hpp>
#include <Tpetra_Operator.hpp>

#include <functional>

#include "tribos/feti/TotalFeti.hpp"

namespace tribos::feti {

/// Which dual operator (makeDualOperator).
enum class DualOperatorKind {
  F,          ///< F = B K^dagger B^T
  PFP,        ///< P F P (the operator of projected CG and SMALSE-M)
  Projector,  ///< P = I - G^T (G G^T)^{-1} G
  PDP,        ///< P D P with D the preconditioner TotalFeti was built with (lumped or Dirichlet)
};

using DualOperatorBase = Tpetra::Operator<Scalar, LO, GO>;

/// The operator `kind` of `feti`, which must outlive it. PDP needs a preconditioner
/// (TotalFetiSettings::lumpedPreconditioner or dirichletPreconditioner): std::invalid_argument
/// otherwise.
Teuchos::RCP<DualOperatorBase> makeDualOperator(const TotalFeti& feti, DualOperatorKind kind);

/// Any symmetric y = op(x) on the dual map of `feti` behind the same contract (map checks,
/// alpha and beta, column by column); `name` appears in its errors.
Teuchos::RCP<DualOperatorBase> wrapDualOperator(const TotalFeti& feti,
                                                std::function<void(const DualVector&, DualVector&)> op,
                                                const char* name);

}  // namespace tribos::feti
