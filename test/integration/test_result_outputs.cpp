// The driver's results on a gmsh scene (input/block_on_plate.xml, tolerance 1e-10): the JSON
// summary's reactions balance the applied load to 1e-8; the block, held by contact only,
// hands its whole load to the plate, whose clamp takes it (reactions = -load, contact force
// on the master block = -load); the Exodus result carries the stress, reaction and contact
// fields, the per-step global variables and the input parameters as info records; the
// summary gives every rank's peak memory (max_rss_per_rank_kb).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <tuple>
#include <vector>

#include "RunCommand.hpp"
#include "TestPaths.hpp"
#include "tribos/mesh/ExodusIO.hpp"

using tribos::test::quote;
using tribos::test::runCommand;

namespace {
double norm(const nlohmann::json& v) {
  return std::sqrt(v[0].get<double>() * v[0].get<double>() + v[1].get<double>() * v[1].get<double>() +
                   v[2].get<double>() * v[2].get<double>());
}

template <class Named>
bool has(const std::vector<Named>& items, const std::string& name) {
  return std::any_of(items.begin(), items.end(), [&](const Named& i) { return i.name == name; });
}
}  // namespace

TEST(resultOutputs, blockOnPlateReactionsEqualTheLoadAndTheResultSaysHowItWasMade) {
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_results_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto summary = (dir / "summary.json").string(), exo = (dir / "result.exo").string();
  const auto run = runCommand(std::string(TRIBOS_DRIVER) + " --input " +
                              quote(tribos::test::sourceDir() + "/input/block_on_plate.xml") +
                              " --set Solver/Tolerance=1e-10 --set Solver/Verbose=false --summary " + quote(summary) +
                              " --output " + quote(exo));
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(summary);
  const auto j = nlohmann::json::parse(in);

  // The load on the block's top: 0.5 MPa shear and 20 MPa pressure on 600 mm^2.
  const auto& load = j["applied_load"];
  EXPECT_NEAR(load[0].get<double>(), 300.0, 1e-9 * 12000.0);
  EXPECT_NEAR(load[2].get<double>(), -12000.0, 1e-9 * 12000.0);
  const double scale = norm(load);
  EXPECT_LE(j["force_balance"].get<double>(), 1e-8);
  ASSERT_EQ(j["reactions"].size(), 1u);
  const auto& plate = j["reactions"]["plate_bottom"];
  const auto& onMaster = j["contact_force_on_master"];  // force of the plate (slave) on the block (master)
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(plate[c].get<double>(), -load[c].get<double>(), 1e-8 * scale) << "component " << c;
    EXPECT_NEAR(onMaster[c].get<double>(), -load[c].get<double>(), 1e-8 * scale) << "component " << c;
    EXPECT_NEAR(j["reaction_total"][c].get<double>(), plate[c].get<double>(), 1e-12 * scale);
  }
  EXPECT_GT(j["strain_energy"].get<double>(), 0.0);
  // Peak memory: one positive figure (KiB) per rank.
  ASSERT_TRUE(j.contains("max_rss_per_rank_kb"));
  const auto& rss = j["max_rss_per_rank_kb"];
  ASSERT_TRUE(rss.is_array());
  ASSERT_EQ(rss.size(), j["n_ranks"].get<size_t>());
  for (const auto& kb : rss) EXPECT_GT(kb.get<long>(), 0);

  const auto data = tribos::mesh::readExodus(exo);
  ASSERT_EQ(data.steps.size(), 1u);
  const auto& step = data.steps[0];
  for (const char* name : {"stress_xx", "stress_yy", "stress_zz", "stress_xy", "stress_yz", "stress_xz", "von_mises",
                           "subdomain"})
    EXPECT_TRUE(has(step.element, name)) << name;
  for (const char* name : {"displ_x", "reaction_z", "nodal_stress_zz", "nodal_von_mises", "contact_pressure",
                           "contact_gap", "contact_opening", "contact_nx", "contact_ny", "contact_nz", "contact_master"})
    EXPECT_TRUE(has(step.nodal, name)) << name;
  for (const char* name : {"converged", "outer_iterations", "pfp_applications", "kkt_equilibrium", "force_balance",
                           "strain_energy"})
    EXPECT_TRUE(has(step.global, name)) << name;
  for (const auto& g : step.global)
    if (g.name == "converged") EXPECT_EQ(g.value, 1.0);
  // Per interface ("contact_" for the flat Contact list): the summary's numbers.
  const auto& interface = j["interfaces"][0];
  for (const auto& [global, key] : {std::pair<const char*, const char*>{"contact_normal_force", "normal_force"},
                                    {"contact_slip", "slip"}, {"contact_peak_pressure", "peak_pressure"}}) {
    const auto g = std::find_if(step.global.begin(), step.global.end(), [&](const auto& v) { return v.name == global; });
    ASSERT_NE(g, step.global.end()) << global;
    EXPECT_EQ(g->value, interface[key].get<double>()) << global;
  }
  EXPECT_TRUE(has(step.global, "contact_force_z"));
  // The info records hold the command line and the effective parameter list.
  const auto& info = data.info;
  EXPECT_TRUE(std::any_of(info.begin(), info.end(),
                          [](const std::string& l) { return l.find("block_on_plate.xml") != std::string::npos; }));
  EXPECT_TRUE(std::any_of(info.begin(), info.end(),
                          [](const std::string& l) { return l.find("<ParameterList") != std::string::npos; }));
  EXPECT_TRUE(std::any_of(info.begin(), info.end(),
                          [](const std::string& l) { return l.find("interface_plate") != std::string::npos; }));
  std::filesystem::remove_all(dir);
}

