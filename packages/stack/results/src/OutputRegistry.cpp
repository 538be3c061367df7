// The output registry (OutputRegistry.hpp).
#include "tribos/stack/OutputRegistry.hpp"

#include <algorithm>

#include "tribos/contact/ContactSolver.hpp"
#include "tribos/core/EnumNames.hpp"
#include "tribos/stack/SolveResults.hpp"

namespace tribos::stack {

namespace {
template <class T>
std::optional<double> asNumber(const std::optional<T>& v) {
  return v ? std::optional<double>(static_cast<double>(*v)) : std::nullopt;
}

/// The residuals of the contact conditions (contact::KktReport) and their tolerance, by name.
std::vector<std::pair<std::string, double>> contactKkt(const contact::KktReport& kkt, double tolerance) {
  return {{"equilibrium", kkt.equilibrium},
          {"gluing_dirichlet", kkt.equality},
          {"non_penetration", kkt.nonPenetration},
          {"complementarity", kkt.complementarity},
          {"normal_sign", kkt.normalSign},
          {"friction_admissibility", kkt.frictionAdmissibility},
          {"slip_rule", kkt.slipRule},
          {"stick_rule", kkt.stickRule},
          {"tolerance", tolerance}};
}

/// In name order: how the summary lists them, and so the result file.
std::vector<std::pair<std::string, double>> byName(std::vector<std::pair<std::string, double>> list) {
  std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return list;
}

void putNumber(nlohmann::json& j, const std::string& key, NumberKind kind, double value) {
  if (kind == NumberKind::Flag)
    j[key] = value != 0.0;
  else if (kind == NumberKind::Count)
    j[key] = static_cast<long long>(value);
  else
    j[key] = value;
}

std::optional<std::vector<double>> vectorComponent(const std::vector<std::array<double, 3>>* v, int c) {
  if (!v) return std::nullopt;
  std::vector<double> out(v->size());
  for (size_t n = 0; n < v->size(); ++n) out[n] = (*v)[n][c];
  return out;
}
}  // namespace

const std::array<StepNumber, 9> kStepNumbers{{
    {"converged", variable::kConverged, NumberKind::Flag, [](const StepOutcome& o) { return asNumber(o.converged); }},
    {"outer_iterations", "outer_iterations", NumberKind::Count,
     [](const StepOutcome& o) { return asNumber(o.outerIterations); }},
    {"inner_iterations", "inner_iterations", NumberKind::Count,
     [](const StepOutcome& o) { return asNumber(o.innerIterations); }},
    {"pfp_applications", "pfp_applications", NumberKind::Count,
     [](const StepOutcome& o) { return asNumber(o.pfpApplications); }},
    {"fixed_point_iterations", "fixed_point_iterations", NumberKind::Count,
     [](const StepOutcome& o) { return asNumber(o.fixedPointIterations); }},
    {"strain_energy", "strain_energy", NumberKind::Real, [](const StepOutcome& o) { return o.strainEnergy; }},
    {"force_balance", "force_balance", NumberKind::Real, [](const StepOutcome& o) { return o.forceBalance; }},
    {variable::kDissipatedEnergy, variable::kDissipatedEnergy, NumberKind::Real,
     [](const StepOutcome& o) { return o.dissipatedEnergy; }},
    {"step", variable::kLoadStep, NumberKind::Count, [](const StepOutcome& o) { return asNumber(o.loadStep); }},
}};

const std::array<InterfaceNumber, 9> kInterfaceNumbers{{
    {"normal_force", NumberKind::Real, [](const InterfaceResult& i) { return i.normalForce; }},
    {"friction_force", NumberKind::Real, [](const InterfaceResult& i) { return i.frictionForce; }},
    {"no_contact", NumberKind::Count, [](const InterfaceResult& i) { return double(i.counts[0]); }},
    {"stick", NumberKind::Count, [](const InterfaceResult& i) { return double(i.counts[1]); }},
    {"slip", NumberKind::Count, [](const InterfaceResult& i) { return double(i.counts[2]); }},
    {"peak_pressure", NumberKind::Real, [](const InterfaceResult& i) { return i.peakPressure; }},
    {"largest_opening", NumberKind::Real, [](const InterfaceResult& i) { return i.largestOpening; }},
    {"largest_overlap", NumberKind::Real, [](const InterfaceResult& i) { return i.largestOverlap; }},
    {variable::kDissipatedEnergy, NumberKind::Real, [](const InterfaceResult& i) { return i.dissipatedEnergy; }},
}};

const std::array<SectionNumber, 2> kSectionNumbers{{
    {"force", [](const SectionState& s) { return s.force; }},
    {variable::kSectionShortening, [](const SectionState& s) { return s.shortening; }},
}};

std::string interfaceVariable(const std::string& interfaceName, const std::string& key) {
  return (interfaceName.empty() ? std::string("contact") : interfaceName) + "_" + key;
}

std::string sectionVariable(const std::string& sectionName, const std::string& key) {
  return sectionName + "_pretension_" + key;
}

StepOutcome outcomeOf(const ContactSolveResult& solve) {
  const auto& r = solve.contact;
  StepOutcome o;
  o.converged = r.converged;
  o.outerIterations = r.counters.outerIterations;
  o.innerIterations = r.counters.innerIterations;
  o.pfpApplications = r.counters.operatorApplications;
  o.fixedPointIterations = r.fixedPointIterations;
  o.dissipatedEnergy = solve.dissipatedEnergy;
  auto kkt = contactKkt(r.kkt, r.kktTolerance);
  kkt.push_back({"projected_gradient", r.counters.projectedGradient});
  kkt.push_back({"equality_constraint", r.counters.equalityResidual});
  kkt.push_back({"max_copy_jump", solve.displacement.maxCopyJump});
  o.kkt = byName(std::move(kkt));
  o.interfaces = &solve.interfaces;
  return o;
}

StepOutcome outcomeOf(const ContactSolveResult& solve, size_t i) {
  const LoadStepRecord& k = solve.steps[i];
  const ContactFields& fields = i < solve.earlierSteps.size() ? solve.earlierSteps[i] : solve;
  StepOutcome o;
  o.converged = k.converged;
  o.outerIterations = k.outerIterations;
  o.pfpApplications = k.pfpApplications;
  o.fixedPointIterations = k.fixedPointIterations;
  o.dissipatedEnergy = fields.dissipatedEnergy;
  o.loadStep = k.step;
  o.kkt = byName(contactKkt(k.kkt, k.kktTolerance));
  o.interfaces = &fields.interfaces;
  o.sections = &k.sections;
  return o;
}

StepOutcome outcomeOf(const LinearFetiResult& linear) {
  StepOutcome o;
  o.converged = linear.converged;
  o.outerIterations = linear.iterations;
  o.pfpApplications = linear.fApplications;
  o.kkt = byName({{"projected_residual", linear.relativeResidual},
                  {"equilibrium", linear.equilibriumResidual},
                  {"equality_constraints", linear.constraintResidual},
                  {"max_copy_jump", linear.maxCopyJump}});
  if (!linear.interfaces.empty()) o.interfaces = &linear.interfaces;  // bonded interfaces
  return o;
}

StepOutcome withStresses(StepOutcome outcome, const StressResults& stress, const ForceBalance& balance) {
  outcome.strainEnergy = stress.strainEnergy;
  outcome.forceBalance = balance.relativeImbalance;
  return outcome;
}

nlohmann::json interfaceSummary(const std::vector<InterfaceResult>& interfaces) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& i : interfaces) {
    nlohmann::json entry = {{"name", i.name},
                            {"interface", i.surfaces},
                            {"friction_model", core::nameOf(contact::kFrictionModelNames, i.law.model)},
                            {kInterfaceForceKey, i.force}};
    for (const auto& number : kInterfaceNumbers) putNumber(entry, number.key, number.kind, number.value(i));
    list.push_back(std::move(entry));
  }
  return list;
}

