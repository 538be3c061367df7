#pragma once
/// \file OutputRegistry.hpp
/// The output registry (issue 40): every number and field a time step of a run shows, each
/// declared once with its name and what it is made of. The JSON summary, the Exodus result's
/// global variables and fields, and the restart reader take their names and values from here;
/// nothing is read back from the summary. Per-node contact fields have their own table
/// (kContactNodalFields, ContactFields.hpp), which this one refers to.
///
/// A new global number is a member of StepOutcome, where it is filled (outcomeOf...), and a
/// line in kStepNumbers (or kInterfaceNumbers, kSectionNumbers); a new field is a line in
/// kStateFields. doc/design.md, "Extending Tribos", has the recipe.
#include <nlohmann/json.hpp>

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/stack/ContactFields.hpp"
#include "tribos/stack/Results.hpp"

namespace tribos::stack {

struct SectionState;        // SolveResults.hpp
struct ContactSolveResult;  // SolveResults.hpp
struct LinearFetiResult;    // SolveResults.hpp

/// What one time step's numbers are made of, typed. Absent: not part of this kind of run (the
/// inner iterations of a history's step, the dissipated energy of a linear solve) or not
/// computed yet (the strain energy before the stresses).
struct StepOutcome {
  std::optional<bool> converged;
  std::optional<long long> outerIterations, innerIterations, pfpApplications, fixedPointIterations;
  std::optional<double> strainEnergy, forceBalance, dissipatedEnergy;
  std::optional<int> loadStep;  ///< a load history's step
  /// The KKT residuals (and their tolerance) by name, in name order.
  std::vector<std::pair<std::string, double>> kkt;
  const std::vector<InterfaceResult>* interfaces = nullptr;  ///< none: no interface results
  const std::vector<SectionState>* sections = nullptr;       ///< none or empty: no pretension
};

/// How the summary writes a number (the result file holds every one as a double).
enum class NumberKind { Flag, Count, Real };

/// One number of a step: its key in the summary (and its step entries), its global variable in
/// the result file, and its value where the step has it.
struct StepNumber {
  const char* summaryKey;
  const char* variable;
  NumberKind kind;
  std::optional<double> (*value)(const StepOutcome&);
};
/// In the order of the result file's global variables, which go on with the KKT residuals
/// ("kkt_<name>"), each interface's numbers and each pretension section's.
extern const std::array<StepNumber, 9> kStepNumbers;

/// One number of each contact interface: its key in the summary's interfaces[i], and in the
/// result file "<interface>_<key>" (interfaceVariable).
struct InterfaceNumber {
  const char* key;
  NumberKind kind;
  double (*value)(const InterfaceResult&);
};
extern const std::array<InterfaceNumber, 9> kInterfaceNumbers;
/// The interface's resultant contact force: the summary's "contact_force" [x, y, z], the result
/// file's "<interface>_force_x", _y, _z.
inline constexpr const char* kInterfaceForceKey = "contact_force";

/// One number of each pretension section: its key in the summary's pretension[i], and in the
/// result file "<section>_pretension_<key>" (sectionVariable).
struct SectionNumber {
  const char* key;
  double (*value)(const SectionState&);
};
extern const std::array<SectionNumber, 2> kSectionNumbers;

/// Global variables that the registry's tables name and other code reads by that name.
namespace variable {
inline constexpr const char* kConverged = "converged";
inline constexpr const char* kLoadStep = "load_step";
/// The friction work so far: the step's (kStepNumbers) and each interface's key (kInterfaceNumbers).
inline constexpr const char* kDissipatedEnergy = "dissipated_energy";
/// A pretension section's locked shortening (kSectionNumbers' key; a restart continues from it).
inline constexpr const char* kSectionShortening = "shortening";
/// The restart's check of the friction memory (contactMemorySum): written with every step that
/// has contact fields.
inline constexpr const char* kContactMemorySum = "contact_memory_sum";
}  // namespace variable

/// "<name>_<key>" of an interface ("contact_<key>" for the flat Contact list's, named "").
std::string interfaceVariable(const std::string& interfaceName, const std::string& key);
/// "<section>_pretension_<key>".
std::string sectionVariable(const std::string& sectionName, const std::string& key);

/// The step of a single contact solve (the summary's top level): its counts, KKT residuals with
/// the solver's own (projected gradient, equality constraint, copy jump), interfaces.
StepOutcome outcomeOf(const ContactSolveResult& solve);
/// Step i of a load history (ContactSolveResult::steps; its fields from earlierSteps, the last
/// from the solve itself).
StepOutcome outcomeOf(const ContactSolveResult& solve, size_t i);
/// A linear (bonded) solve.
StepOutcome outcomeOf(const LinearFetiResult& linear);
/// The outcome with the strain energy and the force balance of its state.
StepOutcome withStresses(StepOutcome outcome, const StressResults& stress, const ForceBalance& balance);

/// The step's numbers into a summary object: the keys of kStepNumbers it has, "kkt",
/// "interfaces" (names, laws, numbers, resultants) and "pretension".
void addStepNumbers(const StepOutcome& outcome, nlohmann::json& summary);
/// Its interfaces as the summary lists them.
nlohmann::json interfaceSummary(const std::vector<InterfaceResult>& interfaces);
/// The result file's global variables of the step, in the registry's order.
std::vector<mesh::GlobalValue> globalVariables(const StepOutcome& outcome);

/// Where a field of a state lives in the result file.
enum class FieldLocation { Node, Element };
/// What a state's fields are made of (null: not computed, a dry run).
struct StateView {
  const std::vector<std::array<double, 3>>* displacement = nullptr;
  const std::vector<std::array<double, 3>>* reaction = nullptr;
  const StressResults* stress = nullptr;
};
/// One field of a state (the contact fields: kContactNodalFields): its name in the result file,
/// where it lives, and its values (none where the state lacks what it is made of).
struct StateField {
  std::string name;
  FieldLocation location;
  std::optional<std::vector<double>> (*values)(const StateView&, int component);
  int component;
};
/// Every field of a state, in the result file's order: displ_x/y/z, reaction_x/y/z, the six
/// element and nodal stresses (kStressComponents), von Mises of both.
const std::vector<StateField>& stateFields();
/// The result's name of displacement component c (0, 1, 2): "displ_x", ... (the restart reads it).
std::string displacementField(int component);

}  // namespace tribos::stack
