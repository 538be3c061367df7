// The behaviours of the failure map (doc/stability.md), one test each on the paper's scene
// (input/two_bricks.xml, 2x1x1 subdomains, H/h = 2: about a second per run): the status the
// driver reports must match what the solve did (a stagnating run never says converged).
#include <gtest/gtest.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "RunCommand.hpp"
#include "TestPaths.hpp"

namespace {
using tribos::test::quote;
using tribos::test::runCommand;
namespace fs = std::filesystem;
using Json = nlohmann::json;

const std::string kDriver = TRIBOS_DRIVER;

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

struct Outcome {
  int status = -1;
  Json summary;
  std::string output;
};

class Stability : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/tribos_stability_XXXXXX";
    ASSERT_NE(::mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The paper's scene with `sets` (--set options), one thread; the summary when written.
  Outcome solve(const std::string& sets, const std::string& scene = "two_bricks.xml") {
    const auto summary = dir_ / "s.json", exo = dir_ / "r.exo";
    fs::remove(summary);
    fs::remove(exo);
    Outcome r;
    const auto cmd = runCommand("OMP_NUM_THREADS=1 " + kDriver + " --input " +
                                quote(tribos::test::sourceDir() + "/input/" + scene) + " --set Solver/Verbose=false " +
                                sets + " --summary " + quote(summary.string()) + " --output " + quote(exo.string()));
    r.status = cmd.status;
    r.output = cmd.output;
    if (fs::exists(summary)) r.summary = Json::parse(std::ifstream(summary));
    if (r.status == 0 || r.status == 3) EXPECT_TRUE(fs::exists(exo)) << "results are written: " << sets;
    return r;
  }

  fs::path dir_;
};

// The largest relative KKT residual of the discrete problem (NaN when one is not finite).
double worstKkt(const Json& summary) {
  double worst = 0.0;
  for (const char* k : {"equilibrium", "gluing_dirichlet", "non_penetration", "complementarity", "normal_sign",
                        "friction_admissibility", "slip_rule", "stick_rule"}) {
    const auto& v = summary.at("kkt").at(k);
    if (v.is_null()) return std::nan("");
    worst = std::max(worst, v.get<double>());
  }
  return worst;
}

// A converged run: exit 0, "converged", every KKT residual within the tolerance.
void expectConverged(const Outcome& r, const std::string& what) {
  ASSERT_EQ(r.status, 0) << what << "\n" << r.output;
  EXPECT_TRUE(r.summary.at("converged").get<bool>()) << what;
  EXPECT_EQ(r.summary.at("message"), "converged") << what;
  EXPECT_LE(worstKkt(r.summary), r.summary.at("kkt").at("tolerance").get<double>()) << what;
}

const std::string kHeldByFriction =
    " --set 'Boundary/Dirichlet Node Sets={dirichlet_aluminium}' --set 'Boundary/steelz/Node Set=dirichlet_steel'"
    " --set 'Boundary/steelz/Components=z'";

std::string friction(double F) {
  return " --set Contact/F1=" + std::to_string(F) + " --set Contact/F2=" + std::to_string(F);
}

std::string scaledPaperLoads(const std::string& s) {
  // (1, 0, 20) s on x = 20 and (0, 0, -30) s on z = 20: the paper's tractions times s.
  const double k = std::stod(s);
  auto num = [](double x) { return (std::ostringstream() << x).str(); };
  return " --set 'Loads/end/Side Set=load_end' --set 'Loads/end/Traction={" + num(k) + ",0," + num(20 * k) +
         "}' --set 'Loads/top/Side Set=load_top' --set 'Loads/top/Traction={0,0," + num(-30 * k) + "}'";
}
}  // namespace

TEST_F(Stability, coulombConvergesFromNoFrictionToFullStick) {
  // F = 0: every contact node slips; F = 10: every one sticks (doc/stability.md, friction sweep).
  const auto none = solve(friction(0.0));
  expectConverged(none, "F = 0");
  EXPECT_EQ(none.summary.at("contact_nodes").at("stick").get<int>(), 0);
  EXPECT_GT(none.summary.at("contact_nodes").at("slip").get<int>(), 0);
  const auto full = solve(friction(10.0));
  expectConverged(full, "F = 10");
  EXPECT_EQ(full.summary.at("contact_nodes").at("slip").get<int>(), 0);
  EXPECT_GT(full.summary.at("contact_nodes").at("stick").get<int>(), 0);
  // Orthotropic with a zero coefficient: free sliding along t1, held along t2.
  expectConverged(solve(" --set Contact/F1=0 --set Contact/F2=10"), "F1 = 0, F2 = 10");
}

TEST_F(Stability, withoutAGapTheSolutionScalesLinearlyWithTheLoad) {
  // u(s f) = s u(f): the reactions scale by s, the strain energy by s^2, to the tolerance
  // (eps = 1e-5; measured deviations in doc/stability.md). At s = 1e6 the moduli are scaled by s
  // too (u(s f, s E) = u(f, E), the energy by s): the paper's load times 1e6 on its steel moves
  // the bricks by 340 mm, through each other, which the check after the solve rightly calls
  // not converged (issue 41); the same magnitudes of force and stiffness stay tested.
  const auto unit = solve(scaledPaperLoads("1"));
  expectConverged(unit, "s = 1");
  for (const std::string s : {"1e-6", "1e6"}) {
    const double k = std::stod(s);
    const bool stiffened = k > 1.0;
    std::string sets = scaledPaperLoads(s);
    if (stiffened)  // the paper's Lame constants (stack/Scene.cpp) times s
      sets += " --set 'Materials/aluminium/Lame Lambda=2.792e10' --set 'Materials/aluminium/Lame Mu=2.593e10'"
              " --set 'Materials/steel/Lame Lambda=6.360e10' --set 'Materials/steel/Lame Mu=8.301e10'";
    const auto scaled = solve(sets);
    expectConverged(scaled, "s = " + s);
    double deviation = 0.0, size = 0.0;
    for (const auto& [set, force] : unit.summary.at("reactions").items())
      for (int c = 0; c < 3; ++c) {
        const double a = scaled.summary.at("reactions").at(set).at(c).get<double>() / k, b = force.at(c).get<double>();
        deviation = std::max(deviation, std::abs(a - b));
        size = std::max(size, std::abs(b));
      }
    EXPECT_LE(deviation / size, 1e-3) << "s = " << s;
    const double energy = scaled.summary.at("strain_energy").get<double>() / (stiffened ? k : k * k);
    EXPECT_NEAR(energy / unit.summary.at("strain_energy").get<double>(), 1.0, 1e-3) << "s = " << s;
  }
}