namespace {
const tribos::mesh::Field& field(const std::vector<tribos::mesh::Field>& fields, const std::string& name) {
  const auto it = std::find_if(fields.begin(), fields.end(), [&](const auto& f) { return f.name == name; });
  if (it == fields.end()) throw std::runtime_error("no field " + name);
  return *it;
}

double global(const tribos::mesh::TimeStep& step, const std::string& name) {
  const auto it = std::find_if(step.global.begin(), step.global.end(), [&](const auto& g) { return g.name == name; });
  if (it == step.global.end()) throw std::runtime_error("no global variable " + name);
  return it->value;
}
}  // namespace

TEST(resultOutputs, aLoadHistoryWritesEveryStepAndEndsAtTheStepThatFails) {
  // block_on_plate.xml (Coulomb 0.3, 20 MPa pressure, held by friction alone): a shear of
  // 5 MPa applied, removed, reversed, then doubled beyond the friction capacity of 6 MPa.
  // Steps 1-3 converge and step 4 cannot: exit 3, and the file holds all four steps at the
  // given times, the last flagged not converged. Friction acts on each step's slip increment:
  // at every slipping node the tangential force has F times the normal force and points along
  // the increment (maximal dissipation), so the dissipated energy grows by |f_t| |ds| there.
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_history_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto summary = (dir / "summary.json").string(), exo = (dir / "result.exo").string();
  const auto run = runCommand(
      std::string(TRIBOS_DRIVER) + " --input " + quote(tribos::test::sourceDir() + "/input/block_on_plate.xml") +
      " --set Solver/Tolerance=1e-9 --set Solver/Verbose=false --set 'Loads/shear/Side Set=block_top'"
      " --set 'Loads/shear/Traction={5, 0, 0}' --set 'Load Steps/Number Of Steps=4'"
      " --set 'Load Steps/Times={10, 20, 30, 40}' --set 'Load Steps/press/Factors={1, 1, 1, 1}'"
      " --set 'Load Steps/shear/Factors={1, 0, -1, 2}' --summary " + quote(summary) + " --output " + quote(exo));
  ASSERT_EQ(run.status, 3) << run.output;
  EXPECT_NE(run.output.find("load step 4 of 4 (press 1, shear 2)"), std::string::npos) << run.output;
  std::ifstream in(summary);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["steps"].size(), 4u);
  // The top-level counts are the sums over the steps; each step lists its factors.
  int outer = 0, updates = 0;
  for (const auto& step : j["steps"]) {
    outer += step["outer_iterations"].get<int>();
    updates += step["fixed_point_iterations"].get<int>();
  }
  EXPECT_EQ(j["outer_iterations"].get<int>(), outer);
  EXPECT_EQ(j["fixed_point_iterations"].get<int>(), updates);
  EXPECT_EQ(j["steps"][2]["factors"]["shear"].get<double>(), -1.0);
  EXPECT_EQ(j["steps"][2]["factors"]["press"].get<double>(), 1.0);
  const auto data = tribos::mesh::readExodus(exo);
  ASSERT_EQ(data.steps.size(), 4u);
  double dissipated = 0.0;
  std::vector<double> slipSoFar;
  for (size_t k = 0; k < 4; ++k) {
    SCOPED_TRACE("step " + std::to_string(k + 1));
    const auto& step = data.steps[k];
    const auto& entry = j["steps"][k];
    EXPECT_EQ(step.time, 10.0 * (k + 1));
    EXPECT_EQ(global(step, "converged"), k < 3 ? 1.0 : 0.0);
    EXPECT_EQ(global(step, "pfp_applications"), entry["pfp_applications"].get<double>());
    EXPECT_EQ(global(step, "contact_dissipated_energy"), entry["interfaces"][0]["dissipated_energy"].get<double>());
    if (k == 3) break;  // the failed step's state is no equilibrium
    EXPECT_LE(entry["force_balance"].get<double>(), 1e-8);
    // The applied shear of this step against the contact force on the master (the block).
    const double shear = 300.0 + 3000.0 * std::vector<double>{1, 0, -1}[k];
    EXPECT_NEAR(entry["interfaces"][0]["contact_force"][0].get<double>(), -shear, 1e-6 * 12000.0);
    const auto& status = field(step.nodal, "contact_status").values;
    const auto& fn = field(step.nodal, "contact_normal").values;
    const auto& f1 = field(step.nodal, "contact_t1").values;
    const auto& f2 = field(step.nodal, "contact_t2").values;
    const auto& s1 = field(step.nodal, "contact_slip_t1").values;
    const auto& s2 = field(step.nodal, "contact_slip_t2").values;
    const auto& total1 = field(step.nodal, "contact_tangential_t1").values;
    const auto& accumulated = field(step.nodal, "contact_accumulated_slip").values;
    if (slipSoFar.empty()) slipSoFar.assign(s1.size(), 0.0);
    double work = 0.0, bound = 0.0, capacity = 0.0, friction = 0.0;
    for (size_t n = 0; n < status.size(); ++n) {
      slipSoFar[n] += s1[n];
      EXPECT_NEAR(total1[n], slipSoFar[n], 1e-12) << "node " << n + 1;
      if (status[n] != 2.0) continue;
      work += f1[n] * s1[n] + f2[n] * s2[n];
      bound += std::hypot(f1[n], f2[n]) * std::hypot(s1[n], s2[n]);
      capacity += 0.3 * fn[n];
      friction += std::hypot(f1[n], f2[n]);
    }
    EXPECT_NEAR(friction, capacity, 1e-6 * 12000.0);
    EXPECT_GE(work, 0.999 * bound);
    dissipated += work;
    EXPECT_NEAR(global(step, "dissipated_energy"), dissipated, 1e-12 * (1.0 + dissipated));
    EXPECT_EQ(step.time, entry["time"].get<double>());
    std::printf("step %zu: %d slip nodes, dissipated so far %.6g, max accumulated slip %.3g\n", k + 1,
                entry["slip"].get<int>(), dissipated, *std::max_element(accumulated.begin(), accumulated.end()));
  }
  // Slip in steps 1 and 3 (the shear up to 5.5 and back to -4.5 MPa), none while it is removed.
  EXPECT_GT(j["steps"][0]["slip"].get<int>(), 0);
  EXPECT_GT(j["steps"][2]["slip"].get<int>(), 0);
  std::filesystem::remove_all(dir);
}

