#include "tribos/stack/Restart.hpp"

#include <algorithm>
#include <cmath>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/core/RankErrors.hpp"
#include "tribos/core/Validators.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/stack/OutputRegistry.hpp"

namespace tribos::stack {
namespace {
const std::vector<double>& nodalField(const mesh::TimeStep& step, const std::string& name, const std::string& where) {
  const auto it = std::find_if(step.nodal.begin(), step.nodal.end(), [&](const auto& f) { return f.name == name; });
  core::requireInput(it != step.nodal.end(),
                     where + ": no nodal variable " + name + " (not a tribos load history result)");
  return it->values;
}

const double* globalValue(const mesh::TimeStep& step, const std::string& name) {
  const auto it = std::find_if(step.global.begin(), step.global.end(), [&](const auto& g) { return g.name == name; });
  return it == step.global.end() ? nullptr : &it->value;
}

// The file's mesh must be the scene's: the same nodes at the same places.
void requireSameNodes(const mesh::Mesh& file, const mesh::Mesh& scene, const std::string& where) {
  core::requireInput(file.numNodes() == scene.numNodes(),
                     where + ": " + std::to_string(file.numNodes()) + " nodes, the scene's mesh has " +
                         std::to_string(scene.numNodes()) + " (a result of another mesh)");
  double size = 0.0;
  for (const auto& x : scene.coords) size = std::max({size, std::abs(x[0]), std::abs(x[1]), std::abs(x[2])});
  for (LO n = 0; n < scene.numNodes(); ++n)
    for (int c = 0; c < 3; ++c)
      core::requireInput(std::abs(file.coords[n][c] - scene.coords[n][c]) <= 1e-9 * size,
                         where + ": node " + std::to_string(n + 1) + " is at " + core::formatPoint(file.coords[n]) +
                             ", in the scene's mesh at " + core::formatPoint(scene.coords[n]) +
                             " (a result of another mesh)");
}
// The file's contact pairs must be B's: the same master node at every slave node, and no
// tangential displacement or slip on a node that is not one of B's slave nodes (a file of a
// scene with other interfaces would hand its memory to the wrong nodes).
void requireSameContactNodes(const mesh::TimeStep& step, const feti::ConstraintMatrix& B, const std::string& where) {
  const auto& master = nodalField(step, nameOf(&ContactFields::contactMaster), where);
  std::vector<char> slave(master.size(), 0);
  for (const auto& node : B.contact) {
    const size_t n = static_cast<size_t>(node.slaveNode);
    slave[n] = 1;
    core::requireInput(master[n] != 0.0, where + ": node " + std::to_string(n + 1) +
                                             ", a slave node of this scene, is none there (a result of other contact "
                                             "interfaces, or a file cut or damaged)");
    core::requireInput(master[n] == static_cast<double>(node.masterNode + 1),
                       where + ": slave node " + std::to_string(n + 1) + " faces master node " +
                           core::formatNumber(master[n]) + " there and node " + std::to_string(node.masterNode + 1) +
                           " in this scene (a result of other contact interfaces)");
  }
  for (const char* name : {nameOf(&ContactFields::contactTangentialT1), nameOf(&ContactFields::contactTangentialT2),
                           nameOf(&ContactFields::contactAccumulatedSlip)}) {
    const auto& values = nodalField(step, name, where);
    for (size_t n = 0; n < values.size(); ++n)
      core::requireInput(slave[n] || values[n] == 0.0,
                         where + ": node " + std::to_string(n + 1) + " has " + name +
                             " there and is no slave node of this scene (a result of other contact interfaces)");
  }
}

// A memory value the next step can start from: finite, within the magnitudes the scene accepts
// (issue 44: NaN or 1e30 memory ended as "check the loads", a negative accumulated slip exit 0).
bool plausible(double v, bool nonNegative) {
  return std::isfinite(v) && std::abs(v) <= core::kMaxMagnitude && (!nonNegative || v >= 0.0);
}
std::string expected(bool nonNegative) {
  return nonNegative ? " (a finite value >= 0, at most 1e100, expected)" : " (a finite value of at most 1e100 in size expected)";
}
void requirePlausible(const std::vector<double>& values, const std::string& name, bool nonNegative,
                      const std::string& where) {
  for (size_t n = 0; n < values.size(); ++n)
    core::requireInput(plausible(values[n], nonNegative),
                       where + ": " + name + " at node " + std::to_string(n + 1) + " is " +
                           core::formatNumber(values[n]) + expected(nonNegative) +
                           ": the file is damaged or not tribos's");
}
void requirePlausible(double value, const std::string& name, const std::string& where) {
  core::requireInput(plausible(value, false), where + ": global variable " + name + " is " + core::formatNumber(value) +
                                                  expected(false) + ": the file is damaged or not tribos's");
}

// The displacement of every node at step k of the file (1 <= k <= the last converged step).
std::vector<std::array<double, 3>> fileDisplacement(const mesh::ExodusData& data, int k, int last,
                                                    const std::string& where) {
  core::requireInput(k >= 1 && k <= last, where + ": the displacement of step " + std::to_string(k) +
                                              " is needed (a condition holds its nodes where that step left them), "
                                              "and the file's last converged step is " + std::to_string(last));
  const mesh::TimeStep& step = data.steps[static_cast<size_t>(k - 1)];
  std::vector<std::array<double, 3>> u(data.mesh.coords.size());
  for (int c = 0; c < 3; ++c) {
    const std::string name = displacementField(c);
    const auto& values = nodalField(step, name, where);
    requirePlausible(values, name, false, where);
    for (size_t n = 0; n < u.size(); ++n) u[n][c] = values[n];
  }
  return u;
}

// Step k of a history is load_step k: 1, 2, ... in order (issue 44: -1 read the factor table
// before its start, 1.5 was taken as 1).
void requireStepNumber(double number, int expected, const std::string& where) {
  core::requireInput(number == static_cast<double>(expected),
                     where + ": its time step " + std::to_string(expected) + " has load_step " +
                         core::formatNumber(number) + " (1, 2, ... in order expected): the file is damaged or not "
                         "tribos's");
}
}  // namespace

RestartState readRestart(const std::string& file, const Scene& scene, const feti::ConstraintMatrix& B,
                         const std::vector<int>& displacementSteps) {
  const std::string where = "Load Steps/Restart From: " + file;
  mesh::ExodusData data;
  try {
    data = mesh::readExodus(file);
  } catch (const core::InputError& e) {
    throw core::InputError(where + ": " + e.what());
  }
  requireSameNodes(data.mesh, scene.mesh, where);
  // The last converged step; the steps before it converged too (a history stops at a failure).
  const mesh::TimeStep* last = nullptr;
  RestartState state;
  state.file = file;
  for (const auto& step : data.steps) {
    const double* number = globalValue(step, variable::kLoadStep);
    const double* converged = globalValue(step, variable::kConverged);
    core::requireInput(number && converged, where + ": no global variables load_step and converged (not a result of "
                                                    "a tribos load history)");
    requireStepNumber(*number, state.step + 1, where);
    core::requireInput(*converged == 0.0 || *converged == 1.0,
                       where + ": load step " + std::to_string(state.step + 1) + " has converged = " +
                           core::formatNumber(*converged) + " (0 or 1 expected): the file is damaged or not tribos's");
    if (*converged != 1.0) break;
    last = &step;
    state.step = static_cast<int>(*number);
  }
  core::requireInput(last != nullptr, where + ": no converged load step to continue from");
  core::requireInput(state.step < scene.loadSteps,
                     where + ": its last converged step is " + std::to_string(state.step) +
                         ", and the scene has Load Steps/Number Of Steps = " + std::to_string(scene.loadSteps) +
                         ": no step left to solve");
  requireSameContactNodes(*last, B, where);
  ContactFields& t = state.totals;
  // The friction memory the history reached (the total tangential displacement, of either sign,
  // and the accumulated slip, >= 0) and the contact forces the first new step starts from.
  for (auto [values, nonNegative] :
       {std::pair{&ContactFields::contactTangentialT1, false}, {&ContactFields::contactTangentialT2, false},
        {&ContactFields::contactAccumulatedSlip, true}, {&ContactFields::contactNormal, false},
        {&ContactFields::contactT1, false}, {&ContactFields::contactT2, false}}) {
    t.*values = nodalField(*last, nameOf(values), where);
    requirePlausible(t.*values, nameOf(values), nonNegative, where);
  }
  // A file cut inside its last step reads the missing values as zeros (issue 44: exit 0 with
  // the friction memory lost); results before this check have no sum, and are taken as they are.
  if (const double* sum = globalValue(*last, variable::kContactMemorySum)) {
    const double now = contactMemorySum(t.contactTangentialT1, t.contactTangentialT2, t.contactAccumulatedSlip);
    core::requireInput(std::abs(now - *sum) <= 1e-12 * std::abs(*sum),
                       where + ": load step " + std::to_string(state.step) + "'s contact memory sums to " +
                           core::formatNumber(now) + ", and the file recorded " + core::formatNumber(*sum) +
                           " with it: the file is cut or damaged");
  }
  for (const auto& one : scene.contacts) {
    const std::string name = interfaceVariable(one.rows.name, variable::kDissipatedEnergy);
    const double* energy = globalValue(*last, name);
    core::requireInput(energy != nullptr, where + ": no global variable " + name + " (the scene's " + one.rows.list() +
                                              " is not in that result)");
    t.interfaces.push_back({one.rows.name, one.rows.slaveSideSet + " -> " + one.rows.masterSideSet, one.law});
    t.interfaces.back().dissipatedEnergy = *energy;
    requirePlausible(*energy, name, where);
  }
  const double* total = globalValue(*last, variable::kDissipatedEnergy);
  core::requireInput(total != nullptr, where + ": no global variable dissipated_energy");
  t.dissipatedEnergy = *total;
  requirePlausible(*total, variable::kDissipatedEnergy, where);
  for (const auto& section : scene.pretensions) {
    const std::string name = sectionVariable(section.name, variable::kSectionShortening);
    const double* shortening = globalValue(*last, name);
    core::requireInput(shortening != nullptr, where + ": no global variable " + name + " (Pretension/" + section.name +
                                                  " is not in that result)");
    requirePlausible(*shortening, name, where);
    state.sectionShortening.push_back(*shortening);
  }
  for (int k : displacementSteps)
    if (k >= 1 && k <= state.step) state.displacements.push_back({k, fileDisplacement(data, k, state.step, where)});
  return state;
}

namespace {
void broadcast(std::vector<double>& values, MPI_Comm comm) {
  long long size = static_cast<long long>(values.size());
  MPI_Bcast(&size, 1, MPI_LONG_LONG, 0, comm);
  values.resize(static_cast<size_t>(size));
  MPI_Bcast(values.data(), static_cast<int>(size), MPI_DOUBLE, 0, comm);
}
}  // namespace

RestartState readRestartOnRoot(const std::string& file, const Scene& scene, const feti::ConstraintMatrix& B,
                               MPI_Comm comm, const std::vector<int>& displacementSteps) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  RestartState state;
  core::onEveryRankOrNone([&] { if (rank == 0) state = readRestart(file, scene, B, displacementSteps); },
                          "Load Steps/Restart From: " + file + " could not serve as a restart (rank 0 read it)", comm);
  state.file = file;
  broadcastRestartState(state, scene, comm);
  return state;
}

