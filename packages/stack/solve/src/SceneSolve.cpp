#include "tribos/stack/SceneSolve.hpp"

#include <Teuchos_ParameterList.hpp>

namespace tribos::stack {

bool isContactProblem(const Scene& scene) {
  if (!scene.pretensions.empty()) return true;  // solved as a history (Pretension.hpp)
  for (const auto& one : scene.contacts)
    if (!one.law.tiesSurfaces()) return true;
  return false;
}

std::string describeSolverChain(const Scene& scene, const Teuchos::ParameterList& tribos) {
  if (isContactProblem(scene)) return describeContactChain(scene, tribos);
  return "linear T-FETI (projected CG, preconditioner " + tribos.sublist("FETI").get<std::string>("Preconditioner") +
         ")";
}

SceneSolveResult solveScene(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                            const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos, MPI_Comm comm,
                            core::Stopwatch runStart, const StepObserver& afterStep) {
  SceneSolveResult result;
  result.contactProblem = isContactProblem(scene);
  result.chain = describeSolverChain(scene, tribos);
  const auto& solver = tribos.sublist("Solver");
  if (result.contactProblem) {
    result.contactSolve = solveContactScene(scene, std::move(owned), B, tribos, comm, runStart, afterStep);
  } else {
    result.linear = solveLinearFeti(scene, std::move(owned), B, tribos.sublist("FETI"), solver.get<double>("Tolerance"),
                                    comm, solver.get<double>("Max Seconds"), runStart);
  }
  return result;
}

}  // namespace tribos::stack