void addStepNumbers(const StepOutcome& outcome, nlohmann::json& summary) {
  for (const auto& number : kStepNumbers)
    if (const auto value = number.value(outcome)) putNumber(summary, number.summaryKey, number.kind, *value);
  if (!outcome.kkt.empty())
    for (const auto& [name, value] : outcome.kkt) summary["kkt"][name] = value;
  if (outcome.interfaces) summary["interfaces"] = interfaceSummary(*outcome.interfaces);
  if (outcome.sections)
    for (const auto& s : *outcome.sections) {
      nlohmann::json entry = {{"name", s.name}};
      for (const auto& number : kSectionNumbers) entry[number.key] = number.value(s);
      summary["pretension"].push_back(std::move(entry));
    }
}

std::vector<mesh::GlobalValue> globalVariables(const StepOutcome& outcome) {
  std::vector<mesh::GlobalValue> out;
  for (const auto& number : kStepNumbers)
    if (const auto value = number.value(outcome)) out.push_back({number.variable, *value});
  for (const auto& [name, value] : outcome.kkt) out.push_back({"kkt_" + name, value});
  if (outcome.interfaces)
    for (const auto& i : *outcome.interfaces) {
      for (const auto& number : kInterfaceNumbers) out.push_back({interfaceVariable(i.name, number.key), number.value(i)});
      for (int c = 0; c < 3; ++c) out.push_back({interfaceVariable(i.name, std::string("force_") + "xyz"[c]), i.force[c]});
    }
  if (outcome.sections)
    for (const auto& s : *outcome.sections)
      for (const auto& number : kSectionNumbers) out.push_back({sectionVariable(s.name, number.key), number.value(s)});
  return out;
}

const std::vector<StateField>& stateFields() {
  static const std::vector<StateField> fields = [] {
    std::vector<StateField> list;
    const auto displacement = [](const StateView& s, int c) { return vectorComponent(s.displacement, c); };
    const auto reaction = [](const StateView& s, int c) { return vectorComponent(s.reaction, c); };
    for (int c = 0; c < 3; ++c) list.push_back({displacementField(c), FieldLocation::Node, displacement, c});
    for (int c = 0; c < 3; ++c)
      list.push_back({std::string("reaction_") + "xyz"[c], FieldLocation::Node, reaction, c});
    using Values = std::optional<std::vector<double>>;
    const auto element = [](const StateView& s, int c) { return s.stress ? Values(s.stress->element[c]) : std::nullopt; };
    const auto nodal = [](const StateView& s, int c) { return s.stress ? Values(s.stress->nodal[c]) : std::nullopt; };
    for (int c = 0; c < 6; ++c) {
      list.push_back({std::string("stress_") + kStressComponents[c], FieldLocation::Element, element, c});
      list.push_back({std::string("nodal_stress_") + kStressComponents[c], FieldLocation::Node, nodal, c});
    }
    list.push_back({"von_mises", FieldLocation::Element,
                    [](const StateView& s, int) { return s.stress ? Values(s.stress->elementVonMises) : std::nullopt; }, 0});
    list.push_back({"nodal_von_mises", FieldLocation::Node,
                    [](const StateView& s, int) { return s.stress ? Values(s.stress->nodalVonMises) : std::nullopt; }, 0});
    return list;
  }();
  return fields;
}

std::string displacementField(int component) { return std::string("displ_") + "xyz"[component]; }

}  // namespace tribos::stack
