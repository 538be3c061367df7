// Linear T-FETI by Belos's CG against the hand-written projected CG (a measurement for
// issue 29, not a test): the same scene, the same TotalFeti, solved
//   (a) by feti::solveProjectedCg as stack/LinearFetiSolve.cpp calls it;
//   (b) by Belos::PseudoBlockCGSolMgr (one right-hand side: Belos's CGIter) on
//       P F P mu = P h, h = d~ - F lambda_Im, mu_0 = 0, lambda = lambda_Im + mu, with the left
//       preconditioner P D P (D = FETI/Preconditioner; none for "None"), both wrapped as
//       Tpetra::Operators that apply every projection (P F P = applyPF(P x), P D P x =
//       P D (P x)): one projection more per operator and per preconditioner application
//       than (a);
//   (c) as (b) with operators that trust their input to lie in Ker G, as (a) does (A x =
//       applyPF(x), M x = P D x): the same operator work per iteration as (a).
// Stopping test in all three: ||r_k|| <= tol ||P h|| with r_k the recursively updated
// (unpreconditioned) projected residual; (b) and (c) use Belos's implicit residual test with
// "Norm of Initial Residual" scaling and the initial residual given (P h), so that Belos
// applies no operator to mu_0 = 0.
//
// Usage: build/bin/tribos_belos_projected_cg --input SCENE.xml [--set "List/Name=value" ...]
//          [--repeats N (3)] [--verbose]
// Prints per method: CG iterations, F applications, median wall seconds of the solve (from
// lambda_Im to lambda, over N runs interleaved a, b, c), the condition estimate, and the
// relative difference of lambda and of the displacements u to (a).
#include <mpi.h>

#include <BelosLinearProblem.hpp>
#include <BelosPseudoBlockCGSolMgr.hpp>
#include <BelosTpetraAdapter.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>
#include <Tpetra_Vector.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include "tribos/core/InputFiles.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/DualOperators.hpp"
#include "tribos/feti/ProjectedCg.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/stack/FetiSettings.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SceneSolve.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

using namespace tribos;

