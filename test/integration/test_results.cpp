// What an analyst reads off a solution (stack/Results.hpp): stresses, strain energy,
// reactions and the force balance, and the contact output fields.
//  - uniform compression: a column held by three symmetry planes under a pressure p on top
//    has the exact uniform state sigma = (0, 0, -p, 0, 0, 0) in every element and at every
//    node (linear fields lie in the P1 space), von Mises = p, strain energy p^2 V / (2E),
//    and the symmetry plane z = 0 carries the load;
//  - the paper's two bricks (Coulomb, tolerance 1e-10): reactions + applied load = 0 to
//    1e-8, and the aluminium brick, which carries no load, passes the contact force on to
//    its clamp;
//  - surfaces from node sets: the same contact scene with loads and contact surfaces given
//    by node sets only (as meshio writes meshes) has the same solution as with side sets.
// ctest runs the first two on 1 and 2 ranks (reactions are gathered from every rank).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "BoxMesh.hpp"
#include "BoxScene.hpp"
#include "ContactScene.hpp"
#include "tribos/fem/Material.hpp"
#include "tribos/stack/Results.hpp"

namespace {
using namespace tribos;
using test::displacementCondition;
using test::with;
using test::worldRank;

double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

std::array<double, 3> plus(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}

const stack::ConditionReaction& reactionOf(const stack::ForceBalance& balance, const std::string& name) {
  const auto it = std::find_if(balance.reactions.begin(), balance.reactions.end(),
                               [&](const stack::ConditionReaction& r) { return r.name == name; });
  if (it == balance.reactions.end()) throw std::runtime_error("no reaction named " + name);
  return *it;
}
}  // namespace

// Nodal stresses at every node, the surface included (issue 42): a complete quadratic
// displacement gives the exact stress at each node, by the patch recovery on linear elements
// (hexahedra with their inner nodes moved, prisms, linear tetrahedra) and by the extrapolation
// from the quadrature points on quadratic tetrahedra. The means of element stresses (the old
// nodal field) miss it by the stress gradient times half an element.
TEST(results, nodalStressesOfAQuadraticDisplacementAreExactAtEveryNode) {
  if (worldRank() != 0) return;
  const double a[3][10] = {{0.1, 0.3, -0.2, 0.5, 0.7, -0.4, 0.2, 0.6, -0.3, 0.25},
                           {-0.2, 0.4, 0.1, -0.6, 0.3, 0.5, -0.1, 0.2, 0.4, -0.35},
                           {0.3, -0.1, 0.6, 0.2, -0.5, 0.1, 0.45, -0.3, 0.15, 0.2}};
  auto displacement = [&](const std::array<double, 3>& x, int c) {
    const double m[10] = {1, x[0], x[1], x[2], x[0] * x[0], x[1] * x[1], x[2] * x[2], x[0] * x[1], x[1] * x[2], x[0] * x[2]};
    double sum = 0.0;
    for (int k = 0; k < 10; ++k) sum += a[c][k] * m[k];
    return sum;
  };
  auto gradient = [&](const std::array<double, 3>& x, int c, int j) {  // d u_c / d x_j
    const double dm[3][10] = {{0, 1, 0, 0, 2 * x[0], 0, 0, x[1], 0, x[2]},
                              {0, 0, 1, 0, 0, 2 * x[1], 0, x[0], x[2], 0},
                              {0, 0, 0, 1, 0, 0, 2 * x[2], 0, x[1], x[0]}};
    double sum = 0.0;
    for (int k = 0; k < 10; ++k) sum += a[c][k] * dm[j][k];
    return sum;
  };
  const auto steel = fem::Material::fromYoungPoisson(1000.0, 0.3);
  for (auto fill : {test::CellElements::Hexahedron, test::CellElements::TwoPrisms, test::CellElements::KuhnTetrahedra,
                    test::CellElements::QuadraticKuhnTetrahedra}) {
    auto mesh = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.5}, {3, 3, 4}, "box", fill);
    if (fill == test::CellElements::Hexahedron)  // inner grid nodes moved: general hexahedra
      for (auto& x : mesh.coords)
        if (x[0] > 0 && x[0] < 1 && x[1] > 0 && x[1] < 1 && x[2] > 0 && x[2] < 1.5) {
          x[0] += 0.05 * std::sin(7 * x[1] + 3 * x[2]);
          x[1] += 0.05 * std::cos(5 * x[0] + 2 * x[2]);
        }
    test::ExodusScene input(mesh, {"Materials/box/Young Modulus=1000", "Materials/box/Poisson Ratio=0.3"});
    const auto scene = input.build();
    std::vector<std::array<double, 3>> u(scene.mesh.numNodes());
    for (LO n = 0; n < scene.mesh.numNodes(); ++n)
      for (int c = 0; c < 3; ++c) u[n][c] = displacement(scene.mesh.coords[n], c);
    const auto stress = stack::evaluateStresses(scene, u);
    double worst = 0.0, size = 0.0;
    for (LO n = 0; n < scene.mesh.numNodes(); ++n) {
      const auto& x = scene.mesh.coords[n];
      constexpr int row[6] = {0, 1, 2, 0, 1, 0}, col[6] = {0, 1, 2, 1, 2, 2};
      double eps[6];
      for (int k = 0; k < 6; ++k) eps[k] = 0.5 * (gradient(x, row[k], col[k]) + gradient(x, col[k], row[k]));
      const double trace = eps[0] + eps[1] + eps[2];
      for (int k = 0; k < 6; ++k) {
        const double exact = 2 * steel.mu * eps[k] + (k < 3 ? steel.lambda * trace : 0.0);
        worst = std::max(worst, std::abs(stress.nodal[k][n] - exact));
        size = std::max(size, std::abs(exact));
      }
    }
    std::printf("quadratic displacement, fill %d: max nodal stress error / max stress = %.2e\n", static_cast<int>(fill),
                worst / size);
    EXPECT_LT(worst, 1e-9 * size) << "fill " << static_cast<int>(fill);
  }
}

