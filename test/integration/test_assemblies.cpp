// Assemblies (issue 30): three bodies stacked on two contact interfaces, Contact/<name>
// sublists with a law each, the middle block the master of one interface and the slave of the
// other. The bodies share one 2 x 2 footprint and are meshed apart (3, 4 and 5 cells across:
// no interface matches), in a quarter model (symmetry planes x = 0 and y = 0 on every body),
// the foundation on a roller at its bottom, a pressure p on the punch's top.
//
// The exact solution is piecewise uniaxial: sigma_zz = -p in every body, so body i strains by
// eps_xx = eps_yy = nu_i p / E_i and eps_zz = -p / E_i. Where neighbours differ in nu / E their
// lateral strains differ and they slide on each other: only a frictionless interface allows it.
// Where they are of one material nothing slides, so Coulomb, Tresca and Bonded interfaces give
// the same field. Linear fields are reproduced by linear tetrahedra, so on matching interfaces
// the discrete solution is the exact one up to the solver's tolerance, on any number of ranks.
// On non-matching ones the mortar rows pass the patch test only up to their quadrature and the
// node-to-surface rows at the footprint's edges (test_nonmatching_patch.cpp: 1e-3 for two
// bodies), so the field is bounded there, as there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "BoxMesh.hpp"
#include "BoxScene.hpp"
#include "tribos/core/Errors.hpp"