void broadcastRestartState(RestartState& state, const Scene& scene, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Bcast(&state.step, 1, MPI_INT, 0, comm);
  ContactFields& t = state.totals;
  broadcast(t.contactTangentialT1, comm);
  broadcast(t.contactTangentialT2, comm);
  broadcast(t.contactAccumulatedSlip, comm);
  for (auto* forces : {&t.contactNormal, &t.contactT1, &t.contactT2}) broadcast(*forces, comm);
  std::vector<double> energies;
  for (const auto& one : t.interfaces) energies.push_back(one.dissipatedEnergy);
  energies.push_back(t.dissipatedEnergy);
  broadcast(energies, comm);
  if (rank != 0)
    for (const auto& one : scene.contacts)
      t.interfaces.push_back({one.rows.name, one.rows.slaveSideSet + " -> " + one.rows.masterSideSet, one.law});
  for (size_t i = 0; i < t.interfaces.size(); ++i) t.interfaces[i].dissipatedEnergy = energies[i];
  t.dissipatedEnergy = energies.back();
  broadcast(state.sectionShortening, comm);
  int count = static_cast<int>(state.displacements.size());
  MPI_Bcast(&count, 1, MPI_INT, 0, comm);
  state.displacements.resize(static_cast<size_t>(count));
  for (auto& [step, u] : state.displacements) {
    MPI_Bcast(&step, 1, MPI_INT, 0, comm);
    std::vector<double> flat(3 * u.size());
    for (size_t n = 0; n < u.size(); ++n)
      for (int c = 0; c < 3; ++c) flat[3 * n + c] = u[n][c];
    broadcast(flat, comm);
    u.resize(flat.size() / 3);
    for (size_t n = 0; n < u.size(); ++n)
      for (int c = 0; c < 3; ++c) u[n][c] = flat[3 * n + c];
  }
}

}  // namespace tribos::stack