TEST(results, uniformCompressionGivesTheExactStressEverywhere) {
  // Column [0,1] x [0,1] x [0,3], E = 1000, nu = 0.25, p = 2 on the top face.
  constexpr double kE = 1000.0, kP = 2.0, kVolume = 3.0;
  const auto mesh = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 3.0}, {2, 2, 6}, "column");
  std::vector<std::string> o = {"Mesh/Subdomains=4", "Materials/column/Young Modulus=1000",
                                "Materials/column/Poisson Ratio=0.25", "Solver/Tolerance=1e-13", "Solver/Verbose=false",
                                "Loads/top/Side Set=column_z1", "Loads/top/Traction={0, 0, -2}"};
  o = with(o, displacementCondition("symmetry_x", "column_x0", "x"));
  o = with(o, displacementCondition("symmetry_y", "column_y0", "y"));
  o = with(o, displacementCondition("symmetry_z", "column_z0", "z"));
  const auto s = test::solveBoxScene(mesh, o);
  ASSERT_TRUE(s.linear.converged);
  if (worldRank() != 0) return;

  const auto stress = stack::evaluateStresses(s.scene, s.displacement());
  const double exact[6] = {0.0, 0.0, -kP, 0.0, 0.0, 0.0};
  double worstElement = 0.0, worstNode = 0.0;
  for (LO e = 0; e < s.scene.mesh.numElements(); ++e) {
    for (int k = 0; k < 6; ++k) worstElement = std::max(worstElement, std::abs(stress.element[k][e] - exact[k]));
    worstElement = std::max(worstElement, std::abs(stress.elementVonMises[e] - kP));
  }
  for (LO n = 0; n < s.scene.mesh.numNodes(); ++n) {
    for (int k = 0; k < 6; ++k) worstNode = std::max(worstNode, std::abs(stress.nodal[k][n] - exact[k]));
    worstNode = std::max(worstNode, std::abs(stress.nodalVonMises[n] - kP));
  }
  std::printf("uniform compression: max |sigma - exact| / p = %.2e (elements), %.2e (nodes)\n", worstElement / kP,
              worstNode / kP);
  EXPECT_LE(worstElement, 1e-10 * kP);
  EXPECT_LE(worstNode, 1e-10 * kP);
  EXPECT_NEAR(stress.strainEnergy, kP * kP * kVolume / (2.0 * kE), 1e-10 * kP * kP * kVolume / kE);

  // The load p A = 2 goes down; the plane z = 0 pushes back with 2; the lateral planes carry nothing.
  const auto balance = stack::forceBalance(s.scene, s.linear.reaction, s.linear.appliedLoad, s.linear.appliedLoadMagnitude);
  EXPECT_NEAR(balance.appliedLoad[2], -kP, 1e-14);
  EXPECT_NEAR(norm(reactionOf(balance, "symmetry_z").force), kP, 1e-10 * kP);
  EXPECT_NEAR(reactionOf(balance, "symmetry_z").force[2], kP, 1e-10 * kP);
  EXPECT_LE(norm(reactionOf(balance, "symmetry_x").force), 1e-10 * kP);
  EXPECT_LE(norm(reactionOf(balance, "symmetry_y").force), 1e-10 * kP);
  EXPECT_LE(balance.relativeImbalance, 1e-10);
}

