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

#include <string>
#include <vector>

#include "tribos/stack/Scene.hpp"

namespace tribos::contact {
struct FrictionSettings;
}

namespace tribos::stack {

/// The complete valid list, built once.
Teuchos::RCP<const Teuchos::ParameterList> sceneValidParameters();

/// The contact interfaces of a validated "Contact" list: each Contact/<name> sublist, its
/// parameters not given there taken from the flat list; or, without sublists, the flat
/// list's one interface (none when its side sets are empty). Throws core::InputError naming
/// `source` and the list when surfaces are missing or given both ways. The side sets are
/// checked against the mesh by buildScene.
std::vector<ContactInterface> readContactInterfaces(const Teuchos::ParameterList& contactList,
                                                    const std::string& source);

/// The friction settings of a validated "Contact" list: the fixed point's from the list, and
/// the law of each of `interfaces` (readContactInterfaces's, read once per run into the
/// scene; the flat law when there is none); the progress callback left empty.
contact::FrictionSettings readFrictionParameters(const std::vector<ContactInterface>& interfaces,
                                                 const Teuchos::ParameterList& contactList);

}  // namespace tribos::stack
