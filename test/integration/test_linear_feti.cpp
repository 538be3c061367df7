// Linear T-FETI = direct solve: for the bonded two bricks and for bodies without contact,
// the T-FETI displacement of every global node agrees with an Amesos2 solve of the
// globally assembled, undecomposed problem to 1e-8 relative, for several decompositions
// of the same mesh, every preconditioner, implicit and explicit F, and the number of MPI
// ranks this executable runs on (ctest runs it on 1, 2 and 4).
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_ParameterList.hpp>

#include <cmath>

#include "DirectSolve.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

namespace {
using namespace tribos;

Teuchos::ParameterList paramsFor(const std::vector<std::string>& overrides) {
  Teuchos::ParameterList params("Tribos");
  const auto valid = stack::sceneValidParameters();
  // The paper's contact pair (tied when Bonded) unless the overrides remove it.
  for (const char* pair : {"Contact/Slave Side Set=contact_aluminium", "Contact/Master Side Set=contact_steel"})
    core::applyOverride(params, *valid, pair);
  for (const auto& o : overrides) core::applyOverride(params, *valid, o);
  core::validateAndSetDefaults(params, *valid, "test");
  return params;
}

// Solves by T-FETI and by the direct reference; returns ||u_feti - u_direct|| / ||u_direct|| on rank 0.
double relativeErrorAgainstDirect(const std::vector<std::string>& overrides, stack::LinearFetiResult* out = nullptr) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  auto params = paramsFor(overrides);
  const auto scene = stack::buildScene(params, "test");
  std::vector<fem::SubdomainSystem> systems;
  stack::assembleOwnedSubdomains(scene, MPI_COMM_WORLD, systems);
  const auto B = feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), size);
  const auto result = stack::solveLinearFeti(scene, std::move(systems), B, params.sublist("FETI"), 1e-11, MPI_COMM_WORLD);
  if (out) *out = result;
  EXPECT_TRUE(result.converged);
  if (rank != 0) return 0.0;

  std::vector<LO> fixed;
  for (const auto& name : scene.dirichletNodeSets)
    for (LO n : scene.mesh.nodeSet(name).nodes) fixed.push_back(n);
  std::vector<std::pair<LO, LO>> tied;
  if (!scene.contacts.empty())
    for (const auto& c : B.contact) tied.push_back({c.slaveNode, c.masterNode});
  const auto reference = test::directSolve(scene.mesh, scene.materials, scene.loads, fixed, tied);
  double diff = 0.0, norm = 0.0;
  for (LO n = 0; n < scene.mesh.numNodes(); ++n)
    for (int c = 0; c < 3; ++c) {
      diff += std::pow(result.displacement[n][c] - reference[n][c], 2);
      norm += std::pow(reference[n][c], 2);
    }
  EXPECT_GT(norm, 0.0);
  return std::sqrt(diff / norm);
}

const std::vector<std::string> kBonded = {"Contact/Friction Model=Bonded"};

std::vector<std::string> with(std::vector<std::string> base, const std::vector<std::string>& more) {
  base.insert(base.end(), more.begin(), more.end());
  return base;
}
}  // namespace

TEST(linearFeti, bondedBricksMatchDirectSolveForSeveralDecompositions) {
  // The same global mesh (h = 2.5) split three ways.
  for (const auto& split : std::vector<std::vector<std::string>>{
           {"Mesh/Subdomains Per Brick=2x1x1", "Mesh/H Over h=4"},
           {"Mesh/Subdomains Per Brick=4x2x2", "Mesh/H Over h=2"},
           {"Mesh/Subdomains Per Brick=2x1x1", "Mesh/H Over h=4", "Mesh/Decomposition=METIS", "Mesh/Subdomains=7"}}) {
    SCOPED_TRACE(split[0] + ", " + split[1]);
    stack::LinearFetiResult result;
    const double error = relativeErrorAgainstDirect(with(kBonded, split), &result);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank == 0) {
      EXPECT_LT(error, 1e-8);
      EXPECT_LT(result.equilibriumResidual, 1e-10);
      EXPECT_LT(result.constraintResidual, 1e-8);
      EXPECT_LT(result.maxCopyJump, 1e-8);
    }
  }
}

TEST(linearFeti, everyPreconditionerAndExplicitFAgreeWithDirectSolve) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  for (const auto& variant : std::vector<std::vector<std::string>>{{"FETI/Preconditioner=Lumped"},
                                                                  {"FETI/Preconditioner=Dirichlet"},
                                                                  {"FETI/Dual Operator=Explicit"}}) {
    SCOPED_TRACE(variant[0]);
    const double error = relativeErrorAgainstDirect(
        with(with(kBonded, {"Mesh/Subdomains Per Brick=4x2x2", "Mesh/H Over h=2"}), variant));
    if (rank == 0) EXPECT_LT(error, 1e-8);
  }
}

TEST(linearFeti, bodiesWithoutContactMatchDirectSolve) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const double error = relativeErrorAgainstDirect({"Contact/Friction Model=None", "Contact/Slave Side Set=",
                                                   "Contact/Master Side Set=", "Mesh/Subdomains Per Brick=4x2x2",
                                                   "Mesh/H Over h=3"});
  if (rank == 0) EXPECT_LT(error, 1e-8);
}
