// core::parameterListFromXml: what Teuchos alone accepts silently or crashes on is an
// InputError naming the file and the parameter path.
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>

#include "tribos/core/Errors.hpp"
#include "tribos/core/XmlParameters.hpp"

namespace {
using tribos::core::InputError;
using tribos::core::parameterListFromXml;

std::string scene(const std::string& body) { return "<ParameterList name=\"Tribos\">" + body + "</ParameterList>"; }
std::string mesh(const std::string& body) { return scene("<ParameterList name=\"Mesh\">" + body + "</ParameterList>"); }
std::string parameter(const std::string& name, const std::string& type, const std::string& value) {
  return "<Parameter name=\"" + name + "\" type=\"" + type + "\" value=\"" + value + "\"/>";
}

// The InputError's message (fails the test if there is none).
std::string errorOf(const std::string& text) {
  try {
    parameterListFromXml(text, "scene.xml");
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "accepted:\n" << text;
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST(XmlParameters, readsValidListsWithTheirTypes) {
  const auto list = parameterListFromXml(
      mesh(parameter("H Over h", "int", "3") + parameter("Initial Gap", "double", " 0.5 ") +
           parameter("Flag", "bool", "true") + parameter("Traction", "Array(double)", "{1, 0, -2.5e1}") +
           parameter("Sets", "Array(string)", "{a, b}")),
      "scene.xml");
  const auto& m = list->sublist("Mesh");
  EXPECT_EQ(m.get<int>("H Over h"), 3);
  EXPECT_EQ(m.get<double>("Initial Gap"), 0.5);
  EXPECT_TRUE(m.get<bool>("Flag"));
  EXPECT_EQ(m.get<Teuchos::Array<double>>("Traction")[2], -25.0);
}

TEST(XmlParameters, valuesThatDoNotReadAsTheirTypeNameTheParameter) {
  const std::pair<std::string, std::string> bad[] = {
      {parameter("H Over h", "int", "2.5"), "is not an integer"},
      {parameter("H Over h", "int", "99999999999"), "out of the range"},
      {parameter("Initial Gap", "double", "garbage"), "is not a number"},
      {parameter("Initial Gap", "double", "inf"), "is not a finite number"},
      {parameter("Initial Gap", "double", "nan"), "is not a finite number"},
      {parameter("Initial Gap", "double", "1e400"), "is not a finite number"},
      {parameter("Flag", "bool", "maybe"), "is not true or false"},
      {parameter("Traction", "Array(double)", "{1, x, 2}"), "element \"x\" is not a number"},
      {parameter("Traction", "Array(double)", "1, 2"), "is not an array"},
      {parameter("Sets", "Array(string)", "a, b"), "\"Mesh/Sets\" (type Array(string)): \"a, b\" is not an array"},
  };
  for (const auto& [xml, reason] : bad) {
    const auto message = errorOf(mesh(xml));
    EXPECT_TRUE(contains(message, "scene.xml")) << message;
    EXPECT_TRUE(contains(message, "\"Mesh/")) << message;
    EXPECT_TRUE(contains(message, reason)) << message;
  }
}

TEST(XmlParameters, aNameGivenTwiceInOneListIsAnError) {
  auto message = errorOf(mesh(parameter("H Over h", "int", "2") + parameter("H Over h", "int", "3")));
  EXPECT_TRUE(contains(message, "\"Mesh/H Over h\" is given twice")) << message;
  message = errorOf(scene("<ParameterList name=\"Mesh\"/><ParameterList name=\"Mesh\"/>"));
  EXPECT_TRUE(contains(message, "\"Mesh\" is given twice")) << message;
  // The same name in different lists is fine.
  EXPECT_NO_THROW(parameterListFromXml(
      scene("<ParameterList name=\"A\">" + parameter("x", "int", "1") + "</ParameterList><ParameterList name=\"B\">" +
            parameter("x", "int", "1") + "</ParameterList>"),
      "scene.xml"));
}

TEST(XmlParameters, deepNestingIsRefusedBeforeParsing) {
  // 100000 levels overflowed the stack of the recursive reader (signal 11).
  for (int levels : {tribos::core::kMaxXmlNesting, 100000}) {
    std::string text;
    for (int i = 0; i < levels; ++i) text += "<ParameterList name=\"a\">";
    for (int i = 0; i < levels; ++i) text += "</ParameterList>";
    if (levels <= tribos::core::kMaxXmlNesting) {
      EXPECT_NO_THROW(parameterListFromXml(text, "scene.xml"));
    } else {
      const auto message = errorOf(text);
      EXPECT_TRUE(contains(message, "nests more than 64")) << message;
    }
  }
  // Comments, declarations and empty elements do not count.
  EXPECT_NO_THROW(parameterListFromXml("<?xml version=\"1.0\"?><!-- <a><b> -->" + mesh(parameter("x", "int", "1")),
                                       "scene.xml"));
}

TEST(XmlParameters, parserErrorsGiveAShortReasonWithoutTeuchosSourceLines) {
  const auto message = errorOf("<ParameterList name=\"Tribos\"><Parameter name=\"x\"");
  EXPECT_TRUE(contains(message, "scene.xml: not a valid XML parameter list")) << message;
  EXPECT_FALSE(contains(message, ".cpp:")) << message;
  EXPECT_FALSE(contains(message, "Throw")) << message;
  EXPECT_TRUE(contains(errorOf("<Tribos/>"), "not <ParameterList>"));
  EXPECT_TRUE(contains(errorOf(mesh("<Parameter name=\"x\" type=\"int\"/>")), "without the attribute \"value\""));
  EXPECT_TRUE(contains(errorOf(mesh("<Foo/>")), "unexpected element <Foo>"));
}

TEST(XmlParameters, writesValuesBackAsXml) {
  Teuchos::ParameterList list("Tribos");
  list.sublist("Solver").set("Tolerance", 1e-5, "epsilon");
  const auto again = parameterListFromXml(tribos::core::parameterListToXml(list), "round trip");
  EXPECT_EQ(again->sublist("Solver").get<double>("Tolerance"), 1e-5);
}
