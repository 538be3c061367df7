// The output registry (issue 40): every number of a step is declared once, and the summary,
// the result file's global variables and the restart's names all come from that declaration.
// A history step with two interfaces and a pretension section, a single contact solve and a
// linear solve: each number the summary holds is the global variable of the same value.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/stack/ContactSolve.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/OutputRegistry.hpp"

using namespace tribos;

namespace {
std::map<std::string, double> byName(const std::vector<mesh::GlobalValue>& globals) {
  std::map<std::string, double> out;
  for (const auto& g : globals) EXPECT_TRUE(out.emplace(g.name, g.value).second) << "twice: " << g.name;
  return out;
}

stack::InterfaceResult anInterface(const std::string& name, double scale) {
  stack::InterfaceResult i;
  i.name = name;
  i.surfaces = "lower -> upper";
  i.normalForce = 1.5 * scale;
  i.force = {0.25 * scale, -0.5 * scale, 2.0 * scale};
  i.frictionForce = 0.125 * scale;
  i.counts = {3, 4, 5};
  i.peakPressure = 7.0 * scale;
  i.largestOpening = 1e-3 * scale;
  i.largestOverlap = 2e-6 * scale;
  i.dissipatedEnergy = 0.75 * scale;
  return i;
}

/// A two-step history whose second step has two interfaces ("" and "punch") and a section.
stack::ContactSolveResult aHistory() {
  stack::ContactSolveResult c;
  c.steps.resize(2);
  c.steps[1].step = 2;
  c.steps[1].converged = true;
  c.steps[1].outerIterations = 11;
  c.steps[1].pfpApplications = 123;
  c.steps[1].fixedPointIterations = 4;
  c.steps[1].kkt.slipRule = 3e-7;
  c.steps[1].kkt.equilibrium = 1e-9;
  c.steps[1].kktTolerance = 1e-5;
  c.steps[1].sections = {{"bolt", 1e4, 0.05}};
  c.earlierSteps.resize(1);
  c.interfaces = {anInterface("", 1.0), anInterface("punch", 3.0)};
  c.dissipatedEnergy = 3.0;
  return c;
}
}  // namespace

TEST(OutputRegistry, everySummaryNumberIsTheGlobalVariableOfTheSameValue) {
  const stack::ContactSolveResult c = aHistory();
  stack::StressResults stress;
  stress.strainEnergy = 42.0;
  stack::ForceBalance balance;
  balance.relativeImbalance = 2e-12;
  const stack::StepOutcome outcome = stack::withStresses(stack::outcomeOf(c, 1), stress, balance);
  nlohmann::json entry;
  stack::addStepNumbers(outcome, entry);
  const auto globals = byName(stack::globalVariables(outcome));

  EXPECT_EQ(globals.at(stack::variable::kLoadStep), 2.0);
  EXPECT_EQ(entry["step"].get<int>(), 2);
  EXPECT_EQ(entry["converged"].get<bool>(), true);
  EXPECT_EQ(globals.at("converged"), 1.0);
  EXPECT_FALSE(entry.contains("inner_iterations"));  // a history step has none
  EXPECT_EQ(globals.count("inner_iterations"), 0u);
  for (const auto& number : stack::kStepNumbers) {
    if (!number.value(outcome)) continue;
    ASSERT_TRUE(entry.contains(number.summaryKey)) << number.summaryKey;
    const auto& v = entry[number.summaryKey];
    EXPECT_EQ(v.is_boolean() ? double(v.get<bool>()) : v.get<double>(), globals.at(number.variable)) << number.variable;
  }
  for (const auto& [name, value] : entry["kkt"].items()) EXPECT_EQ(value.get<double>(), globals.at("kkt_" + name)) << name;
  EXPECT_EQ(globals.at("kkt_slip_rule"), 3e-7);
  EXPECT_EQ(globals.at("kkt_tolerance"), 1e-5);
  ASSERT_EQ(entry["interfaces"].size(), 2u);
  for (const auto& i : entry["interfaces"]) {
    const std::string name = i["name"].get<std::string>();
    for (const auto& number : stack::kInterfaceNumbers)
      EXPECT_EQ(i[number.key].get<double>(), globals.at(stack::interfaceVariable(name, number.key))) << number.key;
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(i[stack::kInterfaceForceKey][k].get<double>(),
                globals.at(stack::interfaceVariable(name, std::string("force_") + "xyz"[k])));
  }
  EXPECT_EQ(globals.at("contact_normal_force"), 1.5);  // the flat Contact list's interface is "contact"
  EXPECT_EQ(globals.at("punch_dissipated_energy"), 2.25);
  EXPECT_EQ(entry["interfaces"][1]["stick"].get<int>(), 4);
  EXPECT_TRUE(entry["interfaces"][1]["stick"].is_number_integer());
  EXPECT_EQ(globals.at(stack::sectionVariable("bolt", stack::variable::kSectionShortening)), 0.05);
  EXPECT_EQ(entry["pretension"][0]["force"].get<double>(), 1e4);
  EXPECT_EQ(globals.at("strain_energy"), 42.0);
  EXPECT_EQ(globals.at(stack::variable::kDissipatedEnergy), 3.0);
}

