// Range validators (open and closed ends, finite only), the parameter table that binds a
// settings struct to its valid list, and the listing with ranges.
#include <gtest/gtest.h>

#include <limits>

#include "tribos/core/Errors.hpp"
#include "tribos/core/ParameterTable.hpp"
#include "tribos/core/Parameters.hpp"

namespace {
using namespace tribos;

template <class T>
bool accepts(const Teuchos::RCP<const Teuchos::ParameterEntryValidator>& v, const T& value) {
  Teuchos::ParameterEntry entry(value);
  try {
    v->validateAndModify("x", "list", &entry);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

struct Settings {
  double step = 1.9;
  int cap = 100;
  bool flag = false;
  std::string mode = "A";
};

const core::ParameterTable<Settings>& table() {
  static const auto t = core::ParameterTable<Settings>()
                            .add("step", &Settings::step, "the step", core::openInterval(0.0, 2.0))
                            .add("cap", &Settings::cap, "the cap", core::intRange(1, 1000))
                            .add("flag", &Settings::flag, "a flag")
                            .add("mode", &Settings::mode, "the mode", {"A", "B"});
  return t;
}
}  // namespace

TEST(Validators, realRangesHaveOpenOrClosedEndsAndRefuseNonFiniteValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto open = core::openInterval(0.0, 2.0);
  EXPECT_TRUE(accepts(open, 1.0));
  EXPECT_FALSE(accepts(open, 0.0));
  EXPECT_FALSE(accepts(open, 2.0));
  EXPECT_FALSE(accepts(open, nan));
  EXPECT_EQ(open->rangeText(), "(0, 2)");
  const auto closed = core::closedInterval(0.0, 1.0);
  EXPECT_TRUE(accepts(closed, 0.0));
  EXPECT_TRUE(accepts(closed, 1.0));
  EXPECT_EQ(closed->rangeText(), "[0, 1]");
  const auto positive = core::greaterThan(0.0);
  EXPECT_FALSE(accepts(positive, inf));  // above every bound, but not finite
  EXPECT_FALSE(accepts(positive, nan));
  EXPECT_TRUE(accepts(positive, 3));     // an int for a real
  EXPECT_EQ(positive->rangeText(), "(0, inf)");
  EXPECT_FALSE(accepts(core::finite(), -inf));
  EXPECT_FALSE(accepts(positive, std::string("1")));  // a string is not a number
}

TEST(Validators, integerAndArrayRanges) {
  const auto ints = core::intRange(1, 10);
  EXPECT_TRUE(accepts(ints, 1));
  EXPECT_FALSE(accepts(ints, 0));
  EXPECT_FALSE(accepts(ints, 11));
  EXPECT_FALSE(accepts(ints, 2.0));  // a real for an int
  const auto three = core::finiteArray(3);
  EXPECT_TRUE(accepts(three, Teuchos::Array<double>(3, 1.0)));
  EXPECT_FALSE(accepts(three, Teuchos::Array<double>(2, 1.0)));
  EXPECT_FALSE(accepts(three, Teuchos::Array<double>(3, std::numeric_limits<double>::quiet_NaN())));
  // Physical magnitudes: a bound below the overflow of squares (1e300 overflowed in norms).
  const auto bounded = core::finiteArray(3, core::kMaxMagnitude);
  EXPECT_TRUE(accepts(bounded, Teuchos::Array<double>(3, -1e100)));
  EXPECT_FALSE(accepts(bounded, Teuchos::Array<double>(3, -1e300)));
  EXPECT_EQ(bounded->rangeText(), "3 finite numbers of magnitude <= 1e+100");
  const auto modulus = core::openClosed(0.0, core::kMaxMagnitude);
  EXPECT_TRUE(accepts(modulus, 1e100));
  EXPECT_FALSE(accepts(modulus, 1e300));
  EXPECT_FALSE(accepts(modulus, 0.0));
  EXPECT_EQ(modulus->rangeText(), "(0, 1e+100]");
}

TEST(Validators, aTableDeclaresTheStructDefaultsAndReadsValidatedLists) {
  Teuchos::ParameterList valid("Component");
  table().declare(valid);
  EXPECT_EQ(valid.get<double>("step"), Settings().step);
  EXPECT_EQ(valid.get<std::string>("mode"), "A");
  Teuchos::ParameterList user("Component");
  user.set("step", 1.5);
  user.set("mode", std::string("B"));
  core::validateAndSetDefaults(user, valid, "scene.xml");
  Settings s;
  table().read(user, s);
  EXPECT_EQ(s.step, 1.5);
  EXPECT_EQ(s.cap, 100);
  EXPECT_EQ(s.mode, "B");
  const std::pair<const char*, Teuchos::ParameterEntry> refused[] = {{"step", Teuchos::ParameterEntry(2.0)},
                                                                      {"cap", Teuchos::ParameterEntry(0)},
                                                                      {"mode", Teuchos::ParameterEntry(std::string("C"))},
                                                                      {"flag", Teuchos::ParameterEntry(1)}};
  for (const auto& [name, entry] : refused) {
    Teuchos::ParameterList bad("Component");
    bad.setEntry(name, entry);
    EXPECT_THROW(core::validateAndSetDefaults(bad, valid, "scene.xml"), core::InputError) << name;
  }
}

TEST(Validators, theListingShowsTypeDefaultRangeAndDoc) {
  Teuchos::ParameterList valid("Tribos");
  table().declare(valid.sublist("Component"));
  const auto text = core::describeParameters(valid);
  EXPECT_NE(text.find("Component/step  (double, default 1.9, range (0, 2))\n      the step"), std::string::npos)
      << text;
  EXPECT_NE(text.find("Component/mode  (string, default A, range A | B)"), std::string::npos) << text;
  EXPECT_NE(text.find("Component/cap  (int, default 100, range [1, 1000])"), std::string::npos) << text;
}

TEST(Validators, overridesRefuseNonFiniteNumbers) {
  Teuchos::ParameterList valid("Tribos");
  table().declare(valid.sublist("Component"));
  Teuchos::ParameterList user("Tribos");
  for (const char* bad : {"Component/step=inf", "Component/step=nan", "Component/step=1e999"})
    EXPECT_THROW(core::applyOverride(user, valid, bad), core::InputError) << bad;
  // A value out of range is stored and refused by the validation that follows, which names
  // the override.
  core::applyOverride(user, valid, "Component/step=3");
  try {
    core::validateAndSetDefaults(user, valid, "--set \"Component/step=3\"");
    FAIL() << "accepted step = 3";
  } catch (const core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--set \"Component/step=3\""), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("(0, 2)"), std::string::npos) << e.what();
  }
}
