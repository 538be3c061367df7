// The Tpetra side of qp::SymmetricOperator (DualTypes.hpp): column by column with the
// one-vector apply.
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <stdexcept>

#include "tribos/qp/DualTypes.hpp"

namespace tribos::qp {

void SymmetricOperator::requireOwnMap(const MultiVector& V, const char* which) const {
  TEUCHOS_TEST_FOR_EXCEPTION(map_.is_null(), std::invalid_argument,
                             "tribos::qp " << name_ << ": made without a map, it serves Tribos's own solvers only");
  const auto& map = V.getMap();
  const bool same = map.get() == map_.get() || map->isSameAs(*map_);
  TEUCHOS_TEST_FOR_EXCEPTION(!same, std::invalid_argument,
                             "tribos::qp " << name_ << ": " << which << " is not on the operator's map ("
                                           << map->getGlobalNumElements() << " entries, the operator's map has "
                                           << map_->getGlobalNumElements() << ")");
}

void SymmetricOperator::apply(const MultiVector& X, MultiVector& Y, Teuchos::ETransp, double alpha,
                              double beta) const {
  requireOwnMap(X, "X");
  requireOwnMap(Y, "Y");
  TEUCHOS_TEST_FOR_EXCEPTION(X.getNumVectors() != Y.getNumVectors(), std::invalid_argument,
                             "tribos::qp " << name_ << ": X has " << X.getNumVectors() << " columns, Y "
                                           << Y.getNumVectors());
  if (column_.is_null()) column_ = Teuchos::rcp(new Vector(map_));
  for (size_t j = 0; j < X.getNumVectors(); ++j) {
    apply(*X.getVector(j), *column_);
    auto y = Y.getVectorNonConst(j);
    if (beta == 0.0)
      y->scale(alpha, *column_);  // Y's old values ignored (no 0 * NaN)
    else
      y->update(alpha, *column_, beta);
  }
}

}  // namespace tribos::qp
