// Per-component displacement conditions (Boundary/<name>: Node Set, Components,
// Displacement) on a scene without contact, solved by linear T-FETI: a box held only by
// three symmetry planes reproduces the exact uniform-strain solution under a pressure and
// under a prescribed end displacement (linear fields lie in the P1 space, so the only error
// is the solver's); contradicting conditions and malformed Components are input errors
// naming what is wrong. ctest runs this on 1 and 2 ranks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "BoxMesh.hpp"
#include "BoxScene.hpp"
#include "tribos/core/Errors.hpp"

namespace {
using namespace tribos;
using test::displacementCondition;
using test::with;
using test::worldRank;

constexpr double kE = 1000.0, kNu = 0.25;

/// Box [0,1] x [0,1] x [0,3], 2 x 2 x 6 cells, 4 METIS subdomains, E = 1000, nu = 0.25,
/// symmetry planes u_x = 0 on x0, u_y = 0 on y0, u_z = 0 on z0 (nothing else holds it: the
/// lateral faces and the top are free to move, so the strain is uniform).
mesh::Mesh box() {
  auto m = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 3.0}, {2, 2, 6}, "box");
  m.validate("test");
  return m;
}

std::vector<std::string> symmetryScene() {
  std::vector<std::string> o = {"Mesh/Subdomains=4", "Materials/box/Young Modulus=1000", "Materials/box/Poisson Ratio=0.25",
                                "Solver/Tolerance=1e-13", "Solver/Verbose=false"};
  o = with(o, displacementCondition("symmetry_x", "box_x0", "x"));
  o = with(o, displacementCondition("symmetry_y", "box_y0", "y"));
  return with(o, displacementCondition("symmetry_z", "box_z0", "z"));
}

/// max over nodes and components |u - exact| / max |exact|.
double relativeError(const test::SolvedBoxScene& s, double ex, double ey, double ez) {
  double diff = 0.0, norm = 0.0;
  const auto& u = s.displacement();
  for (LO n = 0; n < s.scene.mesh.numNodes(); ++n) {
    const auto& x = s.scene.mesh.coords[n];
    const double exact[3] = {ex * x[0], ey * x[1], ez * x[2]};
    for (int c = 0; c < 3; ++c) {
      diff = std::max(diff, std::abs(u[n][c] - exact[c]));
      norm = std::max(norm, std::abs(exact[c]));
    }
  }
  return diff / norm;
}

void expectInputError(const std::vector<std::string>& overrides, bool atConstraints,
                      const std::vector<std::string>& mentions) {
  test::ExodusScene input(box(), with(symmetryScene(), overrides));
  try {
    const auto scene = input.build();
    if (atConstraints) feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), 1);
    ADD_FAILURE() << "no input error";
  } catch (const core::InputError& e) {
    for (const auto& m : mentions) EXPECT_NE(std::string(e.what()).find(m), std::string::npos) << e.what();
  }
}
}  // namespace

TEST(displacementConditions, pressureOnABoxOnSymmetryPlanesGivesTheUniformStrain) {
  // p = 2 on the top: sigma_zz = -p, so u = (nu p/E x, nu p/E y, -p/E z).
  const double p = 2.0;
  const auto s = test::solveBoxScene(box(), with(symmetryScene(), {"Loads/top/Side Set=box_z1",
                                                                   "Loads/top/Traction={0, 0, -2}"}));
  EXPECT_TRUE(s.scene.contacts.empty());
  EXPECT_TRUE(s.linear.converged);
  if (worldRank() != 0) return;
  const double error = relativeError(s, kNu * p / kE, kNu * p / kE, -p / kE);
  std::printf("pressure: max |u - exact| / max |exact| = %.3e (%d CG iterations)\n", error, s.linear.iterations);
  EXPECT_LE(error, 1e-10);
  EXPECT_LE(s.linear.maxCopyJump, 1e-10 * 3.0 * p / kE);
}

