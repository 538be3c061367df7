#pragma once
// Shared set-up for the contact integration tests: a two-brick scene from parameter
// overrides, solved end to end on MPI_COMM_WORLD.
#include <mpi.h>

#include <Teuchos_ParameterList.hpp>

#include <string>
#include <vector>

#include "tribos/core/Parameters.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/stack/ContactSolve.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainSetup.hpp"
#include "WorldRank.hpp"

namespace tribos::test {

struct SolvedContactScene {
  Teuchos::ParameterList params{"Tribos"};
  stack::Scene scene;
  feti::ConstraintMatrix B;
  stack::ContactSolveResult result;
};

/// Builds and solves the scene of the validated list `s.params`; `source` names the scene file
/// (relative mesh paths start from its directory) or "test".
inline void solveValidatedScene(SolvedContactScene& s, const std::string& source, MPI_Comm comm) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  s.scene = stack::buildScene(s.params, source);
  std::vector<fem::SubdomainSystem> systems;
  stack::assembleOwnedSubdomains(s.scene, comm, systems);
  s.B = feti::buildConstraintMatrix(s.scene.mesh, s.scene.decomposition, stack::constraintSpec(s.scene), size);
  s.result = stack::solveContactScene(s.scene, std::move(systems), s.B, s.params, comm);
}

inline SolvedContactScene solveContactScene(const std::vector<std::string>& overrides, MPI_Comm comm = MPI_COMM_WORLD) {
  SolvedContactScene s;
  const auto valid = stack::sceneValidParameters();
  // The paper's contact pair unless the overrides say otherwise (the scene default is no contact).
  for (const char* pair : {"Contact/Slave Side Set=contact_aluminium", "Contact/Master Side Set=contact_steel"})
    core::applyOverride(s.params, *valid, pair);
  for (const auto& o : overrides) core::applyOverride(s.params, *valid, o);
  core::validateAndSetDefaults(s.params, *valid, "test");
  solveValidatedScene(s, "test", comm);
  return s;
}

/// The scene `sceneList` read from the file `source`, with `overrides` ("Path=value") on top.
inline SolvedContactScene solveContactScene(const Teuchos::ParameterList& sceneList, const std::string& source,
                                            const std::vector<std::string>& overrides, MPI_Comm comm = MPI_COMM_WORLD) {
  SolvedContactScene s;
  s.params = sceneList;
  s.params.setName("Tribos");
  const auto valid = stack::sceneValidParameters();
  core::validateAndSetDefaults(s.params, *valid, source);  // as the driver: the file, then each override
  for (const auto& o : overrides) core::applyOverride(s.params, *valid, o);
  core::validateAndSetDefaults(s.params, *valid, source);
  solveValidatedScene(s, source, comm);
  return s;
}

}  // namespace tribos::test
