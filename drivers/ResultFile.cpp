// The Exodus result of a run (ResultFile.hpp).
#include "ResultFile.hpp"

#include <iostream>
#include <sstream>

#include "tribos/core/Errors.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/stack/RunReport.hpp"

namespace tribos::driver {

namespace {
/// Three nodal fields <prefix>x, <prefix>y, <prefix>z from one vector per node.
void addVectorField(const std::string& prefix, const std::vector<std::array<double, 3>>& v, mesh::TimeStep& step) {
  for (int c = 0; c < 3; ++c) {
    mesh::Field f{prefix + "xyz"[c], std::vector<double>(v.size())};
    for (size_t n = 0; n < v.size(); ++n) f.values[n] = v[n][c];
    step.nodal.push_back(std::move(f));
  }
}

void addStressFields(const stack::StressResults& stress, mesh::TimeStep& step) {
  for (int k = 0; k < 6; ++k) {
    step.element.push_back({std::string("stress_") + stack::kStressComponents[k], stress.element[k]});
    step.nodal.push_back({std::string("nodal_stress_") + stack::kStressComponents[k], stress.nodal[k]});
  }
  step.element.push_back({"von_mises", stress.elementVonMises});
  step.nodal.push_back({"nodal_von_mises", stress.nodalVonMises});
}

void addContactFields(const stack::ContactFields& c, mesh::TimeStep& step) {
  for (const auto& field : stack::kContactNodalFields) step.nodal.push_back({field.name, c.*field.values});
}

}  // namespace

mesh::Field subdomainField(const stack::Scene& scene) {
  mesh::Field subdomain{"subdomain", std::vector<double>(scene.mesh.numElements())};
  for (LO e = 0; e < scene.mesh.numElements(); ++e) subdomain.values[e] = scene.decomposition.elementPart[e];
  return subdomain;
}

mesh::TimeStep timeStep(const OutputStep& data, const mesh::Field& subdomain) {
  mesh::TimeStep step;
  step.time = data.displacement ? data.time : 0.0;
  if (data.displacement) addVectorField("displ_", *data.displacement, step);
  if (data.reaction) addVectorField("reaction_", *data.reaction, step);
  if (data.stress) addStressFields(*data.stress, step);
  if (data.contact) addContactFields(*data.contact, step);
  step.element.push_back(subdomain);
  step.global = data.globals;
  if (data.contact)  // the restart's check of the memory (stack::contactMemorySum)
    step.global.push_back({"contact_memory_sum",
                           stack::contactMemorySum(data.contact->contactTangentialT1, data.contact->contactTangentialT2,
                                                   data.contact->contactAccumulatedSlip)});
  return step;
}

void writeOutput(const std::string& path, const stack::Scene& scene, const OutputData& data) {
  const mesh::Field subdomain = subdomainField(scene);
  std::vector<mesh::TimeStep> steps;
  for (const auto& step : data.steps) steps.push_back(timeStep(step, subdomain));
  mesh::writeExodus(path, scene.mesh, steps, data.info);
}

/// The result file says how it was made: the command line and the effective parameter list
/// (defaults filled in) as XML, one info record per line.
std::vector<std::string> infoRecords(int argc, char** argv, const Teuchos::ParameterList& params) {
  std::string command = "tribos";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  std::vector<std::string> info = {"Tribos result", command};
  std::istringstream lines(core::parameterListToXml(params));
  for (std::string line; std::getline(lines, line);) info.push_back(line);
  return info;
}

/// Per-step global variables: the summary's counts and KKT residuals (numbers only).
std::vector<mesh::GlobalValue> globalValues(const nlohmann::json& summary) {
  std::vector<mesh::GlobalValue> out;
  for (const char* key : {"converged", "outer_iterations", "inner_iterations", "pfp_applications",
                          "fixed_point_iterations", "strain_energy", "force_balance", "dissipated_energy"})
    if (summary.contains(key))
      out.push_back({key, summary[key].is_boolean() ? double(summary[key].get<bool>()) : summary[key].get<double>()});
  if (summary.contains("step")) out.push_back({"load_step", summary["step"].get<double>()});  // a load history's
  if (summary.contains("kkt"))
    for (const auto& [name, value] : summary["kkt"].items())
      if (value.is_number()) out.push_back({"kkt_" + name, value.get<double>()});
  // Per contact interface: "<name>_normal_force", ... ("contact_..." for the flat Contact list).
  if (summary.contains("interfaces"))
    for (const auto& i : summary["interfaces"]) {
      const std::string name = i.value("name", std::string());
      const std::string prefix = (name.empty() ? std::string("contact") : name) + "_";
      for (const char* key : {"normal_force", "friction_force", "no_contact", "stick", "slip", "peak_pressure",
                              "largest_opening", "largest_overlap", "dissipated_energy"})
        if (i.contains(key) && i[key].is_number()) out.push_back({prefix + key, i[key].get<double>()});
      if (i.contains("contact_force"))
        for (int c = 0; c < 3; ++c) out.push_back({prefix + "force_" + "xyz"[c], i["contact_force"][c].get<double>()});
    }
  // Per pretension section: "<name>_pretension_force" and "<name>_pretension_shortening" (a
  // restart takes the shortening a section was locked at from it).
  if (summary.contains("pretension"))
    for (const auto& s : summary["pretension"]) {
      const std::string name = s["name"].get<std::string>() + "_pretension_";
      out.push_back({name + "force", s["force"].get<double>()});
      out.push_back({name + "shortening", s["shortening"].get<double>()});
    }
  return out;
}

}  // namespace tribos::driver
