#pragma once
// Scenes on meshes built by the tests themselves (test/common/BoxMesh): the mesh goes to a
// temporary Exodus file that the scene reads through Mesh/Generator = "Exodus" — the path a
// user's preprocessor mesh takes — and the scene is built, checked for free rigid motions
// (as the driver does) and solved on MPI_COMM_WORLD: by SMALSE-M when it has a contact pair,
// else by linear T-FETI.
#include <mpi.h>
#include <unistd.h>

#include <Teuchos_ParameterList.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "tribos/core/Parameters.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/Solvability.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/stack/ContactSolve.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SceneSolve.hpp"
#include "tribos/stack/SubdomainSetup.hpp"
#include "WorldRank.hpp"

namespace tribos::test {

/// The validated parameter list of a scene on `mesh`: Mesh/Generator = Exodus with
/// Mesh/File a temporary file holding `mesh` (one per process, so ranks never race on it),
/// then `overrides` ("Sublist/Name=value"). The file is removed when the scene is built.
struct ExodusScene {
  Teuchos::ParameterList params{"Tribos"};
  std::filesystem::path file;
  ExodusScene(const mesh::Mesh& mesh, const std::vector<std::string>& overrides) {
    static int counter = 0;
    file = std::filesystem::temp_directory_path() /
           ("tribos_box_" + std::to_string(::getpid()) + "_" + std::to_string(counter++) + ".exo");
    mesh::writeExodus(file.string(), mesh);
    const auto valid = stack::sceneValidParameters();
    core::applyOverride(params, *valid, "Mesh/Generator=Exodus");
    core::applyOverride(params, *valid, "Mesh/File=" + file.string());
    for (const auto& o : overrides) core::applyOverride(params, *valid, o);
    core::validateAndSetDefaults(params, *valid, "test");
  }
  ~ExodusScene() { std::filesystem::remove(file); }
  stack::Scene build() const { return stack::buildScene(params, "test"); }
};

struct SolvedBoxScene {
  stack::Scene scene;
  feti::ConstraintMatrix B;
  stack::ContactSolveResult contact;  ///< contact scenes
  stack::LinearFetiResult linear;     ///< scenes without a contact pair, or bonded ones only
  bool contactProblem = false;        ///< stack::isContactProblem: which of the two ran
  /// Displacement of every global node (rank 0), from whichever solver ran.
  const std::vector<std::array<double, 3>>& displacement() const {
    return contactProblem ? contact.displacement.value : linear.displacement;
  }
};

/// Builds and solves the scene; linear solves use Solver/Tolerance as their CG tolerance
/// (as the driver does).
inline SolvedBoxScene solveBoxScene(const mesh::Mesh& mesh, const std::vector<std::string>& overrides) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  ExodusScene input(mesh, overrides);
  SolvedBoxScene s;
  s.scene = input.build();
  std::vector<fem::SubdomainSystem> systems;
  stack::assembleOwnedSubdomains(s.scene, MPI_COMM_WORLD, systems);
  s.B = feti::buildConstraintMatrix(s.scene.mesh, s.scene.decomposition, stack::constraintSpec(s.scene), size);
  feti::requireRestrainedBodies(s.scene.mesh, s.scene.decomposition, s.B);
  s.contactProblem = stack::isContactProblem(s.scene);
  if (s.contactProblem)
    s.contact = stack::solveContactScene(s.scene, std::move(systems), s.B, input.params, MPI_COMM_WORLD);
  else
    s.linear = stack::solveLinearFeti(s.scene, std::move(systems), s.B, input.params.sublist("FETI"),
                                      input.params.sublist("Solver").get<double>("Tolerance"), MPI_COMM_WORLD);
  return s;
}

/// "Boundary/<name>/..." overrides for u_c = value on the node set.
inline std::vector<std::string> displacementCondition(const std::string& name, const std::string& nodeSet,
                                                      const std::string& components,
                                                      const std::string& value = "{0, 0, 0}") {
  return {"Boundary/" + name + "/Node Set=" + nodeSet, "Boundary/" + name + "/Components=" + components,
          "Boundary/" + name + "/Displacement=" + value};
}

inline std::vector<std::string> with(std::vector<std::string> base, const std::vector<std::string>& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}

}  // namespace tribos::test