TEST(displacementConditions, prescribedEndDisplacementGivesTheUniformStrain) {
  // u_z = -0.03 on the top (z = 3), no load: strain -0.01 along z, u = (0.01 nu x,
  // 0.01 nu y, -0.01 z). The top's lateral components stay free.
  const auto s = test::solveBoxScene(box(), with(symmetryScene(), displacementCondition("pressed", "box_z1", "z",
                                                                                        "{0, 0, -0.03}")));
  // The x, y values given with Components "z" are ignored: the same scene with {5, 5, -0.03}.
  const auto t = test::solveBoxScene(box(), with(symmetryScene(), displacementCondition("pressed", "box_z1", "z",
                                                                                        "{5, 5, -0.03}")));
  EXPECT_TRUE(s.linear.converged);
  EXPECT_TRUE(t.linear.converged);
  if (worldRank() != 0) return;
  const double error = relativeError(s, kNu * 0.01, kNu * 0.01, -0.01);
  std::printf("prescribed displacement: max |u - exact| / max |exact| = %.3e (%d CG iterations)\n", error,
              s.linear.iterations);
  EXPECT_LE(error, 1e-10);
  EXPECT_LE(relativeError(t, kNu * 0.01, kNu * 0.01, -0.01), 1e-10);
}

TEST(displacementConditions, contradictingConditionsAndBadComponentsAreInputErrors) {
  // The same node set, component x, values 0 and 1: the message names both conditions.
  expectInputError(with(displacementCondition("left_at_zero", "box_x0", "x", "{0, 0, 0}"),
                        displacementCondition("left_at_one", "box_x0", "x", "{1, 0, 0}")),
                   true, {"left_at_zero", "left_at_one", "u_x"});
  // Equal values on the same component are no contradiction.
  {
    test::ExodusScene input(box(), with(symmetryScene(), displacementCondition("again_x", "box_x0", "x")));
    const auto scene = input.build();
    EXPECT_NO_THROW(feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), 1));
  }
  // Components must list each of x, y, z at most once: the message names the parameter.
  expectInputError(displacementCondition("twice", "box_x1", "xx"), false, {"Boundary/twice/Components", "\"xx\""});
  expectInputError(displacementCondition("unknown", "box_x1", "w"), false, {"Boundary/unknown/Components", "\"w\""});
  expectInputError(displacementCondition("empty", "box_x1", ""), false, {"Boundary/empty/Components"});
  // A node set that does not exist is named too.
  expectInputError(displacementCondition("nowhere", "no_such_set", "x"), false, {"Boundary/nowhere", "no_such_set"});
}

