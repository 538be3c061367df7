// libFuzzer target: the restart reader (Load Steps/Restart From; stack/history/src/Restart.cpp), issue 44.
// A restart file is a tribos result, a netCDF file the Exodus library reads; what the reader
// itself must survive is a result whose *values and layout* are damaged, and a file cut anywhere
// (a job killed while writing). So the fuzz input is read as a list of edits to a valid 2-step
// result of block_on_plate.xml (built once, from the scene and its B): nodal and global values
// set to any double, steps removed or repeated, variables dropped or renamed, a step marked not
// converged; the damaged result is written with mesh::writeExodus and optionally cut at any byte.
// readRestart must then throw core::InputError or return a state a history can continue from
// (a step within the scene, finite memory within 1e100, no negative accumulated slip, one energy
// per interface); anything else (another exception, a crash, a sanitizer report, a timeout) is a
// finding. Byte mutations of the netCDF header itself are not made: they test libnetcdf, not us.
#include <Teuchos_ParameterList.hpp>
#include <fuzzer/FuzzedDataProvider.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "tribos/stack/Restart.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/core/XmlParameters.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/stack/ContactFields.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/SceneParameters.hpp"

namespace {
using namespace tribos;

const char* const kNodal[] = {"contact_master", "contact_tangential_t1", "contact_tangential_t2",
                              "contact_accumulated_slip"};
const char* const kGlobal[] = {"load_step", "converged", "contact_memory_sum", "contact_dissipated_energy",
                               "dissipated_energy"};

struct Base {
  stack::Scene scene;
  feti::ConstraintMatrix B;
  std::vector<mesh::TimeStep> steps;  ///< a valid 2-step history result of the scene
  std::string file;                   ///< where each input's damaged result is written
};

stack::Scene blockOnPlate(int loadSteps) {
  const std::string source = TRIBOS_SOURCE_DIR "/input/block_on_plate.xml";
  std::ifstream in(source);
  std::stringstream text;
  text << in.rdbuf();
  auto list = core::parameterListFromXml(text.str(), source);
  list->sublist("Load Steps").set("Number Of Steps", loadSteps);
  core::validateAndSetDefaults(*list, *stack::sceneValidParameters(), source);
  return stack::buildScene(*list, source);
}

// Step k of a history the reader accepts: the contact memory at B's slave nodes.
mesh::TimeStep validStep(const feti::ConstraintMatrix& B, size_t numNodes, int k) {
  std::vector<double> master(numNodes, 0.0), t1(numNodes, 0.0), t2(numNodes, 0.0), slip(numNodes, 0.0);
  for (const auto& node : B.contact) {
    const size_t n = static_cast<size_t>(node.slaveNode);
    master[n] = node.masterNode + 1.0;
    t1[n] = 1e-4 * k * static_cast<double>(n % 7);
    t2[n] = -2e-5 * static_cast<double>(n % 3);
    slip[n] = 3e-5 * k;
  }
  mesh::TimeStep step;
  step.time = k;
  const double sum = stack::contactMemorySum(t1, t2, slip);
  step.nodal = {{kNodal[0], master}, {kNodal[1], t1}, {kNodal[2], t2}, {kNodal[3], slip}};
  step.global = {{kGlobal[0], double(k)}, {kGlobal[1], 1.0}, {kGlobal[2], sum}, {kGlobal[3], 0.01 * k},
                 {kGlobal[4], 0.01 * k}};
  return step;
}

const Base& base() {
  static const Base b = [] {
    Base made{blockOnPlate(4), {}, {}, {}};
    made.B = feti::buildConstraintMatrix(made.scene.mesh, made.scene.decomposition, stack::constraintSpec(made.scene),
                                         1, 0);
    const size_t numNodes = static_cast<size_t>(made.scene.mesh.numNodes());
    made.steps = {validStep(made.B, numNodes, 1), validStep(made.B, numNodes, 2)};
    made.file = (std::filesystem::temp_directory_path() / ("fuzz_restart_" + std::to_string(getpid()) + ".exo")).string();
    return made;
  }();
  static const bool cleanUp = [] {  // the damaged file of the last input goes when the run ends
    std::atexit([] { std::remove(b.file.c_str()); });
    return true;
  }();
  (void)cleanUp;
  return b;
}

// One edit of the input to the steps (any index wraps onto what exists).
void edit(FuzzedDataProvider& in, std::vector<mesh::TimeStep>& steps) {
  if (steps.empty()) return;
  auto& step = steps[in.ConsumeIntegralInRange<size_t>(0, steps.size() - 1)];
  switch (in.ConsumeIntegralInRange(0, 5)) {
    case 0: {  // a nodal value
      if (step.nodal.empty()) return;
      auto& values = step.nodal[in.ConsumeIntegralInRange<size_t>(0, step.nodal.size() - 1)].values;
      values[in.ConsumeIntegralInRange<size_t>(0, values.size() - 1)] = in.ConsumeFloatingPoint<double>();
      return;
    }
    case 1:  // a global value
      if (!step.global.empty())
        step.global[in.ConsumeIntegralInRange<size_t>(0, step.global.size() - 1)].value = in.ConsumeFloatingPoint<double>();
      return;
    case 2:  // a step removed
      steps.erase(steps.begin() + static_cast<long>(&step - steps.data()));
      return;
    case 3:  // a step repeated
      steps.push_back(step);
      return;
    case 4:  // a nodal variable renamed (or dropped from this step: then every step, as a file holds)
      if (!step.nodal.empty()) step.nodal[in.ConsumeIntegralInRange<size_t>(0, step.nodal.size() - 1)].name += "_x";
      return;
    default:  // a global variable renamed
      if (!step.global.empty()) step.global[in.ConsumeIntegralInRange<size_t>(0, step.global.size() - 1)].name += "_x";
  }
}

// Exodus files hold one set of variable names for every step: the first step's decides.
void sameVariablesInEveryStep(std::vector<mesh::TimeStep>& steps) {
  for (auto& step : steps) {
    for (size_t i = 0; i < step.nodal.size(); ++i) step.nodal[i].name = steps.front().nodal[i].name;
    for (size_t i = 0; i < step.global.size(); ++i) step.global[i].name = steps.front().global[i].name;
  }
}

// What a state the reader returns must satisfy for the history to continue from it.
bool continuable(const stack::RestartState& s, const stack::Scene& scene) {
  const auto plausible = [](double v) { return std::isfinite(v) && std::abs(v) <= 1e100; };
  bool ok = s.step >= 1 && s.step < scene.loadSteps && plausible(s.totals.dissipatedEnergy) &&
            s.totals.interfaces.size() == scene.contacts.size();
  for (const auto* field : {&s.totals.contactTangentialT1, &s.totals.contactTangentialT2})
    for (double v : *field) ok = ok && plausible(v);
  for (double v : s.totals.contactAccumulatedSlip) ok = ok && plausible(v) && v >= 0.0;
  for (const auto& one : s.totals.interfaces) ok = ok && plausible(one.dissipatedEnergy);
  return ok;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const Base& b = base();
  FuzzedDataProvider in(data, size);
  std::vector<mesh::TimeStep> steps = b.steps;
  const int edits = in.ConsumeIntegralInRange(0, 6);
  for (int e = 0; e < edits; ++e) edit(in, steps);
  if (!steps.empty()) sameVariablesInEveryStep(steps);
  const bool cut = in.ConsumeBool();
  const double cutAt = in.ConsumeProbability<double>();
  try {
    mesh::writeExodus(b.file, b.scene.mesh, steps);
    if (cut) std::filesystem::resize_file(b.file, static_cast<uintmax_t>(cutAt * std::filesystem::file_size(b.file)));
    const auto state = stack::readRestart(b.file, b.scene, b.B);
    if (!continuable(state, b.scene)) __builtin_trap();  // accepted, and a history could not continue from it
  } catch (const core::InputError&) {
  }
  return 0;
}
