#pragma once
/// \file CarriedMultipliers.hpp
/// The multipliers of one pairing's B carried to another's (a pairing on the deformed bodies,
/// issue 41): the warm start of the solve on the new rows, so that a second pairing pass costs a
/// warm solve, not a cold one. Gluing and Dirichlet rows are the same rows in both (the same
/// constraints, paired again): their multipliers are carried by their order. A contact node's
/// rows carry its nodal force: the force vector of its rows in `from` (force = scale lambda
/// along nu, t1, t2) is expressed in the frame and scales of its rows in `to`. A slave node
/// paired only in `to` starts at zero. Only a start: the solve on `to` is judged by its own KKT
/// gate as any other.
#include <mpi.h>

#include <vector>

#include "tribos/feti/ConstraintMatrix.hpp"

namespace tribos::feti {

/// lambda on this rank's rows of `to`, from `lambdaOfFrom` on this rank's rows of `from`.
/// Where the two do not have the same number of gluing and of Dirichlet rows (not a pairing of
/// the same constraints), those rows start at zero. Collective over `comm` (the multipliers of
/// `from` are gathered on every rank: one dual vector).
std::vector<double> carryMultipliers(const ConstraintMatrix& from, const std::vector<double>& lambdaOfFrom,
                                     const ConstraintMatrix& to, MPI_Comm comm);

/// lambda on this rank's rows of `B` from the contact forces per global node along each contact
/// node's normal, t1 and t2 (a result's contact_normal, contact_t1, contact_t2: a restart's warm
/// start); the gluing and Dirichlet rows, which a result does not hold, start at zero.
std::vector<double> multipliersFromNodalForces(const ConstraintMatrix& B, const std::vector<double>& normal,
                                               const std::vector<double>& t1, const std::vector<double>& t2,
                                               int rank);

}  // namespace tribos::feti
