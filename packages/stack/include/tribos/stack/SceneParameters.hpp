#pragma once
/// \file SceneParameters.hpp
/// The valid parameter list of a Tribos scene (top-level list "Tribos"): every parameter
/// with its default, validated range and documentation. Components that own settings
/// declare their parameters once and the scene embeds them (SMALSE-M and MPGP:
/// qp/SolverParameters.hpp; the friction law: readFrictionParameters). The driver validates
/// the user's XML against it; `tribos --list-parameters` prints it and doc/parameters.md is
/// generated from that. Include only where a ParameterList is needed.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>

namespace tribos::contact {
struct FrictionSettings;
}

namespace tribos::stack {

/// The complete valid list, built once.
Teuchos::RCP<const Teuchos::ParameterList> sceneValidParameters();

/// The friction law of a validated "Contact" list (the progress callback left empty).
contact::FrictionSettings readFrictionParameters(const Teuchos::ParameterList& contactList);

}  // namespace tribos::stack