TEST(results, paperProblemReactionsBalanceTheLoad) {
  const auto s = test::solveContactScene({"Mesh/Subdomains Per Brick=4x2x2", "Mesh/H Over h=2",
                                          "Contact/Friction Model=Coulomb", "Contact/F1=0.3", "Contact/F2=0.3",
                                          "Solver/Tolerance=1e-10", "Solver/Verbose=false"});
  const auto& r = s.result;
  EXPECT_TRUE(r.contact.converged) << r.contact.message;
  if (worldRank() != 0) return;
  const auto balance = stack::forceBalance(s.scene, r.reaction, r.appliedLoad, r.appliedLoadMagnitude);
  const double load = norm(r.appliedLoad);
  std::printf("paper problem: applied load (%g, %g, %g), |reactions + load| / |load| = %.2e\n", r.appliedLoad[0],
              r.appliedLoad[1], r.appliedLoad[2], balance.relativeImbalance);
  EXPECT_NEAR(load, std::hypot(100.0, 4000.0), 1e-9 * load);  // the paper's tractions on the steel brick
  EXPECT_LE(balance.relativeImbalance, 1e-8);
  ASSERT_EQ(balance.reactions.size(), 2u);
  // Each clamp is in one condition here, so the conditions add up to the total.
  const auto sum = plus(balance.reactions[0].force, balance.reactions[1].force);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], balance.totalReaction[c], 1e-12 * load);
  // The aluminium brick (slave) is loaded only by the steel brick: its clamp takes exactly
  // what it passes on to the steel (the contact force on the master).
  const auto& aluminium = reactionOf(balance, "dirichlet_aluminium").force;
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(aluminium[c], r.totalContactForce[c], 1e-8 * load) << "component " << c;

  // Contact output fields: matching meshes, no initial gap; unit normals; the master node is
  // on the steel's contact surface; bodies in contact have closed their gap.
  const auto& steel = s.scene.mesh.nodeSet("contact_steel").nodes;
  double uMax = 0.0;
  for (const auto& u : r.displacement.value) uMax = std::max(uMax, norm(u));
  for (const auto& c : s.B.contact) {
    const LO n = c.slaveNode;
    EXPECT_EQ(r.contactGap[n], 0.0);
    EXPECT_NEAR(std::hypot(r.contactNx[n], r.contactNy[n], r.contactNz[n]), 1.0, 1e-14);
    const LO master = static_cast<LO>(r.contactMaster[n]) - 1;
    EXPECT_TRUE(std::binary_search(steel.begin(), steel.end(), master)) << "master node " << master + 1;
    EXPECT_GE(r.contactOpening[n], -1e-6 * uMax);
    if (r.contactStatus[n] > 0) EXPECT_LE(std::abs(r.contactOpening[n]), 1e-6 * uMax);
  }
  for (LO n = 0; n < s.scene.mesh.numNodes(); ++n)
    if (r.contactMaster[n] == 0.0) EXPECT_EQ(r.contactNormal[n], 0.0);
}