TEST(OutputRegistry, aSingleSolveAndALinearSolveHaveTheirOwnNumbers) {
  stack::ContactSolveResult c;
  c.contact.converged = false;
  c.contact.counters.outerIterations = 7;
  c.contact.counters.innerIterations = 70;
  c.contact.counters.projectedGradient = 1e-6;
  c.displacement.maxCopyJump = 1e-13;
  const auto single = byName(stack::globalVariables(stack::outcomeOf(c)));
  EXPECT_EQ(single.at("converged"), 0.0);
  EXPECT_EQ(single.at("inner_iterations"), 70.0);
  EXPECT_EQ(single.at("kkt_projected_gradient"), 1e-6);
  EXPECT_EQ(single.at("kkt_max_copy_jump"), 1e-13);
  EXPECT_EQ(single.count(stack::variable::kLoadStep), 0u);

  stack::LinearFetiResult linear;
  linear.converged = true;
  linear.iterations = 30;
  linear.relativeResidual = 1e-9;
  nlohmann::json summary;
  stack::addStepNumbers(stack::outcomeOf(linear), summary);
  const auto globals = byName(stack::globalVariables(stack::outcomeOf(linear)));
  EXPECT_EQ(globals.at("kkt_projected_residual"), 1e-9);
  EXPECT_EQ(summary["kkt"]["projected_residual"].get<double>(), 1e-9);
  EXPECT_FALSE(summary.contains("interfaces"));  // no bonded interface
  EXPECT_EQ(globals.count(stack::variable::kDissipatedEnergy), 0u);
  // The global variables come in the registry's order: the step's numbers, then the KKT
  // residuals by name.
  const auto list = stack::globalVariables(stack::outcomeOf(linear));
  EXPECT_EQ(list.front().name, "converged");
  std::vector<std::string> kkt;
  for (const auto& g : list)
    if (g.name.rfind("kkt_", 0) == 0) kkt.push_back(g.name);
  EXPECT_TRUE(std::is_sorted(kkt.begin(), kkt.end()));
}

TEST(OutputRegistry, stateFieldsAreNamedOnceAndOnlyWhereComputed) {
  std::set<std::string> names;
  for (const auto& f : stack::stateFields()) EXPECT_TRUE(names.insert(f.name).second) << f.name;
  for (const auto& f : stack::kContactNodalFields) EXPECT_TRUE(names.insert(f.name).second) << f.name;
  EXPECT_EQ(stack::displacementField(1), "displ_y");
  const std::vector<std::array<double, 3>> u = {{1, 2, 3}, {4, 5, 6}};
  const stack::StateView onlyDisplacement{&u, nullptr, nullptr};
  int computed = 0;
  for (const auto& f : stack::stateFields())
    if (const auto values = f.values(onlyDisplacement, f.component)) {
      ++computed;
      EXPECT_EQ((*values)[1], u[1][f.component]) << f.name;
    }
  EXPECT_EQ(computed, 3);
}