// A roller on one body at the contact edge (issue 30): the lower box's x = 0 face above its
// clamped bottom, its contact edge included, held in x, the upper box free there. Under a load that sticks
// everywhere (Coulomb, F = 2, shear / pressure = 0.1) the two boxes move as one body, so the
// reference is the single conforming box of both (the same Kuhn tetrahedra) with the roller
// on the lower half of its x = 0 face: no contact code in it. Dropping the tangential rows of
// the edge's slave nodes (the rule for a symmetry plane, where both bodies are held) let the
// upper box slide there without friction.
namespace {
/// The roller scene below with the roller at u_x = `value`: the two boxes in contact against
/// the single conforming box; max |u - u_one_body| / max |u| (rank 0; 0 elsewhere), and the
/// contact nodes that slide.
std::pair<double, int> rollerAgainstOneBody(const std::string& value) {
  auto material = [](const std::string& block) {
    return std::vector<std::string>{"Materials/" + block + "/Young Modulus=1000",
                                    "Materials/" + block + "/Poisson Ratio=0.3"};
  };
  const std::vector<std::string> common = {"Mesh/Subdomains=4", "Solver/Tolerance=1e-10", "Solver/Verbose=false"};
  auto two = with(with(with(common, material("lower")), material("upper")),
                  {"Contact/Friction Model=Coulomb", "Contact/F1=2", "Contact/F2=2", "Contact/Slave Side Set=lower_z1",
                   "Contact/Master Side Set=upper_z0", "Boundary/Dirichlet Node Sets={lower_z0}",
                   "Loads/press/Side Set=upper_z1", "Loads/press/Traction={0.5, 0, -5}"});
  two = with(two, displacementCondition("roller", "roller_lower", "x", value));
  // The lower box's x = 0 face above its clamped bottom (a driven roller there would
  // contradict the clamp), the contact edge included.
  auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "lower");
  mesh::NodeSet roller{"roller_lower", 100, {}};
  for (LO n = 0; n < lower.numNodes(); ++n)
    if (lower.coords[n][0] == 0.0 && lower.coords[n][2] > 0.0) roller.nodes.push_back(n);
  lower.nodeSets.push_back(roller);
  const auto upper = test::boxMesh({0.0, 0.0, 1.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "upper");
  const auto contact = test::solveBoxScene(test::mergeMeshes(lower, upper), two);
  EXPECT_TRUE(contact.contact.contact.converged) << contact.contact.contact.message;

  auto body = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 2.0}, {2, 2, 4}, "body");
  mesh::NodeSet half{"roller_half", 100, {}};
  for (LO n = 0; n < body.numNodes(); ++n)
    if (body.coords[n][0] == 0.0 && body.coords[n][2] > 0.0 && body.coords[n][2] <= 1.0) half.nodes.push_back(n);
  body.nodeSets.push_back(half);
  auto one = with(with(common, material("body")), {"Boundary/Dirichlet Node Sets={body_z0}",
                                                   "Loads/press/Side Set=body_z1", "Loads/press/Traction={0.5, 0, -5}"});
  one = with(one, displacementCondition("roller", "roller_half", "x", value));
  const auto reference = test::solveBoxScene(body, one);
  EXPECT_TRUE(reference.linear.converged);
  const int sliding = contact.contact.contact.statusCounts[2];
  if (worldRank() != 0) return {0.0, sliding};
  // Every node of the two boxes against the node of the single box at the same place.
  const auto& u = contact.displacement();
  const auto& ref = reference.displacement();
  double diff = 0.0, scale = 0.0;
  for (LO n = 0; n < contact.scene.mesh.numNodes(); ++n) {
    const auto& x = contact.scene.mesh.coords[n];
    LO match = -1;
    for (LO m = 0; m < body.numNodes() && match < 0; ++m)
      if (std::abs(body.coords[m][0] - x[0]) + std::abs(body.coords[m][1] - x[1]) + std::abs(body.coords[m][2] - x[2]) <
          1e-12)
        match = m;
    if (match < 0) return {1.0, sliding};
    for (int c = 0; c < 3; ++c) {
      diff = std::max(diff, std::abs(u[n][c] - ref[match][c]));
      scale = std::max(scale, std::abs(ref[match][c]));
    }
  }
  return {diff / scale, sliding};
}
}  // namespace

TEST(displacementConditions, aRollerOnOneBodyAtTheContactEdgeKeepsItsFriction) {
  // At rest (u_x = 0) and driven (u_x = 0.002, which the upper box follows by sticking): the
  // slip at the edge includes the prescribed part (c), so every contact node sticks.
  for (const std::string value : {"{0, 0, 0}", "{0.002, 0, 0}"}) {
    const auto [error, sliding] = rollerAgainstOneBody(value);
    if (worldRank() != 0) continue;
    std::printf("roller %s on one body at the contact edge: max |u - u_one_body| / max |u| = %.2e, %d sliding\n",
                value.c_str(), error, sliding);
    EXPECT_LE(error, 1e-6) << value;
    EXPECT_EQ(sliding, 0) << value;
  }
}

