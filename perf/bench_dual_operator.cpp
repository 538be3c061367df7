// Cost of the dual operators on one Table 1 cell, inside one process (so that start-up, set-up
// and the noise of whole runs stay out): median seconds of F, P, P F P (as MPGP applies it:
// project, F, project), A_rho = P F P + rho Q with three and with two projections (Arho_3P,
// Arho_2P), the Dirichlet and lumped preconditioners D and L (before projection), G, and the
// coarse solve over `repeats` applications, on the paper's two bricks with their contact rows
// (Coulomb, the default scene).
//
// Usage: build/bin/tribos_bench_dual_operator [grid (10x5x5)] [H/h (5)] [repeats (40)] [only this operation]
//          ["List/Name=value" ...] (further parameters, e.g. "FETI/Coarse Factor Precision=Single")
// Threads: OMP_NUM_THREADS; ranks: mpirun. Prints a CSV header and one line: median wall,
// median process CPU and best wall milliseconds per call of each operation (doc/measurements/performance.md).
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_Vector.hpp>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "tribos/core/Parallel.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/stack/FetiSettings.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

using namespace tribos;

namespace {
double processCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Median wall time of `repeats` calls, each bracketed by barriers so that every rank times
// the same collective call; `cpu` gets the median CPU time of the process (all its threads)
// per call, which neighbours on a shared machine disturb less than the wall time; `best`
// the shortest wall time (the call that no neighbour disturbed: on a shared machine the
// steadiest figure to compare two builds by).
double medianSeconds(int repeats, const std::function<void()>& call, double* cpu = nullptr, double* best = nullptr) {
  std::vector<double> t, c;
  call();  // warm-up: first touch of the overlap buffers, caches
  for (int r = 0; r < repeats; ++r) {
    MPI_Barrier(MPI_COMM_WORLD);
    const double cpuStart = processCpuSeconds();
    const auto start = std::chrono::steady_clock::now();
    call();
    MPI_Barrier(MPI_COMM_WORLD);
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    c.push_back(processCpuSeconds() - cpuStart);
  }
  std::sort(t.begin(), t.end());
  std::sort(c.begin(), c.end());
  if (cpu) *cpu = c[c.size() / 2];
  if (best) *best = t.front();
  return t[t.size() / 2];
}

void fill(feti::DualVector& v) {
  auto data = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
  const auto& map = *v.getMap();
  for (size_t i = 0; i < data.extent(0); ++i) data(i, 0) = std::sin(0.37 * static_cast<double>(map.getGlobalElement(i)));
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  {
    Tpetra::ScopeGuard tpetra(&argc, &argv);
    core::warmUpKokkosForThreads();
    const std::string grid = argc > 1 ? argv[1] : "10x5x5", h = argc > 2 ? argv[2] : "5";
    const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 40;
    int size = 1, rank = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);

    Teuchos::ParameterList params("Tribos");
    const auto valid = stack::sceneValidParameters();
    for (const std::string o : {"Mesh/Subdomains Per Brick=" + grid, "Mesh/H Over h=" + h,
                                std::string("Contact/Slave Side Set=contact_aluminium"),
                                std::string("Contact/Master Side Set=contact_steel")})
      core::applyOverride(params, *valid, o);
    for (int a = 5; a < argc; ++a) core::applyOverride(params, *valid, argv[a]);  // further "List/Name=value"
    core::validateAndSetDefaults(params, *valid, "bench");
    const auto scene = stack::buildScene(params, "bench");
    std::vector<fem::SubdomainSystem> systems;
    stack::assembleOwnedSubdomains(scene, MPI_COMM_WORLD, systems);
    const auto B = feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), size);
    feti::TotalFetiSettings settings = stack::totalFetiSettings(params.sublist("FETI"), false);
    settings.dirichletPreconditioner = true;  // MPGP's default preconditioner in face
    const feti::TotalFeti feti(scene.mesh, scene.decomposition, std::move(systems), B,
                               Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_WORLD)), settings);

    auto x = feti.createDualVector(), y = feti.createDualVector(), t = feti.createDualVector(),
         q = feti.createDualVector();
    fill(*x);
    std::vector<Teuchos::RCP<feti::DualVector>> inputs;
    for (double scale : {1.0, 2.0, 3.0, 4.0, 5.0}) {  // one more than TotalFeti's projection memo (4)
      inputs.push_back(feti.createDualVector());
      inputs.back()->update(scale, *x, 0.0);
    }
    size_t next = 0;
    std::vector<double> coarse;
    feti.applyG(*x, coarse);  // the coarse_solve and Gt calls' input, whichever runs first
    std::vector<std::vector<double>> coarseInputs(3, coarse);
    for (size_t i = 0; i < coarseInputs.size(); ++i)
      for (double& v : coarseInputs[i]) v *= 1.0 + static_cast<double>(i);
    std::vector<double> coarseSolved;
    size_t nextCoarse = 0;
    struct Timing {
      const char* name;
      std::function<void()> call;
      double wall = 0.0, cpu = 0.0, best = 0.0;
    };
    std::vector<Timing> timings = {
        {"F", [&] { feti.applyF(*x, *y); }},
        {"P", [&] { feti.project(*x, *y); }},
        {"PFP",
         [&] {
           feti.project(*x, *t);
           feti.applyF(*t, *y);
           feti.project(*y, *y);
         }},
        // A_rho x = P F P x + rho Q x as SMALSE-M applied it before (Q x by a third projection)
        // and as it does now (P F P x = applyPF(P x), Q x = x - P x).
        {"Arho_3P",
         [&] {
           feti.project(*x, *t);
           feti.applyF(*t, *y);
           feti.project(*y, *y);
           feti.project(*x, *q);
           q->update(1.0, *x, -1.0);
           y->update(10.0, *q, 1.0);
         }},
        {"Arho_2P",
         [&] {
           feti.project(*x, *t);
           feti.applyPF(*t, *y);
           y->update(10.0, *x, -10.0, *t, 1.0);
         }},
        // One projection that the memo cannot answer (five inputs in turn; it keeps four):
        // G x, the coarse solve and G^T a, as most projections of a solve.
        {"P_miss",
         [&] {
           feti::DualVector& in = *inputs[next];
           next = (next + 1) % inputs.size();
           feti.project(in, *y);
         }},
        {"D", [&] { feti.applyDirichlet(*x, *y); }},
        {"L", [&] { feti.applyLumped(*x, *y); }},
        {"G", [&] { feti.applyG(*x, coarse); }},
        // Three right-hand sides in turn (the coarse memo keeps two), each copied before the
        // in-place solve: repeated solves of one vector in place drifted it to memo hits.
        {"coarse_solve",
         [&] {
           coarseSolved = coarseInputs[nextCoarse];
           nextCoarse = (nextCoarse + 1) % coarseInputs.size();
           feti.solveCoarse(coarseSolved);
         }},
        {"Gt", [&] { feti.applyGt(coarse, *y); }},
    };
    // Optional 4th argument: time only the operation of that name (the others print 0), e.g.
    // under perf record.
    const std::string only = argc > 4 ? argv[4] : "";
    for (auto& timing : timings)
      if (only.empty() || only == timing.name) timing.wall = medianSeconds(repeats, timing.call, &timing.cpu, &timing.best);
    if (rank == 0) {
      std::printf("grid,h,ranks,threads,subdomains,n_dual,factor_nonzeros,bytes_per_f_application,projection_bytes,"
                  "preconditioner_bytes,factorization_s");
      for (const auto& timing : timings) std::printf(",%s_ms,%s_cpu_ms,%s_best_ms", timing.name, timing.name, timing.name);
      std::printf("\n%s,%s,%d,%d,%d,%lld,%lld,%.0f,%.0f,%.0f,%.3f", grid.c_str(), h.c_str(), size, core::numThreads(),
                  feti.numCoarse() / 6, static_cast<long long>(feti.numDual()), feti.factorNonzeros(),
                  feti.bytesPerFApplication(), feti.profile().projectionBytes, feti.profile().preconditionerBytes,
                  feti.factorizationSeconds());
      for (const auto& timing : timings) std::printf(",%.3f,%.3f,%.3f", 1e3 * timing.wall, 1e3 * timing.cpu, 1e3 * timing.best);
      std::printf("\n");
    }
  }
  MPI_Finalize();
  return 0;
}
