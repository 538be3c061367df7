// Subdomain factorisation benchmark (doc/factorization.md): for the subdomains of the paper's
// Table 1 (two bricks, 2x1x1 subdomains per brick, H/h = 2..5: 81..648 dofs) and larger H/h
// for scaling, the time of SubdomainSolver::compute (K_reg = K + rho R_f R_f^T, METIS
// ordering, symbolic + numeric factorisation) and of one K^+ solve, per SparseCholesky,
// best of several repetitions on one thread. A second table shows why CHOLMOD's own OpenMP
// threads are suppressed: raw CHOLMOD supernodal (Debian: 4 threads compiled in) against the
// wrapper on the same matrix.
//   build-feti/bin/tribos_bench_factorization [H/h ...]
#include <cholmod.h>
#include <omp.h>

#include <Kokkos_Core.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "tribos/feti/SparseCholesky.hpp"
#include "tribos/feti/SubdomainSolver.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

template <class F>
double best(int reps, F&& f) {
  double t = 1e30;
  for (int r = 0; r < reps; ++r) {
    const double t0 = now();
    f();
    t = std::min(t, now() - t0);
  }
  return t;
}

/// Raw CHOLMOD supernodal numeric factorisation (AMD order); with Debian's defaults (its own
/// 4 OpenMP threads) or with OpenMP regions made inactive the way the wrapper does it.
double rawCholmodFactor(const fem::CsrMatrix& A, int reps, bool suppressThreads) {
  cholmod_common c;
  cholmod_start(&c);
  c.print = 0;
  c.supernodal = CHOLMOD_SUPERNODAL;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_AMD;
  cholmod_sparse S{};
  S.nrow = S.ncol = A.n;
  S.nzmax = A.values.size();
  S.p = const_cast<LO*>(A.rowPtr.data());
  S.i = const_cast<LO*>(A.colInd.data());
  S.x = const_cast<double*>(A.values.data());
  S.stype = 1;
  S.itype = CHOLMOD_INT;
  S.xtype = CHOLMOD_REAL;
  S.dtype = CHOLMOD_DOUBLE;
  S.sorted = S.packed = 1;
  cholmod_factor* L = cholmod_analyze(&S, &c);
  const int saved = omp_get_max_active_levels();
  if (suppressThreads) omp_set_max_active_levels(0);
  const double t = best(reps, [&] { cholmod_factorize(&S, L, &c); });
  omp_set_max_active_levels(saved);
  cholmod_free_factor(&L, &c);
  cholmod_finish(&c);
  return t;
}
}  // namespace

int main(int argc, char** argv) {
  Kokkos::ScopeGuard kokkos(argc, argv);
  std::vector<int> sizes{2, 3, 4, 5, 8, 10, 12};
  if (argc > 1) {
    sizes.clear();
    for (int i = 1; i < argc; ++i) sizes.push_back(std::atoi(argv[i]));
  }
  const std::vector<fem::Material> materials{{2.792e4, 2.593e4}, {6.360e4, 8.301e4}};
  std::printf("OMP_NUM_THREADS=%d, best of repetitions, seconds\n\n", omp_get_max_threads());
  std::printf("| H/h | dofs | factorization | compute (K_reg+order+factor) | solve (1 rhs) | nnz(L) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  std::vector<fem::CsrMatrix> shifted;
  for (int hOverH : sizes) {
    const mesh::TwoBricksSpec spec{{2, 1, 1}, hOverH};
    const auto mesh = mesh::generateTwoBricks(spec);
    const auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
    const auto system = fem::assembleSubdomain(mesh, d.subdomains[0], materials, {});
    std::vector<std::array<double, 3>> coords;
    for (LO n : d.subdomains[0].nodes) coords.push_back(mesh.coords[n]);
    const int n = system.K.n;
    const int reps = n < 1000 ? 50 : (n < 5000 ? 10 : 4);
    std::vector<double> x(n, 1.0), y(n);
    for (const auto& name : feti::sparseCholeskyNames()) {
      feti::SubdomainSolver solver;
      const double tCompute = best(reps, [&] { solver.compute(system, coords, core::valueOf(feti::kFactorizationNames, name)); });
      const double tSolve = best(reps * 4, [&] { solver.applyGeneralizedInverse(x.data(), y.data()); });
      std::printf("| %d | %d | %s | %.2e | %.2e | %lld |\n", hOverH, n, name.c_str(), tCompute, tSolve,
                  solver.factor().factorNonzeros());
    }
    // K + (max diag) I: SPD, same pattern, for the raw comparison below.
    fem::CsrMatrix A = system.K;
    double rho = 0.0;
    for (LO i = 0; i < n; ++i) rho = std::max(rho, A.at(i, i));
    for (LO i = 0; i < n; ++i)
      for (LO k = A.rowPtr[i]; k < A.rowPtr[i + 1]; ++k)
        if (A.colInd[k] == i) A.values[k] += rho;
    shifted.push_back(std::move(A));
  }
  std::printf("\nCHOLMOD supernodal numeric factorisation of K + rho I (AMD order): Debian's own\n");
  std::printf("OpenMP threads on, as called from outside a parallel region; off (max active levels 0,\n");
  std::printf("what the tribos wrapper does); and the tribos wrapper (METIS order + analysis included):\n\n");
  std::printf("| dofs | threads on | threads off | ratio | tribos CHOLMOD |\n|---|---|---|---|---|\n");
  for (const auto& A : shifted) {
    const int reps = A.n < 1000 ? 50 : (A.n < 5000 ? 10 : 4);
    const double tOn = rawCholmodFactor(A, reps, false), tOff = rawCholmodFactor(A, reps, true);
    auto chol = feti::makeSparseCholesky("CHOLMOD");
    const double tOurs = best(reps, [&] { chol->factorize(A); });
    std::printf("| %d | %.2e | %.2e | %.1f | %.2e |\n", A.n, tOn, tOff, tOn / tOff, tOurs);
  }
  return 0;
}