// Two stacked boxes in contact: the lower one clamped at its bottom, the upper one held by
// symmetry planes x = 0, y = 0 and the contact, pressed by a traction on its top.
TEST(results, nodeSetSurfacesGiveTheSameSolutionAsSideSets) {
  const auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "lower");
  const auto upper = test::boxMesh({0.0, 0.0, 1.0}, {1.0, 1.0, 1.0}, {3, 3, 2}, "upper");
  const auto withSideSets = test::mergeMeshes(lower, upper);
  auto nodeSetsOnly = withSideSets;
  nodeSetsOnly.sideSets.clear();
  std::vector<std::string> o = {"Mesh/Subdomains=4", "Materials/lower/Young Modulus=1000",
                                "Materials/lower/Poisson Ratio=0.3", "Materials/upper/Young Modulus=3000",
                                "Materials/upper/Poisson Ratio=0.2", "Solver/Tolerance=1e-10", "Solver/Verbose=false",
                                "Boundary/Dirichlet Node Sets={lower_z0}", "Contact/Friction Model=None",
                                "Contact/Slave Side Set=lower_z1", "Contact/Master Side Set=upper_z0",
                                "Loads/press/Traction={0, 0, -5}"};
  o = with(o, displacementCondition("upper_x", "upper_x0", "x"));
  o = with(o, displacementCondition("upper_y", "upper_y0", "y"));
  const auto bySideSets = test::solveBoxScene(withSideSets, with(o, {"Loads/press/Side Set=upper_z1"}));
  const auto byNodeSets = test::solveBoxScene(nodeSetsOnly, with(o, {"Loads/press/Node Set=upper_z1"}));
  EXPECT_TRUE(bySideSets.contact.contact.converged);
  EXPECT_TRUE(byNodeSets.contact.contact.converged);
  if (worldRank() != 0) return;
  EXPECT_EQ(byNodeSets.B.contact.size(), bySideSets.B.contact.size());
  double diff = 0.0, scale = 0.0;
  for (size_t n = 0; n < bySideSets.displacement().size(); ++n) {
    scale = std::max(scale, norm(bySideSets.displacement()[n]));
    for (int c = 0; c < 3; ++c)
      diff = std::max(diff, std::abs(bySideSets.displacement()[n][c] - byNodeSets.displacement()[n][c]));
  }
  EXPECT_LE(diff, 1e-8 * scale);
  // The upper box passes its load (5 on its unit top) through the contact to the clamp.
  const auto& r = byNodeSets.contact;
  EXPECT_NEAR(r.appliedLoad[2], -5.0, 1e-12);
  EXPECT_NEAR(r.totalContactForce[2], 5.0, 1e-8 * 5.0);  // force of the lower (slave) box on the upper
  const auto balance = stack::forceBalance(byNodeSets.scene, r.reaction, r.appliedLoad, r.appliedLoadMagnitude);
  EXPECT_NEAR(reactionOf(balance, "lower_z0").force[2], 5.0, 1e-8 * 5.0);
  EXPECT_LE(balance.relativeImbalance, 1e-8);
}

// Where a contact surface meets a symmetry plane, the contact rows drop the prescribed
// components of their nodes, and the support takes that part of the contact force: the
// reactions must include it to balance the load. Two stacked boxes, each held by the
// symmetry planes x = 0 and y = 0, the lower one on z = 0, Coulomb friction with t1 along
// (1, 1, 0) (so the tangential rows have x and y components) under a load with shear.
TEST(results, reactionsBalanceWhereContactMeetsSymmetryPlanes) {
  const auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "lower");
  const auto upper = test::boxMesh({0.0, 0.0, 1.0}, {1.0, 1.0, 1.0}, {3, 3, 2}, "upper");
  std::vector<std::string> o = {"Mesh/Subdomains=4", "Materials/lower/Young Modulus=1000",
                                "Materials/lower/Poisson Ratio=0.3", "Materials/upper/Young Modulus=3000",
                                "Materials/upper/Poisson Ratio=0.2", "Solver/Tolerance=1e-10", "Solver/Verbose=false",
                                "Contact/Friction Model=Coulomb", "Contact/F1=0.3", "Contact/F2=0.3",
                                "Contact/T1 Direction={1, 1, 0}", "Contact/Slave Side Set=lower_z1",
                                "Contact/Master Side Set=upper_z0", "Loads/press/Side Set=upper_z1",
                                "Loads/press/Traction={0.5, 0.3, -5}"};
  for (const char* body : {"lower", "upper"}) {
    o = with(o, displacementCondition(std::string(body) + "_x", std::string(body) + "_x0", "x"));
    o = with(o, displacementCondition(std::string(body) + "_y", std::string(body) + "_y0", "y"));
  }
  o = with(o, displacementCondition("lower_z", "lower_z0", "z"));
  const auto s = test::solveBoxScene(test::mergeMeshes(lower, upper), o);
  const auto& r = s.contact;
  EXPECT_TRUE(r.contact.converged) << r.contact.message;
  if (worldRank() != 0) return;
  const auto balance = stack::forceBalance(s.scene, r.reaction, r.appliedLoad, r.appliedLoadMagnitude);
  std::printf("contact on symmetry planes: |reactions + load| / |load| = %.2e\n", balance.relativeImbalance);
  EXPECT_LE(balance.relativeImbalance, 1e-8);
  // The upper box is held by its planes and the contact only: its planes take the load
  // minus what the contact passes on (the force of the lower, slave, box on it).
  const auto& ux = reactionOf(balance, "upper_x").force;
  const auto& uy = reactionOf(balance, "upper_y").force;
  EXPECT_NEAR(ux[0] + r.totalContactForce[0] + r.appliedLoad[0], 0.0, 1e-8 * norm(r.appliedLoad));
  EXPECT_NEAR(uy[1] + r.totalContactForce[1] + r.appliedLoad[1], 0.0, 1e-8 * norm(r.appliedLoad));
}

