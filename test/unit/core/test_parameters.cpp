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
