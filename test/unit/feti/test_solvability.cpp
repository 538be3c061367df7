// Free rigid motions before the solve (feti/Solvability.hpp): the kernel of B restricted to
// the bodies' rigid modes, on the paper's two bricks with various Dirichlet / contact sets,
// over structured and METIS decompositions (rows that touch several subdomains).
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>

#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "tribos/core/Errors.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/Solvability.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {

/// Rotates every node about `axis` (through the origin) by `angle` (Rodrigues' formula).
void rotate(mesh::Mesh& mesh, std::array<double, 3> axis, double angle) {
  const double norm = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
  for (double& a : axis) a /= norm;
  const double c = std::cos(angle), s = std::sin(angle);
  for (auto& x : mesh.coords) {
    const double dot = axis[0] * x[0] + axis[1] * x[1] + axis[2] * x[2];
    const std::array<double, 3> cross = {axis[1] * x[2] - axis[2] * x[1], axis[2] * x[0] - axis[0] * x[2],
                                         axis[0] * x[1] - axis[1] * x[0]};
    for (int d = 0; d < 3; ++d) x[d] = c * x[d] + s * cross[d] + (1.0 - c) * dot * axis[d];
  }
}

struct Built {
  mesh::Mesh mesh;
  mesh::Decomposition d;
  feti::ConstraintMatrix B;
};

/// The two bricks of `spec`, structured or (metisParts > 0) METIS decomposition; tilted:
/// the whole scene rotated by 0.7 rad about (1, 2, 3), so no face is axis-aligned.
Built build(const feti::ConstraintSpec& cs, const mesh::TwoBricksSpec& spec, int metisParts, bool tilted = false) {
  Built b;
  b.mesh = mesh::generateTwoBricks(spec);
  if (tilted) rotate(b.mesh, {1.0, 2.0, 3.0}, 0.7);
  b.d = mesh::buildDecomposition(b.mesh, metisParts ? mesh::metisPartition(b.mesh, metisParts)
                                                    : mesh::structuredPartition(b.mesh, spec));
  b.B = feti::buildConstraintMatrix(b.mesh, b.d, cs, 1);
  return b;
}

/// The decompositions every case runs on: (subdomain grid, METIS parts or 0 = structured).
const std::vector<std::pair<mesh::TwoBricksSpec, int>> kDecompositions = {
    {{{2, 1, 1}, 2}, 0}, {{{4, 2, 2}, 2}, 0}, {{{2, 1, 1}, 3}, 7}};

feti::ConstraintSpec spec(std::vector<std::string> dirichlet, bool contact, bool tangential) {
  feti::ConstraintSpec cs;
  cs.dirichletNodeSets = std::move(dirichlet);
  if (contact) cs.interfaces.push_back({"", "contact_aluminium", "contact_steel", tangential});
  return cs;
}

std::string trace(const std::pair<mesh::TwoBricksSpec, int>& decomposition) {
  const auto& g = decomposition.first.subdomainsPerBrick;
  return std::to_string(g.nx) + "x" + std::to_string(g.ny) + "x" + std::to_string(g.nz) + " H/h " +
         std::to_string(decomposition.first.hOverH) + " metis " + std::to_string(decomposition.second);
}

}  // namespace