// Force scales that exist (issue 30): a scene driven by a prescribed displacement alone (no
// load) converges with every KKT residual relative to the forces it has, and the reaction
// of the indenting condition is the contact resultant; loads that cancel (the same force up
// and down on two faces) balance to round-off, not to |reactions| / |round-off|.
TEST(results, aDisplacementDrivenIndentationConvergesAndItsReactionIsTheContactForce) {
  const auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {3, 3, 2}, "lower");
  const auto upper = test::boxMesh({0.25, 0.25, 1.0}, {0.5, 0.5, 0.5}, {2, 2, 2}, "upper");
  std::vector<std::string> o = {"Mesh/Subdomains=4", "Materials/lower/Young Modulus=1000",
                                "Materials/lower/Poisson Ratio=0.3", "Materials/upper/Young Modulus=3000",
                                "Materials/upper/Poisson Ratio=0.2", "Solver/Verbose=false",
                                "Contact/Friction Model=Coulomb", "Contact/Slave Side Set=lower_z1",
                                "Contact/Master Side Set=upper_z0", "Boundary/Dirichlet Node Sets={lower_z0}",
                                // Rows for the indenter's x and y = 0 too: their reactions are -lambda,
                                // which balance to round-off by construction (the default, Automatic,
                                // eliminates them: K u - f, which carries the solve's error, ~1e-8 here).
                                "FETI/Displacement Conditions=Multipliers"};
  o = with(o, displacementCondition("indent", "upper_z1", "xyz", "{0, 0, -0.01}"));
  const auto s = test::solveBoxScene(test::mergeMeshes(lower, upper), o);
  const auto& r = s.contact;
  ASSERT_TRUE(r.contact.converged) << r.contact.message;
  EXPECT_LE(r.contact.kkt.equilibrium, 1e-6);
  EXPECT_EQ(r.appliedLoadMagnitude, 0.0);
  if (worldRank() != 0) return;
  const auto balance = stack::forceBalance(s.scene, r.reaction, r.appliedLoad, r.appliedLoadMagnitude);
  const double push = -reactionOf(balance, "indent").force[2];
  EXPECT_GT(push, 0.0);
  EXPECT_NEAR(r.totalContactForce[2], push, 1e-6 * push);  // the lower (slave) box pushes the punch up
  EXPECT_NEAR(reactionOf(balance, "lower_z0").force[2], push, 1e-6 * push);
  EXPECT_LE(balance.relativeImbalance, 1e-10);
}

TEST(results, loadsThatCancelBalanceToRoundOff) {
  const auto mesh = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "box");
  std::vector<std::string> o = {"Mesh/Subdomains=2", "Materials/box/Young Modulus=1000",
                                "Materials/box/Poisson Ratio=0.3", "Solver/Tolerance=1e-10", "Solver/Verbose=false",
                                "Boundary/Dirichlet Node Sets={box_x0}", "Loads/down/Side Set=box_z1",
                                "Loads/down/Traction={0, 0, -1}", "Loads/up/Side Set=box_x1",
                                "Loads/up/Traction={0, 0, 1}"};
  const auto s = test::solveBoxScene(mesh, o);
  ASSERT_TRUE(s.linear.converged);
  // |down| + |up| = 2, less what cancels at the nodes of the edge the two faces share.
  EXPECT_GT(s.linear.appliedLoadMagnitude, 1.5);
  EXPECT_LE(s.linear.appliedLoadMagnitude, 2.0 + 1e-12);
  if (worldRank() != 0) return;
  EXPECT_LE(std::abs(s.linear.appliedLoad[2]), 1e-12);
  const auto balance = stack::forceBalance(s.scene, s.linear.reaction, s.linear.appliedLoad,
                                           s.linear.appliedLoadMagnitude);
  EXPECT_LE(balance.relativeImbalance, 1e-10);
}

