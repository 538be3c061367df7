// The Exodus result of a run (ResultFile.hpp).
#include "ResultFile.hpp"

#include <iostream>
#include <sstream>

#include "tribos/core/Errors.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/stack/OutputRegistry.hpp"

namespace tribos::driver {

namespace {
/// The state's fields (stack::stateFields) and contact fields (stack::kContactNodalFields).
void addStateFields(const OutputStep& data, mesh::TimeStep& step) {
  const stack::StateView view{data.displacement, data.reaction, data.stress};
  for (const auto& field : stack::stateFields())
    if (auto values = field.values(view, field.component))
      (field.location == stack::FieldLocation::Node ? step.nodal : step.element).push_back({field.name, std::move(*values)});
  if (data.contact)
    for (const auto& field : stack::kContactNodalFields) step.nodal.push_back({field.name, data.contact->*field.values});
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
  addStateFields(data, step);
  step.element.push_back(subdomain);
  step.global = data.globals;
  if (data.contact)  // the restart's check of the memory (stack::contactMemorySum)
    step.global.push_back({stack::variable::kContactMemorySum,
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

}  // namespace tribos::driver
