#pragma once
// The Exodus result of a run (step (6) of drivers/tribos.cpp): its time steps, fields and
// global variables, and the checkpoints of a load history (Load Steps/Checkpoint Seconds).
#include <Teuchos_ParameterList.hpp>

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tribos/core/OutputFile.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/stack/ContactSolve.hpp"
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
  std::vector<mesh::GlobalValue> globals;
};

/// Everything the Exodus result shows besides the mesh: one time step, or one per load step.
struct OutputData {
  std::vector<OutputStep> steps{1};
  std::vector<std::string> info;
};

/// Writes the Exodus result at `path`: the mesh, the subdomain of every element and the steps.
void writeOutput(const std::string& path, const stack::Scene& scene, const OutputData& data);

/// The result file says how it was made: the command line and the effective parameter list
/// (defaults filled in) as XML, one info record per line.
std::vector<std::string> infoRecords(int argc, char** argv, const Teuchos::ParameterList& params);

/// Per-step global variables: the summary's counts and KKT residuals (numbers only), of the
/// summary itself or of one entry of its steps.
std::vector<mesh::GlobalValue> globalValues(const nlohmann::json& summary);

/// The checkpoints of a load history (Load Steps/Checkpoint Seconds; issue 43): after a
/// converged step, once the interval has passed since the run started or the last checkpoint,
/// rank 0 writes the result file with every step converged so far, as the final write would
/// show them (their stresses computed once each). A write that fails is a warning, not the end
/// of the run: the final write reports its own failure. Given on every rank (StepObserver).
class Checkpoints {
 public:
  /// `exodus`: the result file on rank 0, null elsewhere.
  Checkpoints(const stack::Scene& scene, core::OutputFile* exodus, double seconds, std::vector<std::string> info,
              int rank);
  void operator()(const stack::ContactSolveResult& soFar);
  int written() const { return written_; }

 private:
  void write(const stack::ContactSolveResult& soFar);
  const stack::Scene& scene_;
  core::OutputFile* exodus_;
  double seconds_;
  std::vector<std::string> info_;
  int rank_;
  core::Stopwatch since_;
  std::vector<stack::StressResults> stress_;  ///< per step written so far
  std::vector<std::vector<mesh::GlobalValue>> globals_;
  int written_ = 0;
};

}  // namespace tribos::driver
