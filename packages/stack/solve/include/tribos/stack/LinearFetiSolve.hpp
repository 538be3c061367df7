#pragma once
/// \file LinearFetiSolve.hpp
/// The scene -> T-FETI wiring for problems without inequality constraints: no contact, or
/// contact rows treated as equalities ("Bonded"). Builds B, the dual operators, solves by
/// projected CG and recovers the displacements of the user's global mesh.
#include <mpi.h>

#include <array>
#include <vector>

#include "tribos/core/Timer.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/stack/SolveResults.hpp"
#include "tribos/stack/Scene.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

/// B's description for the scene: its Dirichlet sets, the displacement conditions that hold in
/// step 1, its contact pair (tangential rows unless the friction model is "None").
feti::ConstraintSpec constraintSpec(const Scene& scene);

/// Solves the linear T-FETI problem. `owned` are this rank's assembled subdomain systems
/// (stack::assembleOwnedSubdomains), consumed. `feti` is the validated "FETI" sublist.
/// `maxSeconds` > 0: wall-clock budget (Solver/Max Seconds) from `runStart` (the start of the
/// run; by default this call), the factorisation included. Collective over `comm`.
LinearFetiResult solveLinearFeti(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                 const feti::ConstraintMatrix& B, const Teuchos::ParameterList& feti,
                                 double tolerance, MPI_Comm comm, double maxSeconds = 0.0,
                                 core::Stopwatch runStart = {});

}  // namespace tribos::stack
