#pragma once
// The Exodus result of a run (step (6) of drivers/tribos.cpp): its time steps, fields and
// global variables (a load history's, step by step: HistoryResults.hpp).
#include <Teuchos_ParameterList.hpp>

#include <array>
#include <string>
#include <vector>

#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/stack/ContactFields.hpp"
#include "tribos/stack/Results.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::driver {

/// One time step of the Exodus result; null pointers: not computed (dry run).
struct OutputStep {
  double time = 0.0;
  const std::vector<std::array<double, 3>>* displacement = nullptr;
  const std::vector<std::array<double, 3>>* reaction = nullptr;
  const stack::StressResults* stress = nullptr;
  const stack::ContactFields* contact = nullptr;  ///< scenes with contact interfaces
  std::vector<mesh::GlobalValue> globals;  ///< stack::globalVariables of the step
};

/// Everything the Exodus result shows besides the mesh: one time step, or one per load step.
struct OutputData {
  std::vector<OutputStep> steps{1};
  std::vector<std::string> info;
};

/// The subdomain of every element, as the result shows it.
mesh::Field subdomainField(const stack::Scene& scene);
/// One time step of the Exodus result: its fields, `subdomain` and its global variables (with
/// contact_memory_sum where it has contact fields).
mesh::TimeStep timeStep(const OutputStep& data, const mesh::Field& subdomain);

/// Writes the Exodus result at `path`: the mesh, the subdomain of every element and the steps.
void writeOutput(const std::string& path, const stack::Scene& scene, const OutputData& data);

/// The result file says how it was made: the command line and the effective parameter list
/// (defaults filled in) as XML, one info record per line.
std::vector<std::string> infoRecords(int argc, char** argv, const Teuchos::ParameterList& params);

}  // namespace tribos::driver
