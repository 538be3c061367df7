#pragma once
/// \file SolverParameters.hpp
/// The parameters of SMALSE-M and MPGP, declared once: src/SolverParameters.cpp holds one
/// table line per parameter (name, documentation, validated range) bound to a field of
/// SmalseSettings / MpgpSettings, whose member initialisers are the defaults. The scene's
/// "Solver" list embeds this list, and SmalseM::getValidParameters() returns it.
///
/// A new parameter: a field with its default in the settings struct and one line in the
/// table; nothing else (the scene, `tribos --list-parameters` and doc/parameters.md follow).
#include "tribos/qp/SmalseM.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::qp {

/// Declares into `solver` (a list shaped like the scene's "Solver"): "Tolerance" and "Max
/// Outer Iterations" (SmalseSettings::tolerance, maxOuterIterations), the sublist
/// "SMALSE-M" (the other SmalseSettings) and the sublist "MPGP" (MpgpSettings).
void declareSolverParameters(Teuchos::ParameterList& solver);

/// The settings of a Solver-shaped list that passed core::validateAndSetDefaults against a
/// list that embeds declareSolverParameters(). Parameters absent keep their defaults;
/// entries that are not SMALSE-M's or MPGP's (the scene's "Verbose", ...) are ignored. The
/// callbacks (monitors, progress, stop request) are left empty.
SmalseSettings readSolverParameters(const Teuchos::ParameterList& solver);

}  // namespace tribos::qp
