// T-FETI's dual operators as one family (DualOperators.hpp).
#include "tribos/feti/DualOperators.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace tribos::feti {

FOperator::FOperator(const TotalFeti& feti) : qp::SymmetricOperator(feti.dualMap(), "F"), feti_(feti) {}

void FOperator::apply(const qp::Vector& x, qp::Vector& y) const { feti_.applyF(x, y); }

ProjectedDualOperator::ProjectedDualOperator(const TotalFeti& feti)
    : qp::ProjectedOperator(feti.dualMap(), "P F P"), feti_(feti), tmp_(feti.createDualVector()) {}

bool ProjectedDualOperator::applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s,
                                                qp::EqualityCoordinates* ofX) const {
  applyWith(x, y, ofX ? &coordinates_ : nullptr);
  y.update(s, x, -s, *tmp_, 1.0);  // + s (x - P x)
  if (!ofX) return false;
  ofX->u.swap(coordinates_.gx);
  ofX->w.swap(coordinates_.a);
  return true;
}

void ProjectedDualOperator::applyWith(const qp::Vector& x, qp::Vector& y, CoarseCoordinates* ofX) const {
  feti_.project(x, *tmp_, ofX);
  feti_.applyPF(*tmp_, y);  // P F P x = P F (P x), F's kernel projections skipped on Ker G
}

namespace {
/// D's name, after checking that the TotalFeti holds its blocks.
const char* preconditionerName(const TotalFeti& feti, DualPreconditioner D) {
  const DualPreconditioner built = feti.preconditioner();
  const bool available = D == DualPreconditioner::Lumped ? built != DualPreconditioner::None
                                                         : D == DualPreconditioner::Dirichlet && built == D;
  TEUCHOS_TEST_FOR_EXCEPTION(!available, std::invalid_argument,
                             "tribos::feti: P D P needs a T-FETI built with a "
                                 << (D == DualPreconditioner::Dirichlet ? "Dirichlet" : "lumped or Dirichlet")
                                 << " preconditioner");
  return D == DualPreconditioner::Dirichlet ? "P S P (Dirichlet)" : "P K P (lumped)";
}
}  // namespace

ProjectedDualPreconditioner::ProjectedDualPreconditioner(const TotalFeti& feti, DualPreconditioner D)
    : qp::ProjectedOperator(feti.dualMap(), preconditionerName(feti, D)),
      feti_(feti),
      dirichlet_(D == DualPreconditioner::Dirichlet),
      tmp_(feti.createDualVector()) {}

void ProjectedDualPreconditioner::apply(const qp::Vector& x, qp::Vector& y) const {
  feti_.project(x, *tmp_);
  if (dirichlet_)
    feti_.applyDirichlet(*tmp_, y);
  else
    feti_.applyLumped(*tmp_, y);
  feti_.project(y, y);
}

bool ProjectedDualPreconditioner::applyPlusComplement(const qp::Vector& x, qp::Vector& y, double s,
                                                      qp::EqualityCoordinates*) const {
  apply(x, y);
  y.update(s, x, -s, *tmp_, 1.0);  // + s (x - P x)
  return false;
}

void CoarseSpaceProjector::applyQ(const qp::Vector& x, qp::Vector& y) const {
  feti_.project(x, y);
  y.update(1.0, x, -1.0);
}

double CoarseSpaceProjector::normQ(const qp::Vector& x, qp::Vector&) const {
  feti_.coarseCoordinates(x, gx_, a_);
  double q = 0.0;
  for (size_t i = 0; i < a_.size(); ++i) q += gx_[i] * a_[i];
  return std::sqrt(std::max(q, 0.0));
}

bool CoarseSpaceProjector::coordinates(const qp::Vector& x, std::vector<double>& u, std::vector<double>& w) const {
  feti_.coarseCoordinates(x, u, w);
  return true;
}

namespace {
/// y = op(x) given as a function.
class FunctionOperator : public qp::SymmetricOperator {
 public:
  FunctionOperator(const TotalFeti& feti, std::function<void(const DualVector&, DualVector&)> op, const char* name)
      : qp::SymmetricOperator(feti.dualMap(), name), op_(std::move(op)) {}
  void apply(const qp::Vector& x, qp::Vector& y) const override { op_(x, y); }

 private:
  std::function<void(const DualVector&, DualVector&)> op_;
};
}  // namespace

Teuchos::RCP<qp::SymmetricOperator> wrapDualOperator(const TotalFeti& feti,
                                                     std::function<void(const DualVector&, DualVector&)> op,
                                                     const char* name) {
  return Teuchos::rcp(new FunctionOperator(feti, std::move(op), name));
}

Teuchos::RCP<qp::SymmetricOperator> makeDualOperator(const TotalFeti& feti, DualOperatorKind kind) {
  switch (kind) {
    case DualOperatorKind::F: return Teuchos::rcp(new FOperator(feti));
    case DualOperatorKind::PFP: return Teuchos::rcp(new ProjectedDualOperator(feti));
    case DualOperatorKind::Projector: {
      const TotalFeti* f = &feti;
      return wrapDualOperator(feti, [f](const DualVector& x, DualVector& y) { f->project(x, y); }, "P");
    }
    case DualOperatorKind::PDP: return Teuchos::rcp(new ProjectedDualPreconditioner(feti));
  }
  throw std::invalid_argument("tribos::feti::makeDualOperator: unknown kind");
}

}  // namespace tribos::feti
