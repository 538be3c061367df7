#include "tribos/stack/FetiSettings.hpp"

#include <Teuchos_ParameterList.hpp>

#include "tribos/feti/TotalFeti.hpp"

namespace tribos::stack {

feti::TotalFetiSettings totalFetiSettings(const Teuchos::ParameterList& feti, bool exactProjector) {
  feti::TotalFetiSettings settings;
  settings.factorization = core::valueOf(feti::kFactorizationNames, feti.get<std::string>("Factorization"));
  settings.explicitF = core::valueOf(feti::kDualOperatorNames, feti.get<std::string>("Dual Operator")) ==
                       feti::DualOperator::Explicit;
  const auto preconditioner = dualPreconditioner(feti);
  settings.dirichletPreconditioner = preconditioner == feti::DualPreconditioner::Dirichlet;
  settings.lumpedPreconditioner = preconditioner == feti::DualPreconditioner::Lumped;
  if (!exactProjector)
    settings.coarsePrecision = core::valueOf(feti::kCoarsePrecisionNames, feti.get<std::string>("Coarse Factor Precision"));
  settings.factorOptions.cholmodMode = core::valueOf(feti::kCholmodModeNames, feti.get<std::string>("CHOLMOD Mode"));
  settings.factorOptions.subtreeSolveFromValues = feti.get<int>("Subtree Solve From");
  settings.distributedCoarseFromValues = feti.get<int>("Distributed Coarse From");
  settings.singleCoarseGate = feti.get<double>("Single Coarse Gate");
  return settings;
}

feti::DualPreconditioner dualPreconditioner(const Teuchos::ParameterList& feti) {
  return core::valueOf(feti::kDualPreconditionerNames, feti.get<std::string>("Preconditioner"));
}

}  // namespace tribos::stack
