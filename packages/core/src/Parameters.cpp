#include "tribos/core/Parameters.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>

#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Validators.hpp"
#include "tribos/core/XmlParameters.hpp"

namespace tribos::core {

namespace {
constexpr const char* kAnyName = "*";

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
                   const std::string& where, const std::string& path, int depth,
                   bool fillDefaults = true) {
  // A valid list whose only entry is the sublist kAnyName holds user-named sublists (one
  // per body, per load, ...), each validated against that template.
  if (valid.numParams() == 1 && valid.isSublist(kAnyName)) {
    for (auto it = user.begin(); it != user.end(); ++it) {
      const std::string here = (path.empty() ? "" : path + "/") + user.name(it);
      if (!user.entry(it).isList())
        throw InputError(where + ": \"" + here + "\" must be a sublist (\"" + path +
                         "\" holds one sublist per named item)");
      // No defaults at this level: which of a template's alternatives the user gave matters.
      validateLevel(user.sublist(user.name(it)), valid.sublist(kAnyName), where, here, depth - 1,
                    /*fillDefaults=*/false);
    }
    return;
  }
  for (auto it = user.begin(); it != user.end(); ++it) {
    const std::string& name = user.name(it);
    const std::string here = path.empty() ? name : path + "/" + name;
    if (!valid.isParameter(name) && valid.isSublist(kAnyName) && user.entry(it).isList()) {
      // Beside named entries, a template kAnyName validates user-named sublists (one per
      // boundary condition, ...).
      validateLevel(user.sublist(name), valid.sublist(kAnyName), where, here, depth - 1, /*fillDefaults=*/false);
      continue;
    }
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
        throw InputError(where + ": parameter \"" + here + "\" is invalid: " + teuchosReason(e.what()));
      }
    }
  }
  // Fill in defaults, recursing into sublists that the user did not give.
  if (!fillDefaults) return;
  for (auto it = valid.begin(); it != valid.end(); ++it) {
    const std::string& name = valid.name(it);
    const auto& entry = valid.entry(it);
    if (name == kAnyName) continue;  // a template, not a list to create
    if (entry.isList()) {
      if (depth > 0)
        validateLevel(user.sublist(name, false, entry.docString()), valid.sublist(name), where,
                      path.empty() ? name : path + "/" + name, depth - 1);
    } else if (!user.isParameter(name)) {
      // Marked as a default (ParameterEntry::isDefault): a reader can tell a value the user
      // gave from one filled in here (Contact/F2 follows F1 unless given).
      user.setEntry(name, entry);
      user.getEntry(name).setAnyValue(entry.getAny(false), /*isDefault=*/true);
    }
  }
}

// The default as a user would write it: "0.3", "{1, 0, 0}", "true", "\"\"" for an empty
// string, "none (required)" for a placeholder NaN (a template entry without a default).
std::string defaultText(const Teuchos::ParameterEntry& entry) {
  const auto& any = entry.getAny(false);
  if (any.type() == typeid(double)) {
    const double x = Teuchos::any_cast<double>(any);
    return std::isnan(x) ? "none (required)" : formatShortest(x);
  }
  if (any.type() == typeid(bool)) return Teuchos::any_cast<bool>(any) ? "true" : "false";
  if (any.type() == typeid(std::string)) {
    const auto& s = Teuchos::any_cast<std::string>(any);
    return s.empty() ? "\"\"" : s;
  }
  if (any.type() == typeid(Teuchos::Array<double>)) {
    std::string text;
    for (double x : Teuchos::any_cast<Teuchos::Array<double>>(any)) text += (text.empty() ? "" : ", ") + formatShortest(x);
    return "{" + text + "}";
  }
  if (any.type() == typeid(Teuchos::Array<std::string>)) {
    std::string text;
    for (const auto& x : Teuchos::any_cast<Teuchos::Array<std::string>>(any)) text += (text.empty() ? "" : ", ") + x;
    return "{" + text + "}";
  }
  std::ostringstream out;
  out << any;
  return out.str();
}

// The parameters of a level first, then its sublists: a component's own settings read
// together, before the components it embeds.
void describeLevel(const Teuchos::ParameterList& valid, const std::string& prefix,
                   std::ostringstream& out) {
  for (const bool lists : {false, true}) {
    for (auto it = valid.begin(); it != valid.end(); ++it) {
      const auto& entry = valid.entry(it);
      if (entry.isList() != lists) continue;
      const std::string path = prefix.empty() ? valid.name(it) : prefix + "/" + valid.name(it);
      if (lists) {
        describeLevel(Teuchos::getValue<Teuchos::ParameterList>(entry), path, out);
        continue;
      }
      const std::string range = describeRange(entry);
      out << path << "  (" << entry.getAny(false).typeName() << ", default " << defaultText(entry)
          << (range.empty() ? "" : ", range " + range) << ")\n      " << entry.docString() << "\n";
    }
  }
}
}  // namespace