TEST(Solvability, clampedBricksHaveNoFreeMotion) {
  for (const auto& dec : kDecompositions)
    for (bool tangential : {true, false}) {
      SCOPED_TRACE(trace(dec) + " tangential " + std::to_string(tangential));
      // Both bricks clamped: no motion free, whether the contact has tangential rows or not.
      const auto clamped = spec({"dirichlet_aluminium", "dirichlet_steel"}, true, tangential);
      const auto both = build(clamped, dec.first, dec.second);
      EXPECT_TRUE(feti::freeRigidMotions(both.mesh, both.d, both.B).empty());
      EXPECT_NO_THROW(feti::requireRestrainedBodies(both.mesh, both.d, both.B));
      // Both clamped and no contact at all: still none.
      const auto apart = build(spec(clamped.dirichletNodeSets, false, tangential), dec.first, dec.second);
      EXPECT_TRUE(feti::freeRigidMotions(apart.mesh, apart.d, apart.B).empty());
    }
  // Only the aluminium clamped, but the contact has tangential rows (friction or bonded):
  // the steel brick is held through the contact.
  for (const auto& dec : kDecompositions) {
    SCOPED_TRACE(trace(dec));
    const auto held = build(spec({"dirichlet_aluminium"}, true, true), dec.first, dec.second);
    EXPECT_TRUE(feti::freeRigidMotions(held.mesh, held.d, held.B).empty());
  }
}

TEST(Solvability, frictionlessContactLeavesTheSlidingModesFree) {
  // The aluminium clamped, the steel held only by normal rows on the flat face z = 10:
  // it may slide in x and y and spin about z.
  for (const auto& dec : kDecompositions) {
    SCOPED_TRACE(trace(dec));
    const auto b = build(spec({"dirichlet_aluminium"}, true, false), dec.first, dec.second);
    ASSERT_EQ(b.mesh.blocks.at(1).name, "steel");
    const auto free = feti::freeRigidMotions(b.mesh, b.d, b.B);
    ASSERT_EQ(free.size(), 3u);
    const char* expected[3] = {"body \"steel\": translation x", "body \"steel\": translation y",
                               "body \"steel\": rotation about z"};
    for (size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(free[i].bodies, std::vector<int>{1});
      EXPECT_EQ(free[i].description, expected[i]);
    }
  }
}

TEST(Solvability, unconstrainedBricksHaveTwelveFreeMotions) {
  // No Dirichlet row and no contact: B has only gluing rows, which every rigid motion of a
  // body satisfies, so all 6 modes of both bodies are free (each one mode of one body).
  for (const auto& dec : kDecompositions) {
    SCOPED_TRACE(trace(dec));
    const auto b = build(spec({}, false, true), dec.first, dec.second);
    ASSERT_GT(b.B.numRows, 0);
    const auto free = feti::freeRigidMotions(b.mesh, b.d, b.B);
    ASSERT_EQ(free.size(), 12u);
    const char* modes[6] = {"translation x",    "translation y",    "translation z",
                            "rotation about x", "rotation about y", "rotation about z"};
    for (size_t i = 0; i < 12; ++i) {
      const int body = static_cast<int>(i / 6);
      EXPECT_EQ(free[i].bodies, std::vector<int>{body});
      EXPECT_EQ(free[i].description, "body \"" + b.mesh.blocks[body].name + "\": " + modes[i % 6]);
    }
  }
}

TEST(Solvability, contactWithoutDirichletLeavesTheJointMotionsFree) {
  for (const auto& dec : kDecompositions) {
    SCOPED_TRACE(trace(dec));
    // Tangential rows tie the bricks together: the 6 motions of the pair are free, each one
    // a motion of both bodies.
    const auto tied = build(spec({}, true, true), dec.first, dec.second);
    const auto joint = feti::freeRigidMotions(tied.mesh, tied.d, tied.B);
    ASSERT_EQ(joint.size(), 6u);
    for (const auto& m : joint) {
      EXPECT_EQ(m.bodies, (std::vector<int>{0, 1}));
      EXPECT_NE(m.description.find("together with"), std::string::npos) << m.description;
    }
    // Normal rows only: those 6, plus the steel sliding on the aluminium (3).
    const auto sliding = build(spec({}, true, false), dec.first, dec.second);
    EXPECT_EQ(feti::freeRigidMotions(sliding.mesh, sliding.d, sliding.B).size(), 9u);
  }
}

