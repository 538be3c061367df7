#include "tribos/core/XmlParameters.hpp"

#include <Teuchos_ParameterList.hpp>
#include <Teuchos_StringInputSource.hpp>
#include <Teuchos_XMLObject.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>
#include <Teuchos_XMLParameterListReader.hpp>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include "tribos/core/Errors.hpp"

namespace tribos::core {

namespace {

// ---- Nesting depth, on the raw text (before any recursive parser sees it) ----

// Moves `i` past the first `end` at or after it, counting the lines crossed; false when the
// text ends first (the parser reports the unterminated construct).
bool skipPast(const std::string& text, size_t& i, const std::string& end, int& line) {
  const size_t at = text.find(end, i);
  const size_t stop = at == std::string::npos ? text.size() : at + end.size();
  line += static_cast<int>(std::count(text.begin() + static_cast<long>(i), text.begin() + static_cast<long>(stop), '\n'));
  i = stop;
  return at != std::string::npos;
}

// Moves `i` past the '>' that ends the tag opened at `i`, skipping quoted attribute values.
bool skipTag(const std::string& text, size_t& i, int& line) {
  char quote = 0;
  for (++i; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (quote) {
      if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c;
    } else if (c == '>') {
      ++i;
      return true;
    }
  }
  return false;
}

void requireShallowNesting(const std::string& text, const std::string& source) {
  int depth = 0, line = 1;
  size_t i = 0;
  while (i < text.size()) {
    if (text[i] != '<') {
      if (text[i++] == '\n') ++line;
      continue;
    }
    bool complete = true;
    if (text.compare(i, 4, "<!--") == 0) {
      complete = skipPast(text, i, "-->", line);
    } else if (text.compare(i, 9, "<![CDATA[") == 0) {
      complete = skipPast(text, i, "]]>", line);
    } else if (text.compare(i, 2, "<?") == 0 || text.compare(i, 2, "<!") == 0) {
      complete = skipTag(text, i, line);
    } else {
      const bool closing = text.compare(i, 2, "</") == 0;
      const int tagLine = line;
      complete = skipTag(text, i, line);
      const bool empty = complete && text[i - 2] == '/';  // <Parameter .../>
      if (closing) {
        --depth;
      } else if (!empty && ++depth > kMaxXmlNesting) {
        throw InputError(source + ": the XML nests more than " + std::to_string(kMaxXmlNesting) +
                         " elements deep (line " + std::to_string(tagLine) +
                         "); a Tribos scene needs a few levels of ParameterList");
      }
    }
    if (!complete) return;  // unterminated: the parser names it
  }
}

// ---- Values that must read completely as their type ----

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// Why `text` is not a value of `type` ("" when it is, or when the type is not checked here).
std::string scalarProblem(const std::string& type, const std::string& text) {
  const std::string t = trimmed(text);
  if (type == "int") {
    static const std::regex integer("[+-]?[0-9]+");
    if (!std::regex_match(t, integer)) return "\"" + t + "\" is not an integer";
    errno = 0;
    const long long v = std::strtoll(t.c_str(), nullptr, 10);
    if (errno == ERANGE || v < INT_MIN || v > INT_MAX) return "\"" + t + "\" is out of the range of int";
    return "";
  }
  if (type == "double" || type == "float") {
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    if (t.empty() || *end != '\0') return "\"" + t + "\" is not a number";
    if (!std::isfinite(v)) return "\"" + t + "\" is not a finite number";
    return "";
  }
  if (type == "bool") {
    std::string lower = t;
    std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
    for (const char* word : {"true", "false", "yes", "no", "1", "0"})
      if (lower == word) return "";
    return "\"" + t + "\" is not true or false";
  }
  return "";
}

// "{1, 2, 3}" -> its items; false when the braces are missing.
bool arrayItems(const std::string& text, std::vector<std::string>& items) {
  const std::string t = trimmed(text);
  if (t.size() < 2 || t.front() != '{' || t.back() != '}') return false;
  const std::string inner = t.substr(1, t.size() - 2);
  if (trimmed(inner).empty()) return true;
  std::istringstream in(inner);
  for (std::string item; std::getline(in, item, ',');) items.push_back(item);
  return true;
}

std::string valueProblem(const std::string& type, const std::string& value) {
  // Every array type: Teuchos's own message for missing braces names no parameter.
  static const std::regex array("Array\\((int|double|float|string|bool)\\)");
  std::smatch element;
  if (!std::regex_match(type, element, array)) return scalarProblem(type, value);
  std::vector<std::string> items;
  if (!arrayItems(value, items)) return "\"" + value + "\" is not an array \"{a, b, ...}\"";
  for (const auto& item : items)
    if (auto problem = scalarProblem(element[1], item); !problem.empty()) return "element " + problem;
  return "";
}

// ---- The XML tree: names unique per list, values of their type ----

const std::string& requiredAttribute(const Teuchos::XMLObject& xml, const std::string& name,
                                     const std::string& where) {
  if (!xml.hasAttribute(name))
    throw InputError(where + ": <" + xml.getTag() + "> without the attribute \"" + name + "\"");
  return xml.getRequired(name);
}

void checkList(const Teuchos::XMLObject& list, const std::string& path, const std::string& source, int depth) {
  std::set<std::string> names;
  for (int i = 0; i < list.numChildren(); ++i) {
    const Teuchos::XMLObject& child = list.getChild(i);
    const std::string& tag = child.getTag();
    const std::string where = source + (path.empty() ? "" : ": in \"" + path + "\"");
    if (depth == 0 && (tag == "Validators" || tag == "Dependencies")) continue;  // Teuchos's own sections
    if (tag != "Parameter" && tag != "ParameterList")
      throw InputError(where + ": unexpected element <" + tag + "> (a parameter list holds <Parameter> and "
                       "<ParameterList> elements)");
    const std::string& name = requiredAttribute(child, "name", where);
    const std::string here = path.empty() ? name : path + "/" + name;
    if (!names.insert(name).second)
      throw InputError(source + ": \"" + here + "\" is given twice" +
                       (path.empty() ? std::string() : " in \"" + path + "\"") + "; give each parameter and sublist once");
    if (tag == "ParameterList") {
      checkList(child, here, source, depth + 1);
      continue;
    }
    const std::string& type = requiredAttribute(child, "type", source + ": parameter \"" + here + "\"");
    const std::string& value = requiredAttribute(child, "value", source + ": parameter \"" + here + "\"");
    if (auto problem = valueProblem(type, value); !problem.empty())
      throw InputError(source + ": parameter \"" + here + "\" (type " + type + "): " + problem);
  }
}

// A copy of `in` with names and values only.
Teuchos::ParameterList valuesOnly(const Teuchos::ParameterList& in) {
  Teuchos::ParameterList out(in.name());
  for (auto it = in.begin(); it != in.end(); ++it) {
    const auto& entry = in.entry(it);
    if (entry.isList()) {
      out.sublist(in.name(it)) = valuesOnly(Teuchos::getValue<Teuchos::ParameterList>(entry));
    } else {
      Teuchos::ParameterEntry value;
      value.setAnyValue(entry.getAny(false));
      out.setEntry(in.name(it), value);
    }
  }
  return out;
}
}  // namespace

std::string teuchosReason(const std::string& what) {
  static const std::regex bookkeeping("^(\\S+:[0-9]+:|Throw number = .*|Throw test that evaluated to true:.*)$");
  std::istringstream in(what);
  std::string reason;
  for (std::string line; std::getline(in, line);) {
    line = trimmed(line);
    if (line.empty() || std::regex_match(line, bookkeeping)) continue;
    reason += (reason.empty() ? "" : " ") + line;
  }
  return reason.empty() ? what : reason;
}

Teuchos::RCP<Teuchos::ParameterList> parameterListFromXml(const std::string& text, const std::string& source) {
  requireShallowNesting(text, source);
  Teuchos::XMLObject xml;
  try {
    xml = Teuchos::StringInputSource(text).getObject();
  } catch (const std::exception& e) {
    throw InputError(source + ": not a valid XML parameter list: " + teuchosReason(e.what()));
  }
  if (xml.getTag() != "ParameterList")
    throw InputError(source + ": the top element is <" + xml.getTag() + ">, not <ParameterList>");
  checkList(xml, "", source, 0);
  try {
    return Teuchos::rcp(new Teuchos::ParameterList(Teuchos::XMLParameterListReader().toParameterList(xml)));
  } catch (const std::exception& e) {
    throw InputError(source + ": not a valid Teuchos parameter list: " + teuchosReason(e.what()));
  }
}

std::string parameterListToXml(const Teuchos::ParameterList& list) {
  std::ostringstream xml;
  Teuchos::writeParameterListToXmlOStream(valuesOnly(list), xml);
  return xml.str();
}

}  // namespace tribos::core
