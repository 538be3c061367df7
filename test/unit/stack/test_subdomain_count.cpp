// Mesh/Subdomains = 0: the subdomain count chosen from the mesh (stack/SubdomainCount.hpp),
// and a scene read from a file gets it.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include "TestPaths.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainCount.hpp"

namespace tribos::stack {
namespace {

TEST(SubdomainCount, givenCountIsKept) {
  const auto c = chooseSubdomainCount(7, 100000, 100000, 2, 2000, 16);
  EXPECT_EQ(c.count, 7);
  EXPECT_TRUE(c.reason.empty());
}

TEST(SubdomainCount, oneSubdomainPerTargetNodesRounded) {
  EXPECT_EQ(chooseSubdomainCount(0, 19098, 19098, 2, 2000, 1).count, 10);  // 9.55
  EXPECT_EQ(chooseSubdomainCount(0, 6344, 6344, 2, 2000, 1).count, 3);    // 3.17
  EXPECT_EQ(chooseSubdomainCount(0, 6344, 6344, 2, 1000, 1).count, 6);
  const auto c = chooseSubdomainCount(0, 31586, 31586, 2, 2000, 2);
  EXPECT_EQ(c.count, 16);
  EXPECT_EQ(c.reason, "from the mesh: 31586 nodes / Mesh/Nodes Per Subdomain 2000");
}

TEST(SubdomainCount, atLeastOnePerBodyAndOnePerRank) {
  const auto bodies = chooseSubdomainCount(0, 1442, 1442, 4, 2000, 1);
  EXPECT_EQ(bodies.count, 4);
  EXPECT_NE(bodies.reason.find("raised to one per body"), std::string::npos) << bodies.reason;
  const auto ranks = chooseSubdomainCount(0, 1442, 1442, 4, 2000, 6);
  EXPECT_EQ(ranks.count, 6);
  EXPECT_NE(ranks.reason.find("raised to one per rank"), std::string::npos) << ranks.reason;
  EXPECT_EQ(chooseSubdomainCount(0, 0, 0, 1, 2000, 1).count, 1);
}

// The Hertz sphere's mesh (6 344 nodes) with Mesh/Subdomains = 0: three subdomains, from
// the mesh alone (the same on one rank and on two), and the report says why.
TEST(SubdomainCount, aSceneWithoutACountIsCutByItsMesh) {
  const std::string source = test::sourceDir() + "/input/hertz_sphere.xml";
  auto params = Teuchos::getParametersFromXmlFile(source);
  params->sublist("Mesh").set("Subdomains", 0);
  core::validateAndSetDefaults(*params, *sceneValidParameters(), source);
  const Scene scene = buildScene(*params, source, MPI_COMM_WORLD);
  EXPECT_EQ(scene.decomposition.numSubdomains(), 3);
  EXPECT_EQ(scene.subdomainChoice, "from the mesh: 6344 nodes / Mesh/Nodes Per Subdomain 2000");
}

// The same scene on its 10-node tetrahedra (7 094 nodes): counted by its corner nodes, as H/h
// counts elements, two subdomains (one per body), not the four its nodes would give.
TEST(SubdomainCount, aQuadraticMeshIsCountedByItsCornerNodes) {
  const std::string source = test::sourceDir() + "/input/hertz_sphere.xml";
  auto params = Teuchos::getParametersFromXmlFile(source);
  params->sublist("Mesh").set("Subdomains", 0);
  params->sublist("Mesh").set("File", std::string("meshes/hertz_sphere_tet10_h0.3.exo"));
  core::validateAndSetDefaults(*params, *sceneValidParameters(), source);
  const Scene scene = buildScene(*params, source, MPI_COMM_WORLD);
  const int corners = cornerNodeCount(scene.mesh);
  EXPECT_GT(corners, 0);
  EXPECT_LT(corners, scene.mesh.numNodes() / 4);
  EXPECT_EQ(scene.decomposition.numSubdomains(), 2);
  EXPECT_EQ(scene.subdomainChoice, "from the mesh: " + std::to_string(corners) +
                                       " corner nodes (of 7094) / Mesh/Nodes Per Subdomain 2000, raised to one per body");
}

}  // namespace
}  // namespace tribos::stack