void validateAndSetDefaults(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                            const std::string& where, int depth) {
  validateLevel(user, valid, where, "", depth);
}

bool givenByUser(const Teuchos::ParameterList& list, const std::string& name) {
  return list.isParameter(name) && !list.getEntry(name).isDefault();
}

std::string describeParameters(const Teuchos::ParameterList& valid, const std::string& prefix) {
  std::ostringstream out;
  describeLevel(valid, prefix, out);
  return out.str();
}

}  // namespace tribos::core

namespace tribos::core {

namespace {
double parseDouble(const std::string& text, const std::string& context) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0') throw InputError(context + ": \"" + text + "\" is not a number");
  // strtod reads "inf", "nan" and overflows to Inf: every Tribos parameter is finite.
  if (!std::isfinite(v)) throw InputError(context + ": \"" + text + "\" is not a finite number");
  return v;
}

int parseInt(const std::string& text, const std::string& context) {
  char* end = nullptr;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || v < -2147483647L || v > 2147483647L)
    throw InputError(context + ": \"" + text + "\" is not an integer");
  return static_cast<int>(v);
}

// "{a, b, c}" -> {"a", "b", "c"} (braces optional, items trimmed).
std::vector<std::string> splitArray(std::string text) {
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t"), e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
  };
  text = trim(text);
  if (!text.empty() && text.front() == '{' && text.back() == '}') text = text.substr(1, text.size() - 2);
  std::vector<std::string> items;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) items.push_back(trim(item));
  if (items.size() == 1 && items[0].empty()) items.clear();
  return items;
}
// `text` read as a value of the type of `valid`.
Teuchos::any parseAs(const Teuchos::any& valid, const std::string& text, const std::string& context) {
  if (valid.type() == typeid(int)) return Teuchos::any(parseInt(text, context));
  if (valid.type() == typeid(double)) return Teuchos::any(parseDouble(text, context));
  if (valid.type() == typeid(bool)) {
    if (text != "true" && text != "false") throw InputError(context + ": expected true or false");
    return Teuchos::any(text == "true");
  }
  if (valid.type() == typeid(std::string)) return Teuchos::any(text);
  if (valid.type() == typeid(Teuchos::Array<int>)) {
    Teuchos::Array<int> a;
    for (const auto& item : splitArray(text)) a.push_back(parseInt(item, context));
    return Teuchos::any(a);
  }
  if (valid.type() == typeid(Teuchos::Array<double>)) {
    Teuchos::Array<double> a;
    for (const auto& item : splitArray(text)) a.push_back(parseDouble(item, context));
    return Teuchos::any(a);
  }
  if (valid.type() == typeid(Teuchos::Array<std::string>)) {
    Teuchos::Array<std::string> a;
    for (const auto& item : splitArray(text)) a.push_back(item);
    return Teuchos::any(a);
  }
  throw InputError(context + ": parameters of type " + valid.typeName() + " cannot be set from the command line");
}
}  // namespace

void applyOverride(Teuchos::ParameterList& user, const Teuchos::ParameterList& valid,
                   const std::string& assignment) {
  const std::string context = "--set \"" + assignment + "\"";
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(context + ": expected \"Sublist/Name=value\"");
  const std::string path = assignment.substr(0, eq), value = assignment.substr(eq + 1);

  std::vector<std::string> names;
  std::string part;
  std::istringstream in(path);
  while (std::getline(in, part, '/')) names.push_back(part);

  const Teuchos::ParameterList* validLevel = &valid;
  Teuchos::ParameterList* userLevel = &user;
  for (size_t i = 0; i + 1 < names.size(); ++i) {
    const bool anyName = !validLevel->isSublist(names[i]) && validLevel->isSublist(kAnyName);
    const std::string validName = anyName ? kAnyName : names[i];
    if (!validLevel->isSublist(validName))
      throw InputError(context + ": no sublist \"" + names[i] + "\"; valid names are:\n" + listValid(*validLevel));
    validLevel = &validLevel->sublist(validName);
    userLevel = &userLevel->sublist(names[i]);
  }
  const std::string& name = names.back();
  if (!validLevel->isParameter(name) || validLevel->isSublist(name))
    throw InputError(context + ": no parameter \"" + name + "\" there; valid names are:\n" + listValid(*validLevel));

  // Stored without the valid entry's validator: the caller validates the whole list next
  // (a value out of range is then an InputError naming this override).
  Teuchos::ParameterEntry entry;
  entry.setAnyValue(parseAs(validLevel->getEntry(name).getAny(false), value, context));
  userLevel->setEntry(name, entry);
}

}  // namespace tribos::core
