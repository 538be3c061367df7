#pragma once
/// \file ContactFields.hpp
/// The contact results on the user's mesh: nodal fields on the slave surfaces and each
/// interface's resultants, from the contact nodes' forces, statuses and openings, whichever
/// solver found them (the contact solve, or linear T-FETI for scenes whose interfaces are all
/// bonded).
#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "tribos/contact/FrictionModel.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::contact {
struct ContactNodeResult;  // contact/ContactSolver.hpp (heavy: TotalFeti); callers include it
}

namespace tribos::stack {

/// One contact interface's resultants and extremes (rank 0; ContactFields::interfaces).
struct InterfaceResult {
  std::string name;       ///< the Contact/<name> sublist ("" for the flat Contact list)
  std::string surfaces;   ///< "slave set -> master set"
  contact::FrictionLaw law;
  double normalForce = 0.0;            ///< sum of its normal nodal forces
  std::array<double, 3> force{};       ///< sum of its nodal contact forces in x, y, z (on the master)
  double frictionForce = 0.0;          ///< sum of the lengths of its tangential nodal forces
  std::array<int, 3> counts{0, 0, 0};  ///< its contact nodes: no contact, stick, slip
  double peakPressure = 0.0, largestOpening = 0.0, largestOverlap = 0.0;
  /// Friction work: sum over its slipping nodes of the tangential force times the slip (this
  /// solve, a load step's increment in a history), and so far over the history.
  double stepDissipation = 0.0, dissipatedEnergy = 0.0;
};

/// The sum of |t1| + |t2| + accumulated slip over the nodes, in node order: written with every
/// step of a result (global variable contact_memory_sum) and compared by a restart, so that a
/// file cut inside a step, whose missing values read as zeros, is refused (issue 44).
double contactMemorySum(const std::vector<double>& tangentialT1, const std::vector<double>& tangentialT2,
                        const std::vector<double>& accumulatedSlip);

struct ContactFields {
  /// Per global node (rank 0), zero off the slave surface: force of the slave body on the
  /// master body in (nu, t1, t2), status (0 none, 1 stick, 2 slip), pressure (normal force
  /// per tributary area).
  std::vector<double> contactNormal, contactT1, contactT2, contactStatus, contactPressure;
  /// Per global node (rank 0), zero off the slave surface: the initial signed gap d along nu
  /// (negative: overlap), the gap after deformation (ContactNodeResult::opening), the
  /// normal nu, and the master node with the largest weight (1-based id; 0 off the surface).
  std::vector<double> contactGap, contactOpening, contactNx, contactNy, contactNz, contactMaster;
  /// Per global node (rank 0), zero off the slave surface: the tangential relative displacement
  /// (u_slave - u_master along t1, t2) in this solve (a load step: its increment), the total so
  /// far, and the accumulated slip (sum of the increments' lengths where the node slipped).
  std::vector<double> contactSlipT1, contactSlipT2, contactTangentialT1, contactTangentialT2, contactAccumulatedSlip;
  double dissipatedEnergy = 0.0;  ///< over every interface, so far (rank 0)
  double totalNormalForce = 0.0;    ///< sum of the normal nodal forces (rank 0)
  std::array<double, 3> totalContactForce{};  ///< sum of nodal contact forces in x, y, z (rank 0)
  std::vector<InterfaceResult> interfaces;  ///< per scene interface, in the scene's order (rank 0)
};

/// One per-node field of ContactFields: its name in the Exodus result and its member.
struct ContactNodalField {
  const char* name;
  std::vector<double> ContactFields::*values;
};
/// Every per-node contact field, in the order the result writes them: the one list the gather,
/// the result writer, the release of a written step and the restart reader take their fields
/// and names from (a new field is a member and a line here).
extern const std::array<ContactNodalField, 16> kContactNodalFields;
/// The result's name of one of them (kContactNodalFields).
const char* nameOf(std::vector<double> ContactFields::*values);

/// Fills `out` on rank 0 from the contact nodes whose rows this rank owns (`nodes`); the
/// geometry (gap, normal, master) comes from B on every rank. Every rank gets the interfaces'
/// names and laws, rank 0 their sums. Collective over `comm`.
void gatherContactFields(const Scene& scene, const feti::ConstraintMatrix& B,
                         const std::vector<contact::ContactNodeResult>& nodes, MPI_Comm comm, ContactFields& out);

/// A load step after `previous`: the totals so far (tangential displacement, accumulated slip,
/// dissipated energy) are the previous step's plus this one's (rank 0).
void addEarlierSteps(const ContactFields& previous, ContactFields& now);

/// The slip fields of the nodes of frictionless interfaces (no tangential rows, so the solver
/// reports no tangential relative displacement), from the kinematics (rank 0): the relative
/// displacement of the node's row, u_slave - sum_j w_j u_master_j, along t1 and t2 (this state
/// less `before`'s totals where a history has them: the increment, as gatherContactFields's),
/// and the accumulated slip where the node slips. `displacement`: per global node.
void addKinematicSlip(const Scene& scene, const feti::ConstraintMatrix& B,
                      const std::vector<std::array<double, 3>>& displacement, const ContactFields* before,
                      ContactFields& out);

/// The friction of the tangential components whose slip is prescribed (feti::ContactNode::
/// slipPrescribed: the slave node and its nearest master node held along t_j at different
/// values, so no row): where this state moves the slave against that master along t_j (the
/// increment since `before`), a node in contact slides, and the law's sliding force (F_j times
/// its normal force) acts against the slip on the held components of the two nodes (the free
/// tangential row carries none: contact::DualContactProblem). Added to the contact fields, the
/// interface sums and `reaction` (the supports carry it); rank 0 (`displacement`, `reaction`:
/// per global node). Returns the change of the status counts (no contact, stick, slip) it made.
std::array<int, 3> addPrescribedSlipFriction(const Scene& scene, const feti::ConstraintMatrix& B,
                                             const std::vector<std::array<double, 3>>& displacement,
                                             const ContactFields* before, std::vector<std::array<double, 3>>& reaction,
                                             ContactFields& out);

/// The contact nodes of this rank's rows of a bonded (tied) solve: forces rowScale lambda,
/// status stick, opening -(B u - c)_N / rowScale. `ownedLambda` and `ownedResidual` (B u - c)
/// hold this rank's rows [B.firstRowOfRank[rank], B.firstRowOfRank[rank + 1]).
std::vector<contact::ContactNodeResult> tiedNodeResults(const feti::ConstraintMatrix& B, int rank,
                                                        const std::vector<double>& ownedLambda,
                                                        const std::vector<double>& ownedResidual);

}  // namespace tribos::stack