namespace {
using namespace tribos;
using test::displacementCondition;
using test::with;
using test::worldRank;

constexpr double kPressure = 10.0;
struct Material {
  double E, nu;
};
constexpr Material kSteel{210000.0, 0.25}, kAluminium{70000.0, 0.33};

/// Foundation z in [-2, 0], block [0, 2], punch [2, 3]; footprint [0, 2]^2.
mesh::Mesh threeBodies(bool matching = false, double punchLift = 0.0) {
  const int foundationCells = matching ? 4 : 3, punchCells = matching ? 4 : 5;
  const auto foundation =
      test::boxMesh({0.0, 0.0, -2.0}, {2.0, 2.0, 2.0}, {foundationCells, foundationCells, 2}, "foundation");
  const auto block = test::boxMesh({0.0, 0.0, 0.0}, {2.0, 2.0, 2.0}, {4, 4, 2}, "block");
  const auto punch =
      test::boxMesh({0.0, 0.0, 2.0 + punchLift}, {2.0, 2.0, 1.0}, {punchCells, punchCells, 1}, "punch");
  return test::mergeMeshes(test::mergeMeshes(foundation, block), punch);
}

struct Stack {
  std::string topLaw, bottomLaw;  ///< Friction Model of punch/block and block/foundation
  Material punch, block, foundation;
};

std::vector<std::string> sceneOf(const Stack& s, bool swapOrder = false) {
  std::vector<std::string> o = {"Mesh/Subdomains=6", "Solver/Tolerance=1e-10", "Solver/Verbose=false",
                                "Loads/press/Side Set=punch_z1", "Loads/press/Pressure=" + std::to_string(kPressure),
                                "Contact/F1=0.3", "Contact/F2=0.3", "Contact/Slip Bound=1"};
  const std::pair<const char*, Material> bodies[] = {{"punch", s.punch}, {"block", s.block}, {"foundation", s.foundation}};
  for (const auto& [body, m] : bodies) {
    const std::string b = body;
    o.push_back("Materials/" + b + "/Young Modulus=" + std::to_string(m.E));
    o.push_back("Materials/" + b + "/Poisson Ratio=" + std::to_string(m.nu));
    o = with(o, displacementCondition(b + "_x", b + "_x0", "x"));
    o = with(o, displacementCondition(b + "_y", b + "_y0", "y"));
  }
  o = with(o, displacementCondition("roller", "foundation_z0", "z"));
  const std::vector<std::string> top = {"Contact/punch_on_block/Slave Side Set=punch_z0",
                                        "Contact/punch_on_block/Master Side Set=block_z1",
                                        "Contact/punch_on_block/Friction Model=" + s.topLaw};
  const std::vector<std::string> bottom = {"Contact/block_on_foundation/Slave Side Set=block_z0",
                                           "Contact/block_on_foundation/Master Side Set=foundation_z1",
                                           "Contact/block_on_foundation/Friction Model=" + s.bottomLaw};
  return swapOrder ? with(with(o, bottom), top) : with(with(o, top), bottom);
}

/// The uniaxial field at x (the body's material and the bodies below it).
std::array<double, 3> exact(const Stack& s, const std::array<double, 3>& x, const std::string& body) {
  const double p = kPressure;
  const Material& m = body == "punch" ? s.punch : body == "block" ? s.block : s.foundation;
  double uz = -p / s.foundation.E * (std::min(x[2], 0.0) + 2.0);
  if (body != "foundation") uz += -p / s.block.E * (std::min(x[2], 2.0) - 0.0);
  if (body == "punch") uz += -p / s.punch.E * (x[2] - 2.0);
  return {m.nu * p / m.E * x[0], m.nu * p / m.E * x[1], uz};
}

/// max |u - exact| / max |exact| over every node (rank 0).
double fieldError(const test::SolvedBoxScene& r, const Stack& s) {
  const auto& mesh = r.scene.mesh;
  const auto& u = r.displacement();
  double error = 0.0, size = 0.0;
  for (int b = 0; b < mesh.numBlocks(); ++b) {
    const auto& block = mesh.blocks[b];
    for (LO e = block.first; e < block.first + block.count; ++e)
      for (LO n : mesh.elementNodes(e)) {
        const auto ref = exact(s, mesh.coords[n], block.name);
        for (int c = 0; c < 3; ++c) {
          error = std::max(error, std::abs(u[n][c] - ref[c]));
          size = std::max(size, std::abs(ref[c]));
        }
      }
  }
  return error / size;
}

class ThreeBodies : public ::testing::TestWithParam<Stack> {};

TEST_P(ThreeBodies, twoInterfacesGiveTheUniaxialFieldAndCarryTheLoadEach) {
  const Stack& s = GetParam();
  for (const bool matching : {true, false}) {
    SCOPED_TRACE(matching ? "matching interfaces" : "non-matching interfaces");
    const auto r = test::solveBoxScene(threeBodies(matching), sceneOf(s));
    // Bonded interfaces alone: a linear solve, with the same per-interface results.
    ASSERT_EQ(r.contactProblem, s.topLaw != "Bonded" || s.bottomLaw != "Bonded");
    EXPECT_TRUE(r.contactProblem ? r.contact.contact.converged : r.linear.converged) << r.contact.contact.message;
    ASSERT_EQ(r.B.interfaces.size(), 2u);
    for (const auto& i : r.B.interfaces) {
      EXPECT_EQ(i.unpairedSlaveNodes, 0) << i.label;
      EXPECT_EQ(i.overlappingPairs, 0) << i.label << " largest " << i.largestOverlap;
    }
    if (worldRank() != 0) continue;
    const double error = fieldError(r, s);
    std::printf("%s over %s, %s: max |u - exact| / max |exact| = %.3e\n", s.topLaw.c_str(), s.bottomLaw.c_str(),
                matching ? "matching" : "non-matching", error);
    EXPECT_LT(error, matching ? 1e-8 : 3e-4);
    // Each interface carries the whole load p x area (quarter footprint 2 x 2).
    const auto& interfaces = r.contactProblem ? r.contact.interfaces : r.linear.interfaces;
    ASSERT_EQ(interfaces.size(), 2u);
    EXPECT_EQ(interfaces[0].name, "punch_on_block");
    EXPECT_EQ(interfaces[1].name, "block_on_foundation");
    for (const auto& i : interfaces) {
      EXPECT_NEAR(i.normalForce, 4.0 * kPressure, 1e-8 * 4.0 * kPressure) << i.name;
      EXPECT_NEAR(i.force[2], -4.0 * kPressure, 1e-8 * 4.0 * kPressure) << i.name;  // on the master, downwards
      EXPECT_EQ(i.counts[0], 0) << i.name << ": every slave node presses";
    }
    // Frictionless contact slides ("slip"); where one material meets itself, friction and ties hold.
    EXPECT_EQ(interfaces[0].counts[s.topLaw != "None" ? 2 : 1], 0) << s.topLaw;
    EXPECT_EQ(interfaces[1].counts[s.bottomLaw != "None" ? 2 : 1], 0) << s.bottomLaw;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Laws, ThreeBodies,
    ::testing::Values(Stack{"None", "None", kSteel, kAluminium, kSteel},            // every interface slides
                      Stack{"None", "Coulomb", kSteel, kAluminium, kAluminium},     // frictionless over Coulomb
                      Stack{"None", "Bonded", kSteel, kAluminium, kAluminium},      // tied under frictionless
                      Stack{"Coulomb", "Tresca", kAluminium, kAluminium, kAluminium},
                      Stack{"Bonded", "Bonded", kAluminium, kAluminium, kAluminium}),  // linear T-FETI
    [](const ::testing::TestParamInfo<Stack>& info) { return info.param.topLaw + "_over_" + info.param.bottomLaw; });

TEST(ThreeBodiesOrder, theOrderOfTheInterfaceSublistsChangesNoBit) {
  // Rows are numbered by slave node whatever interface they belong to.
  const Stack s{"None", "Coulomb", kSteel, kAluminium, kAluminium};
  const auto a = test::solveBoxScene(threeBodies(), sceneOf(s));
  const auto b = test::solveBoxScene(threeBodies(), sceneOf(s, /*swapOrder=*/true));
  EXPECT_EQ(a.contact.contact.counters.operatorApplications, b.contact.contact.counters.operatorApplications);
  if (worldRank() != 0) return;
  EXPECT_EQ(a.displacement(), b.displacement());
  EXPECT_EQ(a.contact.interfaces[0].name, b.contact.interfaces[1].name);
  EXPECT_EQ(a.contact.interfaces[0].normalForce, b.contact.interfaces[1].normalForce);
}

/// The message of the input error that building the scene and its B throws ("" if none).
std::string inputError(const std::vector<std::string>& overrides) {
  try {
    const test::ExodusScene input(threeBodies(), overrides);
    const auto scene = input.build();
    feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), 1);
  } catch (const core::InputError& e) {
    return e.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// Materials for the three bodies, the foundation clamped: a scene to add interfaces to.
std::vector<std::string> inputBase() {
  std::vector<std::string> base = {"Mesh/Subdomains=3", "Boundary/Dirichlet Node Sets={foundation_z0}"};
  for (const char* body : {"punch", "block", "foundation"}) {
    base.push_back(std::string("Materials/") + body + "/Young Modulus=70000");
    base.push_back(std::string("Materials/") + body + "/Poisson Ratio=0.3");
  }
  return base;
}

TEST(ThreeBodiesInput, aSlaveNodeOnTwoInterfacesKeepsTheRowsOfOne) {
  // The rule for corners: a block on a floor and against a wall, its edge x = 0, z = 0 on
  // both slave surfaces. Each of its nodes is paired with both masters at gap 0; the smaller
  // gap wins, the earlier interface on a tie: the floor keeps the 3 edge nodes, the wall
  // counts them as shared, and no node has rows on both.
  const auto block = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "block");
  const auto floor = test::boxMesh({0.0, 0.0, -1.0}, {2.0, 1.0, 1.0}, {2, 1, 1}, "floor");
  const auto wall = test::boxMesh({-1.0, 0.0, 0.0}, {1.0, 1.0, 2.0}, {1, 1, 2}, "wall");
  std::vector<std::string> o = {"Mesh/Subdomains=3", "Contact/floor/Slave Side Set=block_z0",
                                "Contact/floor/Master Side Set=floor_z1", "Contact/wall/Slave Side Set=block_x0",
                                "Contact/wall/Master Side Set=wall_x1"};
  for (const char* body : {"block", "floor", "wall"}) {
    o.push_back(std::string("Materials/") + body + "/Young Modulus=70000");
    o.push_back(std::string("Materials/") + body + "/Poisson Ratio=0.3");
  }
  const test::ExodusScene input(test::mergeMeshes(test::mergeMeshes(block, floor), wall), o);
  const auto scene = input.build();
  const auto B = feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), 1);
  ASSERT_EQ(B.interfaces.size(), 2u);
  EXPECT_EQ(B.interfaces[0].pairedSlaveNodes, 9);
  EXPECT_EQ(B.interfaces[0].sharedSlaveNodes, 0);
  EXPECT_EQ(B.interfaces[1].pairedSlaveNodes, 6);
  EXPECT_EQ(B.interfaces[1].sharedSlaveNodes, 3);
  std::vector<int> rows(scene.mesh.numNodes(), 0);
  for (const auto& node : B.contact) ++rows[node.slaveNode];
  EXPECT_EQ(*std::max_element(rows.begin(), rows.end()), 1);
}