namespace {
using MV = Tpetra::MultiVector<Scalar, LO, GO>;
using OP = Tpetra::Operator<Scalar, LO, GO>;
using feti::DualVector;

struct Run {
  int iterations = 0;
  long long fApplications = 0;
  double seconds = 0.0, kappa = 0.0, relativeResidual = 0.0;
  bool converged = false;
  Teuchos::RCP<DualVector> lambda;
};

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Run solveHandWritten(const feti::TotalFeti& feti, const feti::ProjectedCgSettings& cg) {
  Run run;
  run.lambda = feti.createDualVector();
  const long long f0 = feti.fApplications();
  MPI_Barrier(MPI_COMM_WORLD);
  const auto start = std::chrono::steady_clock::now();
  const auto result = feti::solveProjectedCg(feti, *run.lambda, cg);
  MPI_Barrier(MPI_COMM_WORLD);
  run.seconds = seconds(start);
  run.iterations = result.iterations;
  run.fApplications = feti.fApplications() - f0;
  run.kappa = result.conditionEstimate;
  run.relativeResidual = result.relativeResidual;
  run.converged = result.converged;
  return run;
}

Run solveBelos(const feti::TotalFeti& feti, const feti::ProjectedCgSettings& cg, bool strict, bool verbose) {
  using feti::DualPreconditioner;
  Run run;
  const long long f0 = feti.fApplications();
  MPI_Barrier(MPI_COMM_WORLD);
  const auto start = std::chrono::steady_clock::now();
  // b = P h, h = d~ - F lambda_Im (one F application, as in (a)).
  auto b = Teuchos::rcp(new MV(feti.dualMap(), 1));
  {
    auto h = b->getVectorNonConst(0);
    feti.applyF(feti.lambdaIm(), *h);
    h->update(1.0, feti.dTilde(), -1.0);
    feti.project(*h, *h);
  }
  auto mu = Teuchos::rcp(new MV(feti.dualMap(), 1));  // mu_0 = 0
  // The library's P F P (feti/DualOperators.hpp: the objects SMALSE-M runs on), or P F alone (x in Ker G already).
  auto A = strict ? feti::makeDualOperator(feti, feti::DualOperatorKind::PFP)
                  : feti::wrapDualOperator(
                        feti, [&feti](const DualVector& x, DualVector& y) { feti.applyPF(x, y); }, "P F");
  auto problem = Teuchos::rcp(new Belos::LinearProblem<Scalar, MV, OP>(A, mu, b));
  if (cg.preconditioner != DualPreconditioner::None) {
    const bool dirichlet = cg.preconditioner == DualPreconditioner::Dirichlet;
    problem->setLeftPrec(strict ? feti::makeDualOperator(feti, feti::DualOperatorKind::PDP)
                                : feti::wrapDualOperator(
                                      feti,
                                      [&feti, dirichlet](const DualVector& x, DualVector& y) {
                                        DualVector s(x.getMap());
                                        if (dirichlet) feti.applyDirichlet(x, s);
                                        else feti.applyLumped(x, s);
                                        feti.project(s, y);
                                      },
                                      "P D"));
  }
  // r_0 = b - A mu_0 = b: given, so that Belos applies no P F P to mu_0 = 0. The
  // preconditioned initial residual is only read by the "Norm of Preconditioned Initial
  // Residual" scaling, not used here: a copy of b stands for it (saves one P D P).
  problem->setInitResVec(b);
  problem->setInitPrecResVec(Teuchos::rcp(new MV(*b, Teuchos::Copy)));
  problem->setProblem();
  auto params = Teuchos::parameterList();
  params->set("Convergence Tolerance", cg.tolerance);
  params->set("Maximum Iterations", cg.maxIterations);
  params->set("Implicit Residual Scaling", std::string("Norm of Initial Residual"));
  params->set("Estimate Condition Number", true);
  params->set("Assert Positive Definiteness", true);
  if (verbose) {
    params->set("Verbosity", Belos::Errors + Belos::Warnings + Belos::FinalSummary + Belos::StatusTestDetails);
    params->set("Output Frequency", 1);
  }
  Belos::PseudoBlockCGSolMgr<Scalar, MV, OP> solver(problem, params);
  const Belos::ReturnType status = solver.solve();
  run.lambda = feti.createDualVector();
  run.lambda->update(1.0, feti.lambdaIm(), 1.0, *mu->getVector(0), 0.0);
  MPI_Barrier(MPI_COMM_WORLD);
  run.seconds = seconds(start);
  run.converged = status == Belos::Converged;
  run.iterations = solver.getNumIters();
  run.fApplications = feti.fApplications() - f0;
  run.kappa = solver.getConditionEstimate();
  run.relativeResidual = solver.achievedTol();
  return run;
}

double relativeDifference(const DualVector& x, const DualVector& ref) {
  DualVector d(ref, Teuchos::Copy);
  d.update(1.0, x, -1.0);
  const double n = ref.norm2();
  return d.norm2() / (n > 0.0 ? n : 1.0);
}

double relativeDifference(const std::vector<std::vector<double>>& u, const std::vector<std::vector<double>>& ref) {
  double local[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};
  for (size_t s = 0; s < ref.size(); ++s)
    for (size_t i = 0; i < ref[s].size(); ++i) {
      local[0] += (u[s][i] - ref[s][i]) * (u[s][i] - ref[s][i]);
      local[1] += ref[s][i] * ref[s][i];
    }
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return std::sqrt(global[0]) / (global[1] > 0.0 ? std::sqrt(global[1]) : 1.0);
}

// A hash of lambda's bits by global id, independent of the rank layout (a sum of mixed
// (id, bits) pairs): equal hashes on 1 and 2 ranks mean bit-identical lambdas.
unsigned long long layoutFreeHash(const DualVector& x) {
  const auto data = x.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *x.getMap();
  unsigned long long local = 0, global = 0;
  for (size_t i = 0; i < data.extent(0); ++i) {
    unsigned long long bits = 0;
    const double v = data(i, 0);
    std::memcpy(&bits, &v, sizeof bits);
    unsigned long long h = bits ^ (0x9e3779b97f4a7c15ULL * static_cast<unsigned long long>(map.getGlobalElement(i) + 1));
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    local += h;
  }
  MPI_Allreduce(&local, &global, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return global;
}

std::vector<std::vector<double>> displacements(const feti::TotalFeti& feti, const DualVector& lambda) {
  return feti.recoverDisplacements(lambda, feti.rigidBodyCoefficients(lambda));
}
}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int status = 0;
  {
    Tpetra::ScopeGuard tpetra(&argc, &argv);
    core::warmUpKokkosForThreads();
    int size = 1, rank = 0;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    std::string input;
    std::vector<std::string> overrides;
    int repeats = 3;
    bool verbose = false;
    for (int a = 1; a < argc; ++a) {
      const std::string arg = argv[a];
      if (arg == "--input" && a + 1 < argc) input = argv[++a];
      else if (arg == "--set" && a + 1 < argc) overrides.push_back(argv[++a]);
      else if (arg == "--repeats" && a + 1 < argc) repeats = std::max(1, std::atoi(argv[++a]));
      else if (arg == "--verbose") verbose = true;
      else {
        if (rank == 0) std::cerr << "usage: " << argv[0] << " --input SCENE.xml [--set List/Name=value ...] [--repeats N]\n";
        MPI_Finalize();
        return 2;
      }
    }
    if (input.empty()) {
      if (rank == 0) std::cerr << "--input SCENE.xml is required\n";
      MPI_Finalize();
      return 2;
    }
    // The scene as the driver reads it: the XML, then each --set validated on its own.
    const auto valid = stack::sceneValidParameters();
    auto list = core::parameterListFromXml(core::readRegularTextFile(input, "the scene file", 1 << 24), input);
    Teuchos::ParameterList params = *list;
    params.setName("Tribos");
    core::validateAndSetDefaults(params, *valid, input);
    for (const auto& o : overrides) {
      core::applyOverride(params, *valid, o);
      core::validateAndSetDefaults(params, *valid, "--set \"" + o + "\"");
    }
    if (const int threads = params.sublist("Parallel").get<int>("Threads"); threads > 0) core::setNumThreads(threads);
    const auto scene = stack::buildScene(params, input, MPI_COMM_WORLD);
    if (stack::isContactProblem(scene)) {
      if (rank == 0) std::cerr << input << ": a contact scene; give a bonded one or no contact\n";
      MPI_Finalize();
      return 2;
    }
    std::vector<fem::SubdomainSystem> systems;
    stack::assembleOwnedSubdomains(scene, MPI_COMM_WORLD, systems);
    const auto B = feti::buildConstraintMatrix(scene.mesh, scene.decomposition, stack::constraintSpec(scene), size);
    const auto& fetiList = params.sublist("FETI");
    // As stack::solveLinearFeti builds the operators and the projected CG's settings.
    const feti::TotalFetiSettings settings = stack::totalFetiSettings(fetiList, true);
    const feti::TotalFeti feti(scene.mesh, scene.decomposition, std::move(systems), B,
                               Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_WORLD)), settings);
    feti::ProjectedCgSettings cg;
    cg.tolerance = params.sublist("Solver").get<double>("Tolerance");
    cg.maxIterations = fetiList.get<int>("Max Iterations");
    cg.preconditioner = stack::dualPreconditioner(fetiList);

    const char* names[3] = {"a:handwritten", "b:belos_PFP_PDP", "c:belos_trusting"};
    std::vector<Run> runs[3];
    for (int r = 0; r < repeats; ++r) {  // interleaved, so that a neighbour's load falls on all three
      runs[0].push_back(solveHandWritten(feti, cg));
      runs[1].push_back(solveBelos(feti, cg, true, verbose && r == 0));
      runs[2].push_back(solveBelos(feti, cg, false, false));
    }
    const auto uRef = displacements(feti, *runs[0].front().lambda);
    if (rank == 0)
      std::printf("scene: %s%s, subdomains %d, dual %lld, tolerance %g, preconditioner %s, ranks %d, threads %d\n",
                  input.c_str(), overrides.empty() ? "" : " (with --set)", feti.numCoarse() / 6,
                  static_cast<long long>(feti.numDual()), cg.tolerance, fetiList.get<std::string>("Preconditioner").c_str(),
                  size, core::numThreads());
    if (rank == 0)
      std::printf("%-17s %5s %6s %10s %10s %12s %10s %10s %s\n", "method", "iters", "F_apps", "median_s", "min_s",
                  "kappa", "d_lambda", "d_u", "rel_res lambda_hash");
    for (int m = 0; m < 3; ++m) {
      std::vector<double> t;
      for (const auto& run : runs[m]) t.push_back(run.seconds);
      std::sort(t.begin(), t.end());
      const Run& first = runs[m].front();
      const double dLambda = relativeDifference(*first.lambda, *runs[0].front().lambda);
      const double dU = relativeDifference(displacements(feti, *first.lambda), uRef);
      const unsigned long long hash = layoutFreeHash(*first.lambda);
      if (!first.converged) status = 1;
      if (rank == 0)
        std::printf("%-17s %5d %6lld %10.4f %10.4f %12.6g %10.2e %10.2e %.3e %016llx%s\n", names[m], first.iterations,
                    first.fApplications, t[t.size() / 2], t.front(), first.kappa, dLambda, dU, first.relativeResidual,
                    hash, first.converged ? "" : " NOT CONVERGED");
    }
  }
  MPI_Finalize();
  return status;
}
