#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Parameters.hpp"

namespace {
Teuchos::ParameterList validList() {
  Teuchos::ParameterList valid("Tribos");
  valid.sublist("Mesh").set("H Over h", 2, "elements per subdomain edge");
  valid.sublist("Mesh").set("Generator", std::string("Two Bricks"), "mesh source");
  valid.sublist("Solver").set("Tolerance", 1e-5, "relative tolerance");
  return valid;
}
}  // namespace

TEST(Parameters, fillsDefaultsAndKeepsUserValues) {
  Teuchos::ParameterList user("Tribos");
  user.sublist("Mesh").set("H Over h", 4);
  tribos::core::validateAndSetDefaults(user, validList(), "scene.xml");
  EXPECT_EQ(user.sublist("Mesh").get<int>("H Over h"), 4);
  EXPECT_EQ(user.sublist("Mesh").get<std::string>("Generator"), "Two Bricks");
  EXPECT_DOUBLE_EQ(user.sublist("Solver").get<double>("Tolerance"), 1e-5);
}

TEST(Parameters, unknownNameListsValidOnes) {
  Teuchos::ParameterList user("Tribos");
  user.sublist("Mesh").set("H over h", 4);  // wrong case
  try {
    tribos::core::validateAndSetDefaults(user, validList(), "scene.xml");
    FAIL() << "expected InputError";
  } catch (const tribos::core::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("scene.xml"), std::string::npos) << msg;
    EXPECT_NE(msg.find("Mesh/H over h"), std::string::npos) << msg;
    EXPECT_NE(msg.find("\"H Over h\""), std::string::npos) << msg;
  }
}

TEST(Parameters, wrongTypeIsAnError) {
  Teuchos::ParameterList user("Tribos");
  user.sublist("Solver").set("Tolerance", std::string("small"));
  EXPECT_THROW(tribos::core::validateAndSetDefaults(user, validList(), "scene.xml"),
               tribos::core::InputError);
}

#include <Teuchos_Array.hpp>

TEST(Parameters, overridesTakeTheValidType) {
  Teuchos::ParameterList valid = validList();
  valid.sublist("Loads").sublist("*").set("Traction", Teuchos::Array<double>(3, 0.0), "p");
  Teuchos::ParameterList user("Tribos");
  tribos::core::applyOverride(user, valid, "Mesh/H Over h=5");
  tribos::core::applyOverride(user, valid, "Solver/Tolerance=1e-8");
  tribos::core::applyOverride(user, valid, "Loads/my load/Traction={1, 0, 20}");
  EXPECT_EQ(user.sublist("Mesh").get<int>("H Over h"), 5);
  EXPECT_DOUBLE_EQ(user.sublist("Solver").get<double>("Tolerance"), 1e-8);
  const auto& t = user.sublist("Loads").sublist("my load").get<Teuchos::Array<double>>("Traction");
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[2], 20.0);
  tribos::core::validateAndSetDefaults(user, valid, "cli");  // user-named sublist accepted
  EXPECT_FALSE(user.sublist("Loads").sublist("my load").isParameter("Side Set"));  // no template defaults
}

TEST(Parameters, badOverridesNameTheAssignment) {
  const Teuchos::ParameterList valid = validList();
  Teuchos::ParameterList user("Tribos");
  for (const char* bad : {"Mesh/H Over h=2.5", "Mesh/H Over h", "Mesh/Nope=1", "Nope/H Over h=1",
                          "Solver/Tolerance=abc"}) {
    try {
      tribos::core::applyOverride(user, valid, bad);
      ADD_FAILURE() << "accepted " << bad;
    } catch (const tribos::core::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

#include <Teuchos_StandardParameterEntryValidators.hpp>

TEST(Parameters, aValueOutsideAChoiceIsOneLineWithoutTeuchosBookkeeping) {
  Teuchos::ParameterList valid = validList();
  Teuchos::setStringToIntegralParameter<int>("Friction Model", "Coulomb", "friction",
                                             Teuchos::tuple<std::string>("None", "Coulomb"),
                                             &valid.sublist("Contact"));
  Teuchos::ParameterList user("Tribos");
  user.sublist("Contact").set("Friction Model", std::string("Frictionless"));
  try {
    tribos::core::validateAndSetDefaults(user, valid, "scene.xml");
    FAIL() << "expected InputError";
  } catch (const tribos::core::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("\"Contact/Friction Model\" is invalid"), std::string::npos) << msg;
    EXPECT_NE(msg.find("\"None\" \"Coulomb\""), std::string::npos) << msg;  // the choices, on the line
    EXPECT_EQ(msg.find("Throw number"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}