// Overload said early (issue 30): a box held on another by contact and friction alone,
// sheared at 1.5 times what friction carries (F = 0.3, shear 0.45 of the pressure). There is
// no equilibrium: SMALSE-M's ||G mu|| stalls, and the run stops within the stall window (not
// at Solver/Max Outer Iterations = 100), not converged, naming the interface, its friction
// capacity F N and the load along the contact plane.
TEST(results, anOverloadedFrictionJointStopsEarlyNamingItsCapacity) {
  const auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "lower");
  const auto upper = test::boxMesh({0.0, 0.0, 1.0}, {1.0, 1.0, 0.5}, {3, 3, 2}, "upper");
  const std::vector<std::string> o = {
      "Mesh/Subdomains=4", "Materials/lower/Young Modulus=1000", "Materials/lower/Poisson Ratio=0.3",
      "Materials/upper/Young Modulus=1000", "Materials/upper/Poisson Ratio=0.3", "Solver/Verbose=false",
      "Contact/Friction Model=Coulomb", "Contact/F1=0.3", "Contact/F2=0.3", "Contact/Slave Side Set=lower_z1",
      "Contact/Master Side Set=upper_z0", "Boundary/Dirichlet Node Sets={lower_z0}", "Loads/shear/Side Set=upper_z1",
      "Loads/shear/Traction={0.45, 0, -1}"};
  const auto s = test::solveBoxScene(test::mergeMeshes(lower, upper), o);
  const auto& r = s.contact.contact;
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.counters.stalled);
  EXPECT_LE(r.counters.outerIterations, 40);
  for (const char* words : {"stall window = 20", "lower_z1 -> upper_z0", "friction capacity F N = 0.3 x ",
                            "against an applied load of 0.45"})
    EXPECT_NE(r.message.find(words), std::string::npos) << "missing \"" << words << "\" in: " << r.message;
  // N is the normal force of the iterate it stopped at: the pressure's resultant 1, to 1e-4
  // (0.999985 since rho grows after 10 slow outer iterations, SMALSE-M's default).
  const size_t at = r.message.find("0.3 x ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_NEAR(std::stod(r.message.substr(at + 6)), 1.0, 1e-4) << r.message;
}

// Near and beyond the capacity (issue 42). The same joint at 97 % of what friction carries
// converges to equilibrium: ||G mu|| falls slowly for a while, which the stall window alone took
// for an overload. At 1.25 times the capacity (F = 0.15) the run stops, whichever way (stall or a
// diverging fixed point), naming the capacity, with the counts of the failed solve kept.
namespace {
test::SolvedBoxScene shearedJoint(double F, double shear) {
  const auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "lower");
  const auto upper = test::boxMesh({0.0, 0.0, 1.0}, {1.0, 1.0, 0.5}, {3, 3, 2}, "upper");
  const std::string f = std::to_string(F);
  const std::vector<std::string> o = {
      "Mesh/Subdomains=4", "Materials/lower/Young Modulus=1000", "Materials/lower/Poisson Ratio=0.3",
      "Materials/upper/Young Modulus=1000", "Materials/upper/Poisson Ratio=0.3", "Solver/Verbose=false",
      "Contact/Friction Model=Coulomb", "Contact/F1=" + f, "Contact/Slave Side Set=lower_z1",
      "Contact/Master Side Set=upper_z0", "Boundary/Dirichlet Node Sets={lower_z0}", "Loads/shear/Side Set=upper_z1",
      "Loads/shear/Traction={" + std::to_string(shear) + ", 0, -1}"};
  return test::solveBoxScene(test::mergeMeshes(lower, upper), o);
}
}  // namespace

