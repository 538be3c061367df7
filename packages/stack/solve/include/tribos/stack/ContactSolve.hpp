#pragma once
/// \file ContactSolve.hpp
/// The scene -> contact solver wiring: the solver stack T-FETI (coarse projector, F) ->
/// SMALSE-M -> MPGP -> friction law, built from the parameter list, and the results mapped
/// back onto the user's global mesh.
#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/stack/SolveResults.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

/// Solver settings from the validated "Tribos" list and the scene's interfaces (exposed for
/// tests and perf tools).
contact::FrictionSettings frictionSettings(const Scene& scene, const Teuchos::ParameterList& tribos);
qp::SmalseSettings smalseSettings(const Teuchos::ParameterList& tribos);

/// The chain solveContactScene builds, in words (printed at the start of a run).
std::string describeContactChain(const Scene& scene, const Teuchos::ParameterList& tribos);

/// Solves a contact scene (Friction Model None, Tresca or Coulomb). `owned`: this rank's
/// assembled systems, consumed. Solver/Max Seconds counts from `runStart` (the start of the
/// run; by default this call) and covers the factorisation. With Scene::pairingUpdates, the
/// slave nodes are paired again on the deformed bodies after the solve, and the problem solved
/// again where that changed the pairing (PairingUpdate.cpp). Collective over `comm`.
ContactSolveResult solveContactScene(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                     const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos,
                                     MPI_Comm comm, core::Stopwatch runStart = {}, const StepObserver& afterStep = {});

}  // namespace tribos::stack