TEST(resultOutputs, aHistoryRestartedFromItsResultEndsWhereTheWholeHistoryDoes) {
  // block_on_plate.xml sheared by 5 MPa, then unloaded, reversed and unloaded (4 steps), at
  // eps = 1e-10: the whole history, and its first 2 steps followed by a run restarted from
  // their result (Load Steps/Restart From) for steps 3 and 4. The restart carries the
  // tangential displacement reached (friction's memory), the accumulated slip and the
  // dissipated energy; its first step starts cold. Measured: the displacements agree to
  // 2.4e-10 relative, the dissipated energy to 6e-11.
  const auto dir = std::filesystem::temp_directory_path() / ("tribos_restart_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto path = [&](const char* name) { return quote((dir / name).string()); };
  const std::string scene = std::string(TRIBOS_DRIVER) + " --input " +
                            quote(tribos::test::sourceDir() + "/input/block_on_plate.xml") +
                            " --set Solver/Tolerance=1e-10 --set Solver/Verbose=false"
                            " --set 'Loads/shear/Side Set=block_top' --set 'Loads/shear/Traction={5, 0, 0}'";
  const std::string four = " --set 'Load Steps/Number Of Steps=4' --set 'Load Steps/press/Factors={1, 1, 1, 1}'"
                           " --set 'Load Steps/shear/Factors={1, 0, -1, 0}'";
  const std::string two = " --set 'Load Steps/Number Of Steps=2' --set 'Load Steps/press/Factors={1, 1}'"
                          " --set 'Load Steps/shear/Factors={1, 0}'";
  auto run = runCommand(scene + four + " --output " + path("whole.exo") + " --summary " + path("whole.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  run = runCommand(scene + two + " --output " + path("first.exo"));
  ASSERT_EQ(run.status, 0) << run.output;
  run = runCommand(scene + four + " --set 'Load Steps/Restart From=" + (dir / "first.exo").string() + "' --output " +
                   path("rest.exo") + " --summary " + path("rest.json"));
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("load step 3/4"), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("load step 1/4"), std::string::npos) << run.output;
  const auto whole = tribos::mesh::readExodus((dir / "whole.exo").string());
  const auto rest = tribos::mesh::readExodus((dir / "rest.exo").string());
  ASSERT_EQ(whole.steps.size(), 4u);
  ASSERT_EQ(rest.steps.size(), 2u);  // the new steps only
  EXPECT_EQ(global(rest.steps[0], "load_step"), 3.0);
  EXPECT_EQ(rest.steps[1].time, whole.steps[3].time);
  for (const char* name : {"displ_x", "displ_z", "contact_tangential_t1", "contact_accumulated_slip"}) {
    const auto& a = field(whole.steps[3].nodal, name).values;
    const auto& b = field(rest.steps[1].nodal, name).values;
    double diff = 0.0, size = 0.0;
    for (size_t n = 0; n < a.size(); ++n) {
      diff = std::max(diff, std::abs(a[n] - b[n]));
      size = std::max(size, std::abs(a[n]));
    }
    std::printf("%s: whole history against the restart %.2e of %.2e\n", name, diff, size);
    EXPECT_LE(diff, 1e-8 * size) << name;
  }
  const double energy = global(whole.steps[3], "dissipated_energy");
  EXPECT_GT(energy, 0.0);
  EXPECT_NEAR(global(rest.steps[1], "dissipated_energy"), energy, 1e-8 * energy);
  std::ifstream in((dir / "rest.json").string());
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["restart"]["step"].get<int>(), 2);

  // What cannot be continued is exit 2 naming the file: a result of another mesh, a history
  // with no step left, a missing file, a result of other contact interfaces (slave and master
  // swapped: its memory would go to the wrong nodes); and a restart of a scene without history.
  run = runCommand(scene + two + " --set 'Contact/Slave Side Set=interface_block'"
                                 " --set 'Contact/Master Side Set=interface_plate' --output " + path("swapped.exo"));
  ASSERT_EQ(run.status, 0) << run.output;
  run = runCommand(scene + " --set 'Load Steps/Restart From=" + (dir / "first.exo").string() + "'");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("Load Steps/Restart From continues a load history, and the scene has none"),
            std::string::npos)
      << run.output;
  run = runCommand(std::string(TRIBOS_DRIVER) + " --input " +
                   quote(tribos::test::sourceDir() + "/input/two_bricks.xml") + " --set Solver/Verbose=false --output " +
                   path("bricks.exo"));
  ASSERT_EQ(run.status, 0) << run.output;
  for (const auto& [file, steps, expected] :
       std::vector<std::tuple<std::string, std::string, std::string>>{
           {"bricks.exo", four, "nodes, the scene's mesh has"},
           {"whole.exo", " --set 'Load Steps/Number Of Steps=4' --set 'Load Steps/press/Factors={1, 1, 1, 1}'"
                         " --set 'Load Steps/shear/Factors={1, 0, -1, 0}'", "no step left to solve"},
           {"missing.exo", four, "missing.exo"},
           {"swapped.exo", four, "(a result of other contact interfaces"}}) {
    run = runCommand(scene + steps + " --set 'Load Steps/Restart From=" + (dir / file).string() + "'");
    EXPECT_EQ(run.status, 2) << run.output;
    EXPECT_NE(run.output.find(expected), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("Load Steps/Restart From"), std::string::npos) << run.output;
  }
  // The restart file as --output (issue 44: exit 0, the steps restarted from overwritten).
  run = runCommand(scene + four + " --set 'Load Steps/Restart From=" + (dir / "first.exo").string() + "' --output " +
                   path("first.exo"));
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_NE(run.output.find("(--output): is an input of this run"), std::string::npos) << run.output;
}
