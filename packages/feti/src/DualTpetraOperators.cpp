// T-FETI's dual operators as Tpetra::Operators (DualTpetraOperators.hpp).
#include "tribos/feti/DualTpetraOperators.hpp"

#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <functional>
#include <stdexcept>
#include <string>

namespace tribos::feti {

namespace {
using MultiVector = Tpetra::MultiVector<Scalar, LO, GO>;
using Apply = std::function<void(const DualVector&, DualVector&)>;

/// y = op(x) column by column on the dual map.
class DualTpetraOperator : public DualOperatorBase {
 public:
  DualTpetraOperator(const TotalFeti& feti, Apply op, const char* name)
      : feti_(feti), op_(std::move(op)), name_(name), work_(feti.createDualVector()) {}
  Teuchos::RCP<const Tpetra::Map<LO, GO>> getDomainMap() const override { return feti_.dualMap(); }
  Teuchos::RCP<const Tpetra::Map<LO, GO>> getRangeMap() const override { return feti_.dualMap(); }
  bool hasTransposeApply() const override { return true; }  // symmetric
  void apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, Scalar alpha, Scalar beta) const override {
    requireDualMap(X, "X");
    requireDualMap(Y, "Y");
    TEUCHOS_TEST_FOR_EXCEPTION(X.getNumVectors() != Y.getNumVectors(), std::invalid_argument,
                               "tribos::feti " << name_ << ": X has " << X.getNumVectors() << " columns, Y "
                                               << Y.getNumVectors());
    for (size_t j = 0; j < X.getNumVectors(); ++j) {
      op_(*X.getVector(j), *work_);
      auto y = Y.getVectorNonConst(j);
      if (beta == 0.0)
        y->scale(alpha, *work_);  // Y's old values ignored (no 0 * NaN)
      else
        y->update(alpha, *work_, beta);
    }
  }

 private:
  /// Collective (Map::isSameAs), as every apply is.
  void requireDualMap(const MultiVector& V, const char* which) const {
    const auto& map = V.getMap();
    const bool same = map.get() == feti_.dualMap().get() || map->isSameAs(*feti_.dualMap());
    TEUCHOS_TEST_FOR_EXCEPTION(!same, std::invalid_argument,
                               "tribos::feti " << name_ << ": " << which << " is not on the dual map ("
                                               << map->getGlobalNumElements() << " entries, the dual map has "
                                               << feti_.dualMap()->getGlobalNumElements() << ")");
  }
  const TotalFeti& feti_;
  Apply op_;
  const char* name_;
  Teuchos::RCP<DualVector> work_;
};
}  // namespace

Teuchos::RCP<DualOperatorBase> wrapDualOperator(const TotalFeti& feti, Apply op, const char* name) {
  return Teuchos::rcp(new DualTpetraOperator(feti, std::move(op), name));
}

Teuchos::RCP<DualOperatorBase> makeDualOperator(const TotalFeti& feti, DualOperatorKind kind) {
  const TotalFeti* f = &feti;
  switch (kind) {
    case DualOperatorKind::F:
      return wrapDualOperator(feti, [f](const DualVector& x, DualVector& y) { f->applyF(x, y); },
                                                 "F");
    case DualOperatorKind::PFP: {
      auto Px = feti.createDualVector();
      return wrapDualOperator(
          feti,
          [f, Px](const DualVector& x, DualVector& y) {
            f->project(x, *Px);
            f->applyPF(*Px, y);  // P F P x = P F (P x), with F's kernel projections skipped on Ker G
          },
          "P F P");
    }
    case DualOperatorKind::Projector:
      return wrapDualOperator(feti, [f](const DualVector& x, DualVector& y) { f->project(x, y); },
                                                 "P");
    case DualOperatorKind::PDP: {
      const DualPreconditioner D = feti.preconditioner();
      TEUCHOS_TEST_FOR_EXCEPTION(D == DualPreconditioner::None, std::invalid_argument,
                                 "tribos::feti::makeDualOperator: P D P needs a T-FETI built with a lumped or "
                                 "Dirichlet preconditioner");
      auto Px = feti.createDualVector();
      return wrapDualOperator(
          feti,
          [f, Px, D](const DualVector& x, DualVector& y) {
            f->project(x, *Px);
            if (D == DualPreconditioner::Dirichlet)
              f->applyDirichlet(*Px, y);
            else
              f->applyLumped(*Px, y);
            f->project(y, y);
          },
          D == DualPreconditioner::Dirichlet ? "P S P (Dirichlet)" : "P K P (lumped)");
    }
  }
  throw std::invalid_argument("tribos::feti::makeDualOperator: unknown kind");
}

}  // namespace tribos::feti