TEST_F(Stability, anOpenGapCarriesNoForceAndAClosedOneDoes) {
  const std::string search = " --set 'Contact/Search Distance=2'";
  const auto closed = solve(" --set 'Mesh/Initial Gap=0.001'" + search);
  expectConverged(closed, "gap 0.001");
  EXPECT_GT(closed.summary.at("total_normal_force").get<double>(), 100.0);
  const auto open = solve(" --set 'Mesh/Initial Gap=0.1'" + search);
  expectConverged(open, "gap 0.1");
  EXPECT_EQ(open.summary.at("contact_nodes").at("no_contact").get<int>(),
            open.summary.at("contact_nodes_paired").get<int>());
  EXPECT_LE(std::abs(open.summary.at("total_normal_force").get<double>()), 1e-6);
}

TEST_F(Stability, aBodyHeldByFrictionOnlyConvergesWithStickNodes) {
  const auto held = solve(kHeldByFriction + friction(0.3));
  expectConverged(held, "held by F = 0.3");
  EXPECT_GT(held.summary.at("contact_nodes").at("stick").get<int>(), 0);
}

TEST_F(Stability, theInterfaceSummaryAgreesWithTheTotals) {
  // summary.interfaces (issue 30): the paper's scene has one interface; its counts and normal
  // force are the totals', and with every touching node sliding its friction force is F N.
  const auto r = solve("");
  expectConverged(r, "paper");
  ASSERT_EQ(r.summary.at("interfaces").size(), 1u);
  const auto& i = r.summary.at("interfaces")[0];
  EXPECT_EQ(i.at("interface").get<std::string>(), "contact_aluminium -> contact_steel");
  for (const char* status : {"no_contact", "stick", "slip"})
    EXPECT_EQ(i.at(status).get<int>(), r.summary.at("contact_nodes").at(status).get<int>()) << status;
  const double N = r.summary.at("total_normal_force").get<double>();
  EXPECT_EQ(i.at("normal_force").get<double>(), N);
  ASSERT_EQ(i.at("stick").get<int>(), 0);  // all slide on the paper's scene: |f_t| = F f_nu per node
  EXPECT_NEAR(i.at("friction_force").get<double>(), 0.3 * N, 1e-3 * 0.3 * N);
  EXPECT_GT(i.at("peak_pressure").get<double>(), 0.0);
  EXPECT_GE(i.at("largest_opening").get<double>(), 0.0);
  EXPECT_LE(i.at("largest_overlap").get<double>(), 1e-6);
}

TEST_F(Stability, aLoadBeyondWhatFrictionHoldsStagnatesAndSaysSo) {
  // F = 0.01 cannot carry the 100 N shear: no equilibrium, ||G mu|| stagnates. It was an
  // internal error (G_I G_I^T singular, exit 1, no output), then exit 3 at the outer cap
  // (100); now exit 3 once ||G mu|| has not halved over Solver/SMALSE-M/stall window = 20
  // outer iterations (21 here), with the results written, naming the interface and its
  // friction capacity against the load along the contact plane. Whether the rigid-body recovery of the last
  // iterate also fails ("no equilibrium found" added to the message) depends on round-off in
  // that iterate (it changes with the operator's evaluation order), so it is not asserted.
  const auto r = solve(kHeldByFriction + friction(0.01));
  ASSERT_EQ(r.status, 3) << r.output;
  EXPECT_FALSE(r.summary.at("converged").get<bool>());
  const auto message = r.summary.at("message").get<std::string>();
  EXPECT_TRUE(contains(message, "stopped: ||G mu|| stalled (not halved over Solver/SMALSE-M/stall window = 20")) << message;
  EXPECT_TRUE(contains(message, "friction capacity F N = 0.01 x ")) << message;
  EXPECT_LE(r.summary.at("outer_iterations").get<int>(), 30);
  EXPECT_FALSE(contains(r.output, "internal error")) << r.output;
}

TEST_F(Stability, aMaterialContrastBeyondTheAccuracyIsNotConverged) {
  // E_steel / E_aluminium = 1e8: SMALSE-M stops, but the discrete KKT conditions fail by far
  // (doc/stability.md): exit 3 naming the residual, never "converged".
  const auto r = solve(
      " --set 'Materials/aluminium/Young Modulus=7e4' --set 'Materials/aluminium/Poisson Ratio=0.35'"
      " --set 'Materials/steel/Young Modulus=7e12' --set 'Materials/steel/Poisson Ratio=0.3'");
  ASSERT_EQ(r.status, 3) << r.output;
  EXPECT_FALSE(r.summary.at("converged").get<bool>());
  EXPECT_TRUE(contains(r.summary.at("message").get<std::string>(), "KKT residual")) << r.summary.at("message");
  EXPECT_GT(worstKkt(r.summary), r.summary.at("kkt").at("tolerance").get<double>());
}
