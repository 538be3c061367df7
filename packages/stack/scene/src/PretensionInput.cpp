// Pretension/<name> read into the scene (PretensionInput.hpp).
#include "PretensionInput.hpp"

#include <Teuchos_ParameterList.hpp>

#include <algorithm>

#include "tribos/core/Errors.hpp"

namespace tribos::stack {

namespace {
// A "*" sublist's entry, or its default (validation fills in no defaults under "*").
template <class T>
T valueOr(const Teuchos::ParameterList& list, const std::string& name, const T& fallback) {
  return list.isParameter(name) ? list.get<T>(name) : fallback;
}

/// Pretension/<name>: the section, checked against the scene.
PretensionSection readSection(const Teuchos::ParameterList& sub, const std::string& name, const std::string& where,
                              const Scene& scene) {
  PretensionSection section;
  section.name = name;
  const std::string interface = valueOr(sub, "Interface", std::string());
  core::requireInput(!interface.empty(), where + ": \"Interface\" is required (a Contact/<name> with Friction Model "
                                                 "Bonded: the two sides of the cut)");
  const auto it = std::find_if(scene.contacts.begin(), scene.contacts.end(),
                               [&](const ContactInterface& one) { return one.rows.name == interface; });
  core::requireInput(it != scene.contacts.end(), where + "/Interface: no Contact/" + interface + " in the scene");
  core::requireInput(it->law.tiesSurfaces(), where + "/Interface: Contact/" + interface +
                                                 " is not Bonded (a pretension section is a cut whose sides are "
                                                 "glued: give it Friction Model Bonded)");
  section.interface = static_cast<size_t>(it - scene.contacts.begin());
  const bool force = sub.isParameter("Force"), shortening = sub.isParameter("Shortening");
  core::requireInput(force != shortening, where + ": give Force or Shortening, one of them");
  section.byForce = force;
  section.target = sub.get<double>(force ? "Force" : "Shortening");
  core::requireInput(section.target > 0.0, where + (force ? "/Force" : "/Shortening") + " must be > 0");
  section.steps = valueOr(sub, "Steps", 1);
  core::requireInput(section.steps <= scene.loadSteps,
                     where + "/Steps = " + std::to_string(section.steps) + " exceeds Load Steps/Number Of Steps = " +
                         std::to_string(scene.loadSteps));
  section.forceTolerance = valueOr(sub, "Force Tolerance", 1e-6);
  return section;
}
}  // namespace

void readPretensions(const Teuchos::ParameterList& list, const std::string& source, Scene& scene) {
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (!list.entry(it).isList()) continue;
    const std::string name = list.name(it);
    const std::string where = source + ": Pretension/" + name;
    PretensionSection section = readSection(list.sublist(name), name, where, scene);
    for (const auto& other : scene.pretensions)
      core::requireInput(other.interface != section.interface,
                         where + "/Interface: Contact/" + scene.contacts[section.interface].rows.name +
                             " is already the section Pretension/" + other.name);
    scene.pretensions.push_back(section);
    scene.loadHistory = true;
  }
}

}  // namespace tribos::stack
