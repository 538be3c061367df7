#pragma once
/// \file Parameters.hpp
/// Validation of user parameter lists against a component's valid list. Keeps the
/// Teuchos headers out of this header: callers that build lists include them themselves.
#include <string>

namespace Teuchos {
class ParameterList;
}

namespace tribos::core {

/// Validates `user` against `valid` (names, types, validators) to `depth` levels of
/// sublists and fills in defaults. Any unknown or mistyped name throws InputError whose
/// message starts with `where` (e.g. the XML file and the sublist path) and lists the
/// valid names with their documentation.
void validateAndSetDefaults(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                            const std::string& where, int depth = 1000);

/// One line per parameter: "Path/Name  (type, default value)  doc", recursing into sublists.
std::string describeParameters(const Teuchos::ParameterList& valid, const std::string& prefix = "");

}  // namespace tribos::core
