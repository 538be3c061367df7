// Contact/F2 not given follows F1 of the same list (issue 42: "F1 given alone leaves F2 at its
// default 0.3: friction becomes orthotropic and the push-out force doubles, exit 0"): the
// scene's Contact list validated as the driver validates it, then read into interfaces.
#include <gtest/gtest.h>

#include <Teuchos_ParameterList.hpp>

#include "tribos/core/Parameters.hpp"
#include "tribos/stack/SceneParameters.hpp"

using namespace tribos;

namespace {
/// The interfaces of a scene whose Contact list holds `flat` and the named sublists `named`.
std::vector<stack::ContactInterface> interfacesOf(const Teuchos::ParameterList& contact) {
  Teuchos::ParameterList scene("Tribos");
  scene.sublist("Contact") = contact;
  core::validateAndSetDefaults(scene, *stack::sceneValidParameters(), "test");
  return stack::readContactInterfaces(scene.sublist("Contact"), "test");
}

Teuchos::ParameterList flatContact() {
  Teuchos::ParameterList contact("Contact");
  contact.set("Slave Side Set", std::string("lower"));
  contact.set("Master Side Set", std::string("upper"));
  return contact;
}
}  // namespace

TEST(FrictionParameters, f1AloneIsIsotropic) {
  auto contact = flatContact();
  contact.set("F1", 0.15);
  const auto interfaces = interfacesOf(contact);
  ASSERT_EQ(interfaces.size(), 1u);
  EXPECT_EQ(interfaces[0].law.F1, 0.15);
  EXPECT_EQ(interfaces[0].law.F2, 0.15);
}

TEST(FrictionParameters, bothGivenAreKeptAndNeitherGivesTheDefaults) {
  auto contact = flatContact();
  contact.set("F1", 0.15);
  contact.set("F2", 0.4);
  auto interfaces = interfacesOf(contact);
  EXPECT_EQ(interfaces[0].law.F1, 0.15);
  EXPECT_EQ(interfaces[0].law.F2, 0.4);
  interfaces = interfacesOf(flatContact());
  EXPECT_EQ(interfaces[0].law.F1, contact::FrictionLaw{}.F1);
  EXPECT_EQ(interfaces[0].law.F2, contact::FrictionLaw{}.F2);
  // F2 alone: F1 keeps its default.
  auto onlyF2 = flatContact();
  onlyF2.set("F2", 0.05);
  interfaces = interfacesOf(onlyF2);
  EXPECT_EQ(interfaces[0].law.F1, contact::FrictionLaw{}.F1);
  EXPECT_EQ(interfaces[0].law.F2, 0.05);
}

TEST(FrictionParameters, anInterfaceSublistFollowsItsOwnF1OrTheFlatList) {
  Teuchos::ParameterList contact("Contact");
  contact.set("F1", 0.2);
  contact.set("F2", 0.1);  // orthotropic where a sublist gives neither coefficient
  for (const char* name : {"a", "b", "c"}) {
    auto& one = contact.sublist(name);
    one.set("Slave Side Set", std::string(name) + "_slave");
    one.set("Master Side Set", std::string(name) + "_master");
  }
  contact.sublist("a").set("F1", 0.5);                                // F1 alone: isotropic 0.5
  contact.sublist("b").set("F1", 0.5).set("F2", 0.25);                // both its own
  const auto interfaces = interfacesOf(contact);                      // c: the flat list's
  ASSERT_EQ(interfaces.size(), 3u);
  EXPECT_EQ(interfaces[0].law.F1, 0.5);
  EXPECT_EQ(interfaces[0].law.F2, 0.5);
  EXPECT_EQ(interfaces[1].law.F1, 0.5);
  EXPECT_EQ(interfaces[1].law.F2, 0.25);
  EXPECT_EQ(interfaces[2].law.F1, 0.2);
  EXPECT_EQ(interfaces[2].law.F2, 0.1);
}