// A push-out by prescribed end displacements (issue 42): an upper box pressed onto a lower
// one and pushed along x by its x = 0 face (u_x = 0.01, far beyond the elastic shear), while
// the lower box's x = 0 face is held at u_x = 0. The contact nodes on the x = 0 edge are held
// along x on both bodies at different values: their tangential rows have nothing free. Those
// rows were dropped as on a symmetry plane, so the edge carried no friction and the push force
// was a quarter (the edge's share of the area) short of F N. Now the edge slides with F times
// its normal force, which the supports carry. The y = 0 edge is held along y on both bodies at
// the same value (a symmetry plane): no friction there.
TEST(displacementConditions, aPushOutByPrescribedEndDisplacementsTakesTheWholeFrictionForce) {
  const double F = 0.2;
  auto material = [](const std::string& block) {
    return std::vector<std::string>{"Materials/" + block + "/Young Modulus=1000",
                                    "Materials/" + block + "/Poisson Ratio=0.3"};
  };
  auto o = with(with({"Mesh/Subdomains=4", "Solver/Tolerance=1e-10", "Solver/Verbose=false"}, material("lower")),
                material("upper"));
  o = with(o, {"Contact/Friction Model=Coulomb", "Contact/F1=0.2", "Contact/Slave Side Set=lower_z1",
               "Contact/Master Side Set=upper_z0", "Boundary/Dirichlet Node Sets={lower_z0}",
               "Loads/press/Side Set=upper_z1", "Loads/press/Traction={0, 0, -5}"});
  o = with(o, displacementCondition("hub_end", "lower_x0_above", "x"));
  o = with(o, displacementCondition("push", "upper_x0", "x", "{0.01, 0, 0}"));
  o = with(o, displacementCondition("lower_symmetry", "lower_y0_above", "y"));
  o = with(o, displacementCondition("upper_symmetry", "upper_y0", "y"));
  auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "lower");
  mesh::NodeSet x0{"lower_x0_above", 100, {}}, y0{"lower_y0_above", 101, {}};
  for (LO n = 0; n < lower.numNodes(); ++n) {
    if (lower.coords[n][2] == 0.0) continue;  // the clamped bottom
    if (lower.coords[n][0] == 0.0) x0.nodes.push_back(n);
    if (lower.coords[n][1] == 0.0) y0.nodes.push_back(n);
  }
  lower.nodeSets.push_back(x0);
  lower.nodeSets.push_back(y0);
  const auto upper = test::boxMesh({0.0, 0.0, 1.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "upper");
  const auto s = test::solveBoxScene(test::mergeMeshes(lower, upper), o);
  ASSERT_TRUE(s.contact.contact.converged) << s.contact.contact.message;
  if (worldRank() != 0) return;
  const auto& r = s.contact;
  double push = 0.0;  // the reaction of the pushed face along x
  for (LO n : s.scene.mesh.nodeSet("upper_x0").nodes) push += r.reaction[n][0];
  const double N = r.interfaces.at(0).normalForce;
  std::printf("push-out: push force %.6f, F N = %.6f (N = %.6f), %d of %d contact nodes slide\n", push, F * N, N,
              r.interfaces[0].counts[2], r.interfaces[0].counts[1] + r.interfaces[0].counts[2]);
  EXPECT_NEAR(N, 5.0, 1e-6) << "the pressure over the unit contact area";
  EXPECT_NEAR(std::abs(push), F * N, 0.01 * F * N);
  EXPECT_EQ(r.interfaces[0].counts[1], 0) << "every contact node slides";
  // The edge nodes slide by the prescribed difference, and the friction they carry is F times
  // their normal force.
  for (const auto& c : s.B.contact) {
    const size_t g = static_cast<size_t>(c.slaveNode);
    if (s.scene.mesh.coords[g][0] != 0.0) continue;
    const double tangential = std::hypot(r.contactT1[g], r.contactT2[g]);
    EXPECT_NEAR(tangential, F * r.contactNormal[g], 1e-6 * N) << "edge node " << g;
    const double alongX = std::abs(r.contactSlipT1[g] * c.t1[0] + r.contactSlipT2[g] * c.t2[0]);
    EXPECT_NEAR(alongX, 0.01, 1e-9) << "edge node " << g;
  }
  // Reactions and load balance, the friction included.
  double total[3] = {0.0, 0.0, 0.0};
  for (const auto& f : r.reaction)
    for (int c = 0; c < 3; ++c) total[c] += f[c];
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(total[c] + r.appliedLoad[c], 0.0, 1e-8 * N) << "component " << c;
}