TEST(Solvability, aTiltedSceneGivesTheSameCounts) {
  // Rotated off the axes, the free motions of the sliding steel brick are combinations of
  // its modes (translations in the tilted contact plane, rotation about its normal): the
  // counts and bodies do not change, and each description names only the steel.
  for (const auto& dec : kDecompositions) {
    SCOPED_TRACE(trace(dec));
    const auto sliding = build(spec({"dirichlet_aluminium"}, true, false), dec.first, dec.second, true);
    const auto free = feti::freeRigidMotions(sliding.mesh, sliding.d, sliding.B);
    ASSERT_EQ(free.size(), 3u);
    for (const auto& m : free) {
      EXPECT_EQ(m.bodies, std::vector<int>{1});
      EXPECT_EQ(m.description.find("aluminium"), std::string::npos) << m.description;
      const bool combination =
          m.description.find(" + ") != std::string::npos || m.description.find(" - ") != std::string::npos;
      EXPECT_TRUE(combination) << m.description;
    }
    if (dec.second == 0 && dec.first.subdomainsPerBrick.nx == 2)
      for (const auto& m : free) std::cout << m.description << "\n";
    const auto held = build(spec({"dirichlet_aluminium"}, true, true), dec.first, dec.second, true);
    EXPECT_TRUE(feti::freeRigidMotions(held.mesh, held.d, held.B).empty());
    const auto apart = build(spec({}, false, true), dec.first, dec.second, true);
    EXPECT_EQ(feti::freeRigidMotions(apart.mesh, apart.d, apart.B).size(), 12u);
  }
}

TEST(Solvability, inputErrorNamesTheBodyAndTheRemedy) {
  const auto b = build(spec({"dirichlet_aluminium"}, true, false), {{2, 1, 1}, 2}, 0);
  try {
    feti::requireRestrainedBodies(b.mesh, b.d, b.B);
    FAIL() << "no InputError for a steel brick free to slide";
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    std::cout << what << "\n";
    EXPECT_NE(what.find("3 rigid motions"), std::string::npos);
    EXPECT_NE(what.find("body \"steel\": translation x"), std::string::npos);
    EXPECT_NE(what.find("body \"steel\": rotation about z"), std::string::npos);
    EXPECT_EQ(what.find("aluminium"), std::string::npos);  // the held body is not blamed
    EXPECT_NE(what.find("Dirichlet Node Sets"), std::string::npos);
    EXPECT_NE(what.find("Friction Model"), std::string::npos);
    EXPECT_NE(what.find("contact surface"), std::string::npos);
  }
  // A B that does not belong to the decomposition is an internal error, not an input one.
  auto wrong = b;
  wrong.B.blocks.pop_back();
  EXPECT_THROW(feti::freeRigidMotions(wrong.mesh, wrong.d, wrong.B), std::invalid_argument);
}


TEST(Solvability, eachRankItsRowsGivesTheAnswerOfAllRows) {
  // With a communicator every rank forms the products of the rows it owns (B split for that
  // many ranks) and the Gram matrix is summed reproducibly: every rank reports what one
  // process with all rows reports, on the tilted sliding scene (combinations of modes whose
  // coefficients are printed) and on a held one.
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const Teuchos::MpiComm<int> world(MPI_COMM_WORLD);
  for (const auto& dec : kDecompositions) {
    SCOPED_TRACE(trace(dec));
    for (const auto& cs : {spec({"dirichlet_aluminium"}, true, false), spec({"dirichlet_aluminium"}, true, true)}) {
      Built b = build(cs, dec.first, dec.second, true);
      const auto alone = feti::freeRigidMotions(b.mesh, b.d, b.B);
      b.B = feti::buildConstraintMatrix(b.mesh, b.d, cs, size);
      const auto spread = feti::freeRigidMotions(b.mesh, b.d, b.B, &world);
      ASSERT_EQ(spread.size(), alone.size());
      for (size_t i = 0; i < alone.size(); ++i) EXPECT_EQ(spread[i].description, alone[i].description);
    }
  }
}
