#pragma once
/// \file SolveResults.hpp
/// What a solve hands to the results and the report, whichever stack ran: a contact solve's
/// (ContactSolveResult: its counts, its load steps' records and states), a linear solve's
/// (LinearFetiResult) and the scene's (SceneSolveResult). Plain data: the solve pipeline
/// (stack/solve/) fills them, the output registry and the report (stack/results/,
/// stack/report/) read them.
#include <array>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/stack/ContactFields.hpp"
#include "tribos/stack/GlobalFields.hpp"

namespace tribos::stack {

/// One SMALSE-M outer iteration as the progress line shows it (the JSON summary's `history`).
struct OuterIterationRecord {
  int outer = 0;                 ///< outer iteration, counted over every SMALSE-M run
  int inner = 0;                 ///< its MPGP iterations
  double projectedGradient = 0.0;  ///< ||g^P|| / ||P h||
  double equalityResidual = 0.0;   ///< ||G mu|| / ||P h|| (scale-free, SmalseSettings)
  double M = 0.0;                  ///< M_k / ||PFP||
  double slipBoundChange = 0.0;    ///< Coulomb: ||g_{k+1} - g_k|| / ||g_k|| (contact::FrictionSettings::progress)
  long long pfpApplications = 0;   ///< applications of PFP so far (power method included)
  double elapsedSeconds = 0.0;     ///< since the solver stack was set up (factorisation included)
};

/// One step of a load history (Load Steps), as the summary's `steps` lists it.
/// A pretension section after a step (Pretension/<name>): the tension it carries and its
/// shortening.
struct SectionState {
  std::string name;
  double force = 0.0, shortening = 0.0;
};

struct LoadStepRecord {
  int step = 0;
  double factor = 1.0;          ///< the ramp k / N (prescribed values; loads without a table)
  double time = 1.0;            ///< Load Steps/Times (default: the ramp)
  std::string label;            ///< "ramp r" (a proportional history), else each factor
  std::vector<std::pair<std::string, double>> factors;  ///< each load's and condition's factor, by name
  bool converged = false;
  /// Its tries (1 + the retries of its cutbacks) and their counts, summed over them.
  int attempts = 1;
  int cutbacks = 0;       ///< halvings of the increment (Load Steps/Max Cutbacks)
  double reached = 0.0;   ///< the load position reached, in steps: k when converged, less where it failed
  int outerIterations = 0;
  long long pfpApplications = 0;
  int fixedPointIterations = 0;
  std::array<int, 3> statusCounts{0, 0, 0};  ///< no contact, stick, slip
  std::string message;
  contact::KktReport kkt;
  double kktTolerance = 0.0;
  std::vector<SectionState> sections;  ///< each pretension section at the step's end
  int sectionSolves = 0;  ///< solves of its tries (more than its tries where a section's Force is iterated)
};

/// What the results show of one solved state: the displacement, reactions, applied load and
/// contact fields on the user's mesh (rank 0's fields; the applied load on every rank).
struct StepResults : ContactFields {
  GlobalDisplacement displacement;  ///< rank 0
  /// Reaction force per global node (gatherReactions), rank 0.
  std::vector<std::array<double, 3>> reaction;
  std::array<double, 3> appliedLoad{};  ///< sum of the nodal loads (every rank)
  double appliedLoadMagnitude = 0.0;    ///< sum of their lengths (loadMagnitude)
};

/// One pairing on the deformed bodies after a solve (Solver/Pairing Updates; stack/solve/src/PairingUpdate.cpp).
struct PairingUpdateRecord {
  int update = 0;              ///< 1, 2, ...
  long long paired = 0;        ///< contact nodes of the pairing on the deformed bodies
  long long newlyInside = 0;   ///< slave nodes without rows that the solve left inside the master
  long long movedOn = 0;       ///< paired slave nodes whose nearest master node is no longer in their rows
  /// Nodes paired on the deformed bodies that slid since (by more than 2.5 % of their master
  /// nodes' spread): paired again where the bodies are now.
  long long relinearised = 0;
  bool solvedAgain = false;    ///< any count > 0: the problem was built and solved again on this pairing
};

/// The contact solve, its counts and times, and the results of its last state (StepResults).
struct ContactSolveResult : StepResults {
  contact::ContactResult contact;   ///< counters, KKT, status counts (node list: this rank's); of the
                                    ///< last step, its counters summed over the steps
  std::vector<LoadStepRecord> steps;  ///< Load Steps: one per step solved (empty for one step)
  /// Load Steps: the results of every step before the last (rank 0's fields; kept until the
  /// results file is written, about 30 doubles per mesh node and step).
  std::vector<StepResults> earlierSteps;
  /// Load Steps/Restart From: the file and its last converged step ("" and 0 without).
  std::string restartFile;
  int restartStep = 0;
  double factorizationSeconds = 0.0, solveSeconds = 0.0;
  long long fApplications = 0;
  feti::OperatorProfile profile;  ///< rank 0's operator times and counts (doc/measurements/coarse_problem.md)
  long long factorNonzeros = 0;       ///< feti::TotalFeti::factorNonzeros
  double bytesPerFApplication = 0.0;  ///< feti::TotalFeti::bytesPerFApplication
  std::string chain;                ///< the solver chain that was built, for verbose output
  std::vector<OuterIterationRecord> history;  ///< one per outer iteration (rank 0)
  /// The check after the solve found a slave node without rows inside the master body
  /// (PenetrationCheck.hpp): not converged, and a pairing on the deformed bodies may hold it.
  bool penetrated = false;
  std::vector<PairingUpdateRecord> pairingUpdates;  ///< one per pairing after a solve
};

/// Called on every rank after each converged step of a load history but the last, with the
/// result so far (ContactSolveResult::steps and earlierSteps up to that step): the driver writes
/// each step into the result file as it comes (drivers/HistoryResults.hpp). Where one is given,
/// the stack releases the nodal fields of every earlier step but the last before it solves the
/// next (releaseWrittenSteps), so that rank 0's memory does not grow with the steps: an observer
/// takes what it needs of a step the first time it sees it. Give it on every rank or on none:
/// the stack's work around it may be collective (HistoryPairing.cpp checks each step's pairing).
using StepObserver = std::function<void(const ContactSolveResult&)>;

/// Frees the per-node fields of a step (displacement, reactions, contact fields), keeping what
/// the summary reports of it (the interfaces' resultants, the dissipated energy, the load).
void releaseNodalFields(StepResults& step);
/// releaseNodalFields on every earlier step of `result` but the last (the state a history
/// continues from).
void releaseWrittenSteps(ContactSolveResult& result);

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

/// The result of a scene's solve, whichever stack ran (SceneSolve.hpp).
struct SceneSolveResult {
  bool contactProblem = false;     ///< which stack ran: contactSolve, else linear
  ContactSolveResult contactSolve;
  LinearFetiResult linear;
  std::string chain;               ///< the solver chain built, in words

  bool converged() const { return contactProblem ? contactSolve.contact.converged : linear.converged; }
  const std::string& message() const { return contactProblem ? contactSolve.contact.message : linear.message; }
  /// Per global node, rank 0 only.
  const std::vector<std::array<double, 3>>& displacement() const {
    return contactProblem ? contactSolve.displacement.value : linear.displacement;
  }
  const std::vector<std::array<double, 3>>& reaction() const {
    return contactProblem ? contactSolve.reaction : linear.reaction;
  }
  const std::array<double, 3>& appliedLoad() const {
    return contactProblem ? contactSolve.appliedLoad : linear.appliedLoad;
  }
  double appliedLoadMagnitude() const {
    return contactProblem ? contactSolve.appliedLoadMagnitude : linear.appliedLoadMagnitude;
  }
};

}  // namespace tribos::stack