TEST(ThreeBodiesBonded, aBondedInterfaceTiesTheSurfacesWhereTheyAre) {
  // The punch lifted 0.1 above the block and bonded to it: tied in place, the gap is kept, and
  // (matching meshes, node-to-node rows, the punch only translated) the displacements are
  // those of the touching scene. Before, the bonded rows closed the gap: the punch moved 0.1.
  const auto lifted = threeBodies(true, 0.1);
  for (const std::string bottom : {"Bonded", "Coulomb"}) {
    SCOPED_TRACE("block on foundation: " + bottom);
    const Stack s{"Bonded", bottom, kSteel, kAluminium, kAluminium};
    auto scene = with(sceneOf(s), {"Contact/Search Distance=0.2"});
    const auto touching = test::solveBoxScene(threeBodies(true), scene);
    const auto apart = test::solveBoxScene(lifted, scene);
    if (worldRank() != 0) continue;
    double error = 0.0, size = 0.0;
    for (size_t n = 0; n < touching.displacement().size(); ++n)
      for (int c = 0; c < 3; ++c) {
        error = std::max(error, std::abs(apart.displacement()[n][c] - touching.displacement()[n][c]));
        size = std::max(size, std::abs(touching.displacement()[n][c]));
      }
    EXPECT_LT(error / size, 1e-9) << error / size;
  }
}

