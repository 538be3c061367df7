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
