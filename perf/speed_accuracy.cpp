// Speed against accuracy: for a sequence of tolerances epsilon, the F applications, solve
// time and error of the displacement
//  - frictionless: against the independent active-set solve of the undecomposed problem;
//  - Coulomb F = 0.3: against the same scene solved at epsilon = 1e-11;
// and the KKT residuals. Prints a CSV (doc/speed_accuracy.md).
// Usage: build/bin/tribos_speed_accuracy [grid] [H/h]
#include <mpi.h>

#include <Tpetra_Core.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "ContactScene.hpp"
#include "DirectSolve.hpp"
#include "tribos/core/Parallel.hpp"

using namespace tribos;

namespace {
double relativeError(const std::vector<std::array<double, 3>>& a, const std::vector<std::array<double, 3>>& b) {
  double diff = 0.0, norm = 0.0;
  for (size_t n = 0; n < a.size(); ++n)
    for (int c = 0; c < 3; ++c) {
      diff += std::pow(a[n][c] - b[n][c], 2);
      norm += std::pow(b[n][c], 2);
    }
  return std::sqrt(diff / norm);
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  {
    Tpetra::ScopeGuard tpetra(&argc, &argv);
    core::warmUpKokkosForThreads();
    const std::string grid = argc > 1 ? argv[1] : "4x2x2", h = argc > 2 ? argv[2] : "3";
    std::vector<std::string> cell = {"Mesh/Subdomains Per Brick=" + grid, "Mesh/H Over h=" + h,
                                     "Solver/Verbose=false"};
    // Further arguments: overrides "Path=value" of a solver variant (e.g. FETI/Preconditioner=None).
    for (int i = 3; i < argc; ++i) cell.push_back(argv[i]);
    std::printf("model,epsilon,outer,pfp_applications,solve_s,relative_error,kkt_equilibrium,kkt_complementarity,kkt_friction\n");
    for (const std::string model : {"None", "Coulomb"}) {
      auto base = cell;
      base.push_back("Contact/Friction Model=" + model);
      std::vector<std::array<double, 3>> reference;
      if (model == "None") {
        const auto s = test::solveContactScene(base);
        std::vector<LO> fixed;
        for (const auto& name : s.scene.dirichletNodeSets)
          for (LO n : s.scene.mesh.nodeSet(name).nodes) fixed.push_back(n);
        std::vector<std::pair<LO, LO>> pairs;
        for (const auto& c : s.B.contact) pairs.push_back({c.slaveNode, c.masterNode});
        reference = test::directFrictionlessContact(s.scene.mesh, s.scene.materials, s.scene.loads, fixed, pairs);
      } else {
        auto tight = base;
        tight.push_back("Solver/Tolerance=1e-11");
        reference = test::solveContactScene(tight).result.displacement.value;
      }
      for (double eps : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9}) {
        auto o = base;
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, "Solver/Tolerance=%g", eps);
        o.push_back(buffer);
        const auto s = test::solveContactScene(o);
        const auto& r = s.result.contact;
        std::printf("%s,%g,%d,%lld,%.3f,%.2e,%.1e,%.1e,%.1e\n", model.c_str(), eps, r.counters.outerIterations,
                    r.counters.operatorApplications, s.result.solveSeconds,
                    relativeError(s.result.displacement.value, reference), r.kkt.equilibrium, r.kkt.complementarity,
                    r.kkt.frictionAdmissibility);
        std::fflush(stdout);
      }
    }
  }
  MPI_Finalize();
  return 0;
}