TEST(results, aFrictionJointAt97PercentOfItsCapacityConverges) {
  const auto s = shearedJoint(0.3, 0.97 * 0.3);
  const auto& r = s.contact.contact;
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_FALSE(r.counters.stalled);
  if (test::worldRank() != 0) return;
  const auto balance = stack::forceBalance(s.scene, s.contact.reaction, s.contact.appliedLoad, s.contact.appliedLoadMagnitude);
  EXPECT_LE(balance.relativeImbalance, 1e-8);
  std::printf("joint at 97 %% of its capacity: %d outer iterations, %lld PFP, friction %.6f of capacity %.6f\n",
              r.counters.outerIterations, r.counters.operatorApplications, s.contact.interfaces[0].frictionForce,
              0.3 * s.contact.interfaces[0].normalForce);
}

TEST(results, aFrictionJointBeyondItsCapacityStopsNamingItAndKeepsItsCounts) {
  const auto s = shearedJoint(0.15, 1.25 * 0.15);
  const auto& r = s.contact.contact;
  EXPECT_FALSE(r.converged);
  for (const char* words : {"lower_z1 -> upper_z0", "friction capacity F N = 0.15 x 1", "against an applied load of 0.1875"})
    EXPECT_NE(r.message.find(words), std::string::npos) << "missing \"" << words << "\" in: " << r.message;
  EXPECT_GT(r.counters.outerIterations, 0);
  EXPECT_GT(r.counters.operatorApplications, 0);
  EXPECT_LT(r.counters.outerIterations, 100) << "stopped before Solver/Max Outer Iterations: " << r.message;
  if (test::worldRank() == 0) std::printf("beyond capacity: %s\n", r.message.c_str());
}

// A history whose last step is beyond the capacity (shear 1.25 x F N): the step is cut back
// (Load Steps/Max Cutbacks = 4) and stops near the capacity (the shear factor 0.8, at position
// 1.6, carries 0.15 = F N: reached in [1.5, 1.6], in 1/16 steps), not converged; every try is counted in
// its record and in the totals (the summary's counts are the sum over the tries).
TEST(results, aFailedLoadStepIsCountedInItsRecordAndTheTotals) {
  const auto lower = test::boxMesh({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {2, 2, 2}, "lower");
  const auto upper = test::boxMesh({0.0, 0.0, 1.0}, {1.0, 1.0, 0.5}, {3, 3, 2}, "upper");
  const std::vector<std::string> o = {
      "Mesh/Subdomains=4", "Materials/lower/Young Modulus=1000", "Materials/lower/Poisson Ratio=0.3",
      "Materials/upper/Young Modulus=1000", "Materials/upper/Poisson Ratio=0.3", "Solver/Verbose=false",
      "Contact/Friction Model=Coulomb", "Contact/F1=0.15", "Contact/Slave Side Set=lower_z1",
      "Contact/Master Side Set=upper_z0", "Boundary/Dirichlet Node Sets={lower_z0}",
      "Loads/press/Side Set=upper_z1", "Loads/press/Traction={0, 0, -1}", "Loads/shear/Side Set=upper_z1",
      "Loads/shear/Traction={0.1875, 0, 0}", "Load Steps/Number Of Steps=2", "Load Steps/press/Factors={1, 1}",
      "Load Steps/shear/Factors={0.5, 1}"};
  const auto s = test::solveBoxScene(test::mergeMeshes(lower, upper), o);
  const auto& r = s.contact;
  ASSERT_EQ(r.steps.size(), 2u);
  EXPECT_TRUE(r.steps[0].converged);
  EXPECT_FALSE(r.steps[1].converged);
  EXPECT_GT(r.steps[1].pfpApplications, 0);
  EXPECT_EQ(r.steps[0].attempts, 1);
  EXPECT_EQ(r.steps[1].cutbacks, 4);
  EXPECT_GT(r.steps[1].attempts, 5);
  EXPECT_GE(r.steps[1].reached, 1.5);
  EXPECT_LE(r.steps[1].reached, 1.6);
  EXPECT_EQ(r.contact.counters.operatorApplications, r.steps[0].pfpApplications + r.steps[1].pfpApplications);
  EXPECT_EQ(r.contact.counters.outerIterations, r.steps[0].outerIterations + r.steps[1].outerIterations);
  for (const char* words : {"friction capacity F N = 0.15 x 1", "after 4 cutback(s)"})
    EXPECT_NE(r.contact.message.find(words), std::string::npos) << r.contact.message;
}
