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
/// valid names with their documentation. A valid sublist that contains only a sublist named
/// "*" accepts user sublists of any name, each validated against "*" (materials per body,
/// loads); no defaults are filled in at that level. Defaults filled in are marked
/// (Teuchos::ParameterEntry::isDefault(); givenByUser tells them apart).
void validateAndSetDefaults(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                            const std::string& where, int depth = 1000);

/// Whether `list` holds `name` as the user gave it (by the scene or a --set), not as a default
/// validateAndSetDefaults filled in.
bool givenByUser(const Teuchos::ParameterList& list, const std::string& name);

/// Two lines per parameter, "Path/Name  (type, default D, range R)" and its documentation
/// indented, the parameters of a list before its sublists (`tribos --list-parameters`;
/// doc/tools/make_parameters_md.sh turns it into doc/parameters.md). The range is the
/// validator's (core/Validators.hpp); a NaN default means "no default: give it".
std::string describeParameters(const Teuchos::ParameterList& valid, const std::string& prefix = "");

}  // namespace tribos::core

namespace tribos::core {

/// Applies a command-line override "Sublist/.../Name=value" to `user`. The type of the
/// value is the type of that parameter in `valid` (int, double, bool, string,
/// Array(double) as "{1, 0, 20}", Array(string) as "{a, b}"); user-named sublists under a
/// "*" template (see validateAndSetDefaults) are accepted. Throws InputError naming the
/// override when the path is unknown (listing the valid names) or the value does not parse.
void applyOverride(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& assignment);

}  // namespace tribos::core
