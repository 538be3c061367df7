#pragma once
/// \file SceneSolve.hpp
/// The one place that builds the solver stack of a scene from its validated list: linear
/// T-FETI (projected CG) for scenes without contact or with bonded contact, T-FETI +
/// SMALSE-M + MPGP (+ the Coulomb fixed point) for contact scenes; the result as one object
/// whatever was built (the driver's report reads it, stack/RunReport.hpp).
#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "tribos/core/Timer.hpp"
#include "tribos/stack/ContactSolve.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"

namespace tribos::stack {

/// Whether the scene is solved as a contact problem (a contact pair that is not bonded).
bool isContactProblem(const Scene& scene);

/// The chain solveScene builds, in words.
std::string describeSolverChain(const Scene& scene, const Teuchos::ParameterList& tribos);

/// Builds the stack the scene needs and solves it. `owned`: this rank's assembled systems,
/// consumed. Solver/Max Seconds counts from `runStart`. `afterStep`: called after each
/// converged step of a load history but the last (StepObserver). Collective over `comm`.
SceneSolveResult solveScene(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                            const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos, MPI_Comm comm,
                            core::Stopwatch runStart, const StepObserver& afterStep = {});

}  // namespace tribos::stack
