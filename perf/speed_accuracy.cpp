// Speed against accuracy: for a sequence of tolerances epsilon, the F applications, solve
// time and error of the displacement, the KKT residuals and the converged flag. Prints a CSV
// (doc/measurements/speed_accuracy.md).
// Usage:
//   build/bin/tribos_speed_accuracy [grid] [H/h] [Path=value ...]
//     the paper's two bricks; frictionless error against the independent active-set solve of
//     the undecomposed problem, Coulomb (F = 0.3) against the same scene at epsilon = 1e-11;
//   build/bin/tribos_speed_accuracy --input SCENE.xml
//                                   [--reference-tolerance 1e-11] [--reference-set Path=value ...]
//                                   [Path=value ...]
//     any scene file (non-matching meshes included): each model's error against the same
//     scene and overrides solved at the reference tolerance, with the --reference-set
//     overrides on top (one reference for several variants; its line goes to stderr).
// Overrides "Path=value" select a solver variant (e.g. "Solver/MPGP/tangent CG=false").
// Both forms take --epsilons 1e-2,...,1e-9 (the default list) and --models None,Coulomb.
#include <mpi.h>

#include <Tpetra_Core.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "ContactScene.hpp"
#include "DirectSolve.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/core/XmlParameters.hpp"

using namespace tribos;

namespace {

using Field = std::vector<std::array<double, 3>>;

// ||a - b|| / ||b|| over every global node and component.
double relativeError(const Field& a, const Field& b) {
  double diff = 0.0, norm = 0.0;
  for (size_t n = 0; n < a.size(); ++n)
    for (int c = 0; c < 3; ++c) {
      diff += std::pow(a[n][c] - b[n][c], 2);
      norm += std::pow(b[n][c], 2);
    }
  return std::sqrt(diff / norm);
}

struct Options {
  std::string input;                        // scene file; empty: the two bricks
  std::string grid = "4x2x2", h = "3";      // two bricks only
  std::vector<std::string> models = {"None", "Coulomb"};
  std::vector<std::string> epsilons = {"1e-2", "1e-3", "1e-4", "1e-5", "1e-6", "1e-7", "1e-8", "1e-9"};
  std::string referenceTolerance = "1e-11";
  std::vector<std::string> overrides;
  std::vector<std::string> referenceOverrides;  // on top of `overrides`, for the reference solve only
};

std::vector<std::string> splitCommas(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

Options parse(int argc, char** argv) {
  Options o;
  std::vector<std::string> positional;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--input" && i + 1 < argc) o.input = argv[++i];
    else if (a == "--models" && i + 1 < argc) o.models = splitCommas(argv[++i]);
    else if (a == "--epsilons" && i + 1 < argc) o.epsilons = splitCommas(argv[++i]);
    else if (a == "--reference-tolerance" && i + 1 < argc) o.referenceTolerance = argv[++i];
    else if (a == "--reference-set" && i + 1 < argc) o.referenceOverrides.push_back(argv[++i]);
    else if (a.find('=') != std::string::npos) o.overrides.push_back(a);
    else positional.push_back(a);
  }
  if (!positional.empty()) o.grid = positional[0];
  if (positional.size() > 1) o.h = positional[1];
  return o;
}

Teuchos::ParameterList readScene(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return *core::parameterListFromXml(text.str(), path);
}

// Solves the two bricks (input empty) or the scene file with `overrides`.
test::SolvedContactScene solve(const Options& o, const std::vector<std::string>& overrides) {
  if (o.input.empty()) {
    auto all = overrides;
    all.insert(all.begin(), {"Mesh/Subdomains Per Brick=" + o.grid, "Mesh/H Over h=" + o.h});
    return test::solveContactScene(all);
  }
  static const Teuchos::ParameterList scene = readScene(o.input);
  return test::solveContactScene(scene, o.input, overrides);
}

// The frictionless two bricks: the independent active-set solve of the undecomposed problem.
Field directReference(const test::SolvedContactScene& s) {
  std::vector<LO> fixed;
  for (const auto& name : s.scene.dirichletNodeSets)
    for (LO n : s.scene.mesh.nodeSet(name).nodes) fixed.push_back(n);
  std::vector<std::pair<LO, LO>> pairs;
  for (const auto& c : s.B.contact) pairs.push_back({c.slaveNode, c.masterNode});
  return test::directFrictionlessContact(s.scene.mesh, s.scene.materials, s.scene.loads, fixed, pairs);
}

void printRow(FILE* out, const std::string& model, const std::string& eps, const test::SolvedContactScene& s,
              double error) {
  const auto& r = s.result.contact;
  std::fprintf(out, "%s,%s,%d,%lld,%.3f,%.2e,%.1e,%.1e,%.1e,%d\n", model.c_str(), eps.c_str(),
               r.counters.outerIterations, r.counters.operatorApplications, s.result.solveSeconds, error,
               r.kkt.equilibrium, r.kkt.complementarity, r.kkt.frictionAdmissibility, r.converged ? 1 : 0);
  std::fflush(out);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  {
    Tpetra::ScopeGuard tpetra(&argc, &argv);
    core::warmUpKokkosForThreads();
    const Options o = parse(argc, argv);
    std::printf("model,epsilon,outer,pfp_applications,solve_s,relative_error,kkt_equilibrium,kkt_complementarity,"
                "kkt_friction,converged\n");
    for (const std::string& model : o.models) {
      auto base = o.overrides;
      base.push_back("Solver/Verbose=false");
      base.push_back("Contact/Friction Model=" + model);
      Field reference;
      if (o.input.empty() && model == "None") {
        reference = directReference(solve(o, base));
      } else {
        auto tight = base;
        tight.insert(tight.end(), o.referenceOverrides.begin(), o.referenceOverrides.end());
        tight.push_back("Solver/Tolerance=" + o.referenceTolerance);
        const auto s = solve(o, tight);
        reference = s.result.displacement.value;
        std::fprintf(stderr, "# reference: ");
        printRow(stderr, model, o.referenceTolerance, s, 0.0);
      }
      for (const std::string& eps : o.epsilons) {
        char buffer[32];  // "1e-05" as the CSVs have always written it
        std::snprintf(buffer, sizeof buffer, "%g", std::stod(eps));
        auto variant = base;
        variant.push_back("Solver/Tolerance=" + eps);
        const auto s = solve(o, variant);
        printRow(stdout, model, buffer, s, relativeError(s.result.displacement.value, reference));
      }
    }
  }
  MPI_Finalize();
  return 0;
}
