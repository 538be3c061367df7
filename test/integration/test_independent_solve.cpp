// Accuracy against an independent solver of the same discrete problem: frictionless
// node-to-node contact of the two bricks solved on the undecomposed mesh by a primal-dual
// active set method with Amesos2 (test/common/DirectSolve.cpp) — no FETI, no QP code — versus
// T-FETI + SMALSE-M + MPGP at epsilon = 1e-10. Also prints the relative error (doc/accuracy.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "ContactScene.hpp"
#include "DirectSolve.hpp"

using namespace tribos;

TEST(independentSolve, frictionlessContactMatchesActiveSetDirectSolve) {
  for (const auto& cell : std::vector<std::vector<std::string>>{{"Mesh/Subdomains Per Brick=2x1x1", "Mesh/H Over h=2"},
                                                                {"Mesh/Subdomains Per Brick=2x1x1", "Mesh/H Over h=3"},
                                                                {"Mesh/Subdomains Per Brick=4x2x2", "Mesh/H Over h=2"}}) {
    SCOPED_TRACE(cell[0] + ", " + cell[1]);
    auto overrides = cell;
    overrides.insert(overrides.end(), {"Contact/Friction Model=None", "Solver/Tolerance=1e-10", "Solver/Verbose=false"});
    const auto s = test::solveContactScene(overrides);
    EXPECT_TRUE(s.result.contact.converged);
    if (test::worldRank() != 0) continue;
    std::vector<LO> fixed;
    for (const auto& name : s.scene.dirichletNodeSets)
      for (LO n : s.scene.mesh.nodeSet(name).nodes) fixed.push_back(n);
    std::vector<std::pair<LO, LO>> pairs;
    for (const auto& c : s.B.contact) pairs.push_back({c.slaveNode, c.masterNode});
    int iterations = 0;
    const auto reference =
        test::directFrictionlessContact(s.scene.mesh, s.scene.materials, s.scene.loads, fixed, pairs, &iterations);
    double diff = 0.0, norm = 0.0;
    for (size_t n = 0; n < reference.size(); ++n)
      for (int c = 0; c < 3; ++c) {
        diff += std::pow(s.result.displacement.value[n][c] - reference[n][c], 2);
        norm += std::pow(reference[n][c], 2);
      }
    const double error = std::sqrt(diff / norm);
    std::printf("  %s %s: relative displacement error %.2e (active-set iterations %d)\n", cell[0].c_str(),
                cell[1].c_str(), error, iterations);
    EXPECT_LT(error, 1e-7);
  }
}
