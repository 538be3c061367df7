#pragma once
/// \file SceneParameters.hpp
/// The valid parameter list of a Tribos scene (top-level list "Tribos"): every parameter
/// with its default and documentation. The driver validates the user's XML against it;
/// `tribos --list-parameters` prints it. Include only where a ParameterList is needed.
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_RCP.hpp>

namespace tribos::stack {

/// The complete valid list, built once.
Teuchos::RCP<const Teuchos::ParameterList> sceneValidParameters();

}  // namespace tribos::stack
