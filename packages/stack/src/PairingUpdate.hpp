#pragma once
// Internal to stack/: contact decided by the deformed bodies (issue 41). A solve on the pairing
// of the reference mesh can leave a slave node that had no rows (beyond Search Distance: a pin in
// a clearance hole) inside the master body, or a paired node slid past the master nodes of its
// rows (a joint slipping further than an element). After the solve the slave nodes are paired
// again at x + u (feti::ConstraintSpec::pairingDisplacement: the gaps still from the reference,
// so the rows constrain the total displacement as before); where that finds either case, the
// problem is built on the new pairing and solved again, up to Solver/Pairing Updates times.
// Where it finds neither, the first result stands bit for bit.
#include <mpi.h>

#include <array>
#include <vector>

#include "tribos/stack/ContactSolve.hpp"

namespace tribos::stack {

/// One solve on one pairing (ContactSolve.cpp): solveContactScene without pairing updates.
ContactSolveResult solveOnePairing(const Scene& scene, std::vector<fem::SubdomainSystem> owned,
                                   const feti::ConstraintMatrix& B, const Teuchos::ParameterList& tribos, MPI_Comm comm,
                                   core::Stopwatch runStart, const StepObserver& afterStep = {});

}  // namespace tribos::stack