TEST(ThreeBodiesInput, badInterfacesAreInputErrorsNamingThem) {
  const auto base = inputBase();
  // One contact modelled twice with slave and master swapped (a double pass).
  auto message = inputError(with(base, {"Contact/a/Slave Side Set=block_z0", "Contact/a/Master Side Set=foundation_z1",
                                        "Contact/b/Slave Side Set=foundation_z1", "Contact/b/Master Side Set=block_z0"}));
  EXPECT_TRUE(contains(message, "Contact/b (foundation_z1 -> block_z0) models the contact of Contact/a (block_z0 -> "
                                "foundation_z1) again with slave and master swapped"))
      << message;
  // The same contact twice (issue 44: the later interface got no rows, exit 0), with one law or
  // another on it.
  for (const char* law : {"Coulomb", "Bonded"}) {
    message = inputError(with(base, {"Contact/a/Slave Side Set=block_z0", "Contact/a/Master Side Set=foundation_z1",
                                     "Contact/b/Slave Side Set=block_z0", "Contact/b/Master Side Set=foundation_z1",
                                     std::string("Contact/b/Friction Model=") + law}));
    EXPECT_TRUE(contains(message, "Contact/b (block_z0 -> foundation_z1) models the contact of Contact/a (block_z0 -> "
                                  "foundation_z1) again"))
        << message;
  }
  // An interface sublist without a name (its results would be the flat list's contact_...).
  message = inputError(with(base, {"Contact//Slave Side Set=block_z0", "Contact//Master Side Set=foundation_z1"}));
  EXPECT_TRUE(contains(message, "an interface sublist has an empty name")) << message;
  // Self-contact.
  message = inputError(with(base, {"Contact/self/Slave Side Set=block_z0", "Contact/self/Master Side Set=block_z1"}));
  EXPECT_TRUE(contains(message, "Contact/self (block_z0 -> block_z1): both surfaces have faces on element block "
                                "\"block\": self-contact"))
      << message;
  // The flat shorthand and sublists together.
  message = inputError(with(base, {"Contact/Slave Side Set=block_z0", "Contact/Master Side Set=foundation_z1",
                                   "Contact/b/Slave Side Set=punch_z0", "Contact/b/Master Side Set=block_z1"}));
  EXPECT_TRUE(contains(message, "one-interface shorthand; with interface sublists (Contact/b)")) << message;
  // A sublist without its master surface; an unknown side set names the interface.
  message = inputError(with(base, {"Contact/b/Slave Side Set=punch_z0"}));
  EXPECT_TRUE(contains(message, "Contact/b: give both \"Slave Side Set\" and \"Master Side Set\"")) << message;
  message = inputError(with(base, {"Contact/b/Slave Side Set=punch_z0", "Contact/b/Master Side Set=no_such_set"}));
  EXPECT_TRUE(contains(message, "Contact/b: ") && contains(message, "no_such_set")) << message;
}

}  // namespace
