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
#include "tribos/stack/ContactFields.hpp"
#include "tribos/stack/Scene.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

/// B's description for the scene: its Dirichlet sets, the displacement conditions that hold in
/// step 1, its contact pair (tangential rows unless the friction model is "None").
feti::ConstraintSpec constraintSpec(const Scene& scene);

/// The linear solve; its contact fields (ContactFields) where the scene's interfaces are all
/// bonded (tied), empty without contact.
struct LinearFetiResult : ContactFields {
  bool converged = false;
  std::string message;              ///< "converged", or which limit ended the iterations
  int iterations = 0;
  long long fApplications = 0;
  long long factorNonzeros = 0;       ///< feti::TotalFeti::factorNonzeros
  double bytesPerFApplication = 0.0;  ///< feti::TotalFeti::bytesPerFApplication
  double relativeResidual = 0.0;    ///< ||P r|| / ||P h||
  double conditionEstimate = 0.0;   ///< Lanczos estimate of kappa(P F P | Ker G) (preconditioned)
  double equilibriumResidual = 0.0; ///< max ||K_s u_s - f_s + B_s^T lambda_s||_inf / ||f||_inf
  double constraintResidual = 0.0;  ///< ||B u - c|| / (||B|| ||u||) (= ||B u - c|| / ||u||, rows unit norm)
  double factorizationSeconds = 0.0, solveSeconds = 0.0;
  /// Displacement of every global node (mean over its subdomain copies); rank 0 only.
  std::vector<std::array<double, 3>> displacement;
  /// Largest difference between two copies of a node (gluing error), rank 0 only.
  double maxCopyJump = 0.0;
  /// Reaction force per global node (gatherReactions), rank 0 only.
  std::vector<std::array<double, 3>> reaction;
  std::array<double, 3> appliedLoad{};  ///< sum of the nodal loads (every rank)
  double appliedLoadMagnitude = 0.0;    ///< sum of their lengths (loadMagnitude)
};

/// Solves the linear T-FETI problem. `owned` are this rank's assembled subdomain systems
/// (stack::assembleOwnedSubdomains), consumed. `feti` is the validated "FETI" sublist.
/// `maxSeconds` > 0: wall-clock budget (Solver/Max Seconds) from `runStart` (the start of the
/// run; by default this call), the factorisation included. Collective over `comm`.
LinearFetiResult solveLinearFeti(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                 const feti::ConstraintMatrix& B, const Teuchos::ParameterList& feti,
                                 double tolerance, MPI_Comm comm, double maxSeconds = 0.0,
                                 core::Stopwatch runStart = {});

}  // namespace tribos::stack
