#include "tribos/stack/FetiSettings.hpp"

#include <Teuchos_ParameterList.hpp>

#include "tribos/feti/TotalFeti.hpp"

namespace tribos::stack {

namespace {
feti::CholmodMode cholmodMode(const std::string& name) {
  if (name == "Simplicial") return feti::CholmodMode::Simplicial;
  if (name == "Supernodal") return feti::CholmodMode::Supernodal;
  return feti::CholmodMode::Auto;  // the validator admits nothing else
}
}  // namespace

feti::TotalFetiSettings totalFetiSettings(const Teuchos::ParameterList& feti, bool exactProjector) {
  feti::TotalFetiSettings settings;
  settings.factorization = feti.get<std::string>("Factorization");
  settings.explicitF = feti.get<std::string>("Dual Operator") == "Explicit";
  const std::string preconditioner = feti.get<std::string>("Preconditioner");
  settings.dirichletPreconditioner = preconditioner == "Dirichlet";
  settings.lumpedPreconditioner = preconditioner == "Lumped";
  if (!exactProjector) settings.coarsePrecision = feti.get<std::string>("Coarse Factor Precision");
  settings.factorOptions.cholmodMode = cholmodMode(feti.get<std::string>("CHOLMOD Mode"));
  settings.factorOptions.subtreeSolveFromValues = feti.get<int>("Subtree Solve From");
  settings.distributedCoarseFromValues = feti.get<int>("Distributed Coarse From");
  settings.singleCoarseGate = feti.get<double>("Single Coarse Gate");
  return settings;
}

}  // namespace tribos::stack
