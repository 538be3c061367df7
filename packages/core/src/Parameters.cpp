#include "tribos/core/Parameters.hpp"

#include <Teuchos_ParameterList.hpp>

#include <sstream>

#include "tribos/core/Errors.hpp"

namespace tribos::core {

namespace {
// The names (and docs) that are valid at one level, for error messages.
std::string listValid(const Teuchos::ParameterList& valid) {
  std::ostringstream out;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const auto& entry = valid.entry(it);
    out << "    \"" << valid.name(it) << "\"";
    if (entry.isList()) {
      out << " (sublist)";
    } else {
      out << " (" << entry.getAny(false).typeName() << ", default " << entry.getAny(false) << ")";
    }
    if (!entry.docString().empty()) out << ": " << entry.docString();
    out << "\n";
  }
  return out.str();
}

void validateLevel(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& where, const std::string& path, int depth) {
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    const std::string here = path.empty() ? name : path + "/" + name;
    if (!valid.isParameter(name)) {
      throw InputError(where + ": unknown parameter \"" + here + "\". Valid names in \"" +
                       (path.empty() ? valid.name() : path) + "\" are:\n" + listValid(valid));
    }
    const auto& validEntry = valid.getEntry(name);
    const auto& userEntry = user.entry(it);
    if (validEntry.isList() != userEntry.isList()) {
      throw InputError(where + ": \"" + here + "\" must be " +
                       (validEntry.isList() ? "a sublist" : "a parameter, not a sublist"));
    }
    if (validEntry.isList()) {
      if (depth > 0)
        validateLevel(user.sublist(name), valid.sublist(name), where, here, depth - 1);
      continue;
    }
    if (userEntry.getAny(false).type() != validEntry.getAny(false).type() &&
        validEntry.validator().is_null()) {
      throw InputError(where + ": parameter \"" + here + "\" has type " +
                       userEntry.getAny(false).typeName() + " but must be " +
                       validEntry.getAny(false).typeName() + " (" + validEntry.docString() + ")");
    }
    if (!validEntry.validator().is_null()) {
      try {
        validEntry.validator()->validateAndModify(name, path, &user.getEntry(name));
      } catch (const std::exception& e) {
        throw InputError(where + ": parameter \"" + here + "\" is invalid: " + e.what());
      }
    }
  }
  // Fill in defaults, recursing into sublists that the user did not give.
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const auto& entry = valid.entry(it);
    if (entry.isList()) {
      if (depth > 0)
        validateLevel(user.sublist(name, false, entry.docString()), valid.sublist(name), where,
                      path.empty() ? name : path + "/" + name, depth - 1);
    } else if (!user.isParameter(name)) {
      user.setEntry(name, entry);
    }
  }
}

void describeLevel(const Teuchos::ParameterList& valid, const std::string& prefix,
                   std::ostringstream& out) {
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const auto& entry = valid.entry(it);
    const std::string path = prefix.empty() ? valid.name(it) : prefix + "/" + valid.name(it);
    if (entry.isList()) {
      describeLevel(Teuchos::getValue<Teuchos::ParameterList>(entry), path, out);
    } else {
      out << path << "  (" << entry.getAny(false).typeName() << ", default "
          << entry.getAny(false) << ")\n      " << entry.docString() << "\n";
    }
  }
}
}  // namespace

void validateAndSetDefaults(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                            const std::string& where, int depth) {
  validateLevel(user, valid, where, "", depth);
}

std::string describeParameters(const Teuchos::ParameterList& valid, const std::string& prefix) {
  std::ostringstream out;
  describeLevel(valid, prefix, out);
  return out.str();
}

}  // namespace tribos::core
