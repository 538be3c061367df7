#pragma once
/// \file XmlParameters.hpp
/// Teuchos XML parameter lists read strictly. Teuchos alone converts values with
/// atoi/atof ("2.5" becomes 2, "garbage" 0, "inf" infinity), keeps the last of two
/// parameters with the same name, recurses once per nesting level (a deeply nested file
/// overflows the stack) and reports errors with its own source file and line. Here every
/// such input is an InputError that names the scene and the parameter path.
#include <string>

#include <Teuchos_RCP.hpp>

namespace Teuchos {
class ParameterList;
}

namespace tribos::core {

/// Deepest element nesting accepted in a scene file (scenes need 4 or 5 levels).
constexpr int kMaxXmlNesting = 64;

/// Parses `text`, a Teuchos XML parameter list, after checking (in this order) that its
/// elements nest at most kMaxXmlNesting deep (before any recursive parsing), that it is
/// well-formed XML, that no list holds two entries of the same name, and that every int,
/// double, bool and array value reads completely as its type (doubles finite). Throws
/// InputError whose message starts with `source` (the file name) and names the parameter
/// path ("Mesh/H Over h") or gives the parser's reason in one line.
Teuchos::RCP<Teuchos::ParameterList> parameterListFromXml(const std::string& text, const std::string& source);

/// The XML of the names and values of `list` (documentation and validators left out: the
/// validators are Tribos's own types, which Teuchos cannot write).
std::string parameterListToXml(const Teuchos::ParameterList& list);

/// The reason in a Teuchos exception's text without its source file, line and throw
/// bookkeeping ("XML parse error at line 1: EOF before start element was terminated").
std::string teuchosReason(const std::string& what);

}  // namespace tribos::core
