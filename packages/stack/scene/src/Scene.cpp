#include "tribos/stack/Scene.hpp"

#include "PretensionInput.hpp"

#include <Teuchos_Array.hpp>
#include <Teuchos_ParameterList.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/core/Timer.hpp"
#include "tribos/core/Validators.hpp"
#include "tribos/mesh/BoundaryFaces.hpp"
#include "tribos/mesh/ExodusIO.hpp"
#include "tribos/mesh/TwoBricks.hpp"
#include "tribos/stack/SameMeshOnEveryRank.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainCount.hpp"

namespace tribos::stack {

namespace {
using core::InputError;
using Teuchos::ParameterList;

// The paper's materials (Section 6): Lame constants in MPa.
const fem::Material kAluminium{2.792e4, 2.593e4};
const fem::Material kSteel{6.360e4, 8.301e4};

// get() with a default on a const list (Teuchos only offers it on non-const lists).
template <class T>
T getOr(const ParameterList& pl, const std::string& name, const T& fallback) {
  return pl.isParameter(name) ? pl.get<T>(name) : fallback;
}

fem::Material materialFrom(const ParameterList& body, const std::string& where) {
  const bool lame = body.isParameter("Lame Lambda") || body.isParameter("Lame Mu");
  const bool young = body.isParameter("Young Modulus") || body.isParameter("Poisson Ratio");
  if (lame == young)
    throw InputError(where + ": give either \"Lame Lambda\" and \"Lame Mu\" or \"Young Modulus\" "
                             "and \"Poisson Ratio\"");
  if (lame) {
    const double lambda = getOr(body, "Lame Lambda", 0.0), mu = getOr(body, "Lame Mu", 0.0);
    core::requireInput(std::isfinite(lambda) && std::isfinite(mu),
                       where + ": Lame constants must be finite numbers");
    core::requireInput(mu > 0.0 && 3.0 * lambda + 2.0 * mu > 0.0,
                       where + ": Lame constants must satisfy mu > 0 and 3 lambda + 2 mu > 0 (got lambda = " +
                           std::to_string(lambda) + ", mu = " + std::to_string(mu) + ")");
    return fem::Material{lambda, mu};
  }
  const double E = getOr(body, "Young Modulus", 0.0), nu = getOr(body, "Poisson Ratio", 0.0);
  core::requireInput(std::isfinite(E) && E > 0.0 && nu > -1.0 && nu < 0.5,
                     where + ": need a finite Young Modulus > 0 and -1 < Poisson Ratio < 0.5");
  return fem::Material::fromYoungPoisson(E, nu);
}

std::array<double, 3> vector3(const ParameterList& pl, const std::string& name, const std::string& where) {
  const auto& a = pl.get<Teuchos::Array<double>>(name);
  core::requireInput(a.size() == 3, where + "/" + name + ": needs exactly 3 components, got " +
                                        std::to_string(a.size()));
  for (double v : a) core::requireInput(std::isfinite(v), where + "/" + name + ": not a finite number");
  return {a[0], a[1], a[2]};
}

std::string meshPath(const ParameterList& meshList, const std::string& source) {
  if (meshGenerator(meshList) == MeshGenerator::TwoBricks) return "";
  auto file = meshList.get<std::string>("File");
  core::requireInput(!file.empty(), source + ": Mesh/Generator is \"Exodus\" but Mesh/File is empty");
  // A relative path is relative to the scene file, so scenes can travel with their meshes.
  const std::filesystem::path scenePath(source);
  if (std::filesystem::path(file).is_relative() && scenePath.has_parent_path())
    file = (scenePath.parent_path() / file).string();
  return file;
}

// Mesh/Subdomains, or the count chosen from the mesh where it is 0 (stack/SubdomainCount.hpp).
int subdomainCount(const ParameterList& meshList, MPI_Comm comm, Scene& scene) {
  int ranks = 1;
  if (comm != MPI_COMM_NULL) MPI_Comm_size(comm, &ranks);
  const int requested = meshList.get<int>("Subdomains");
  const auto choice = chooseSubdomainCount(requested, requested > 0 ? 0 : cornerNodeCount(scene.mesh),
                                           scene.mesh.numNodes(), scene.mesh.numBlocks(),
                                           meshList.get<int>("Nodes Per Subdomain"), ranks);
  scene.subdomainChoice = choice.reason;
  return choice.count;
}

void readMesh(const ParameterList& meshList, const std::string& source, MPI_Comm comm, Scene& scene) {
  core::Stopwatch watch;
  const auto decomposition = core::valueOf(kMeshDecompositionNames, meshList.get<std::string>("Decomposition"));
  std::vector<int> parts;
  if (meshGenerator(meshList) == MeshGenerator::TwoBricks) {
    mesh::TwoBricksSpec spec;
    spec.subdomainsPerBrick =
        mesh::BrickGrid::parse(meshList.get<std::string>("Subdomains Per Brick"), "Mesh/Subdomains Per Brick");
    spec.hOverH = meshList.get<int>("H Over h");
    spec.gap = meshList.get<double>("Initial Gap");
    scene.mesh = mesh::generateTwoBricks(spec);
    scene.meshSeconds = watch.seconds();
    watch.restart();
    parts = decomposition == MeshDecomposition::Structured ? mesh::structuredPartition(scene.mesh, spec)
                                          : mesh::metisPartition(scene.mesh, subdomainCount(meshList, comm, scene));
  } else {
    const std::string file = meshPath(meshList, source);
    scene.mesh = comm == MPI_COMM_NULL ? mesh::readExodus(file).mesh : readMeshOnEveryRank(file, comm);
    scene.meshSeconds = watch.seconds();
    watch.restart();
    parts = mesh::metisPartition(scene.mesh, subdomainCount(meshList, comm, scene));
  }
  scene.decomposition = mesh::buildDecomposition(scene.mesh, parts);
  scene.decompositionSeconds = watch.seconds();
}

// Bodies whose shear moduli differ by more than kMaxContrast: the stiffer body's compliance
// in F = B K^+ B^T falls below the round-off of the softer one's (1/DBL_EPSILON = 4.5e15).
// Measured on input/two_bricks.xml (doc/stability.md): a contrast of 1e14 ends in seconds as
// not converged (exit 3), 1e16 and above ran without end.
constexpr double kMaxContrast = 1e15;
std::string threeDigits(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  return text;
}
void checkStiffnessContrast(const Scene& scene, const std::string& source) {
  const auto& m = scene.materials;
  if (m.empty()) return;
  size_t soft = 0, stiff = 0;
  for (size_t b = 1; b < m.size(); ++b) {
    if (m[b].mu < m[soft].mu) soft = b;
    if (m[b].mu > m[stiff].mu) stiff = b;
  }
  const double contrast = m[stiff].mu / m[soft].mu;
  core::requireInput(contrast <= kMaxContrast,
                     source + ": Materials: the shear moduli of element blocks \"" + scene.mesh.blocks[stiff].name +
                         "\" (" + threeDigits(m[stiff].mu) + ") and \"" + scene.mesh.blocks[soft].name +
                         "\" (" + threeDigits(m[soft].mu) + ") differ by a factor " +
                         threeDigits(contrast) + " > 1e15: beyond double precision (the stiffer body's "
                         "compliance is lost in round-off); model it as rigid (prescribed displacements) instead");
}

void readMaterials(const ParameterList& list, const std::string& source, bool paperDefaults, Scene& scene) {
  const auto& blocks = scene.mesh.blocks;
  scene.materials.assign(blocks.size(), fem::Material{});
  if (list.numParams() == 0 && paperDefaults) {
    scene.materials = {kAluminium, kSteel};
    return;
  }
  std::vector<bool> given(blocks.size(), false);
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string where = source + ": Materials/" + list.name(it);
    int b = -1;
    try {
      b = scene.mesh.blockIndex(list.name(it));
    } catch (const InputError& e) {
      throw InputError(where + ": " + e.what());
    }
    scene.materials[b] = materialFrom(list.sublist(list.name(it)), where);
    given[b] = true;
  }
  for (size_t b = 0; b < blocks.size(); ++b)
    core::requireInput(given[b], source + ": no material for element block \"" + blocks[b].name +
                                     "\" (add a sublist Materials/" + blocks[b].name + ")");
  checkStiffnessContrast(scene, source);
}

void readLoads(const ParameterList& list, const std::string& source, bool paperDefaults, Scene& scene) {
  if (list.numParams() == 0 && paperDefaults) {
    // The paper's tractions (Section 6): p = (1, 0, 20) on x = 20, p = (0, 0, -30) on z = 20.
    scene.loads.tractions = {{"load_end", {1.0, 0.0, 20.0}}, {"load_top", {0.0, 0.0, -30.0}}};
    for (const auto& t : scene.loads.tractions) scene.namedLoads.push_back({t.sideSet, fem::Loads{{t}, {}}});
    return;
  }
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string where = source + ": Loads/" + list.name(it);
    const ParameterList& load = list.sublist(list.name(it));
    auto sideSet = getOr(load, "Side Set", std::string());
    const auto nodeSet = getOr(load, "Node Set", std::string());
    const auto block = getOr(load, "Element Block", std::string());
    core::requireInput(sideSet.empty() + nodeSet.empty() + block.empty() == 2,
                       where + ": give exactly one of \"Side Set\" or \"Node Set\" (with Traction and/or "
                               "Pressure) or \"Element Block\" (with Volume Force)");
    try {
      if (!nodeSet.empty())  // its boundary faces, as a side set of the mesh (meshio writes node sets only)
        sideSet = scene.mesh.sideSets[mesh::addSideSetFromNodeSet(scene.mesh, nodeSet)].name;
      if (!sideSet.empty()) {
        scene.mesh.sideSet(sideSet);  // existence check, names the set
        scene.loads.tractions.push_back(
            fem::Traction{sideSet,
                          load.isParameter("Traction") ? vector3(load, "Traction", where)
                                                       : std::array<double, 3>{0.0, 0.0, 0.0},
                          getOr(load, "Pressure", 0.0)});
        scene.namedLoads.push_back({list.name(it), fem::Loads{{scene.loads.tractions.back()}, {}}});
      } else {
        core::requireInput(getOr(load, "Pressure", 0.0) == 0.0,
                           where + ": Pressure acts on faces: give it with \"Side Set\" or \"Node Set\", not "
                                   "with \"Element Block\"");
        const int b = scene.mesh.blockIndex(block);
        scene.loads.volumeForce.resize(scene.mesh.blocks.size(), {0.0, 0.0, 0.0});
        const auto force = vector3(load, "Volume Force", where);
        for (int c = 0; c < 3; ++c) scene.loads.volumeForce[b][c] += force[c];
        fem::Loads own;
        own.volumeForce.assign(scene.mesh.blocks.size(), {0.0, 0.0, 0.0});
        own.volumeForce[b] = force;
        scene.namedLoads.push_back({list.name(it), own});
      }
    } catch (const InputError& e) {
      const std::string what = e.what();
      if (what.rfind(where, 0) == 0) throw;
      throw InputError(where + ": " + what);
    }
  }
}
/// The largest magnitude a load gives (traction components, pressure, volume force) or a
/// displacement condition prescribes.
double largestValue(const fem::Loads& loads) {
  double largest = 0.0;
  for (const auto& t : loads.tractions) {
    for (double p : t.p) largest = std::max(largest, std::abs(p));
    largest = std::max(largest, std::abs(t.pressure));
  }
  for (const auto& b : loads.volumeForce)
    for (double v : b) largest = std::max(largest, std::abs(v));
  return largest;
}
double largestValue(const feti::DisplacementCondition& condition) {
  double largest = 0.0;
  for (double v : condition.value) largest = std::max(largest, std::abs(v));
  return largest;
}

/// A factor table times the values it scales stays within the magnitudes every input has
/// (core::kMaxMagnitude): beyond, the step's loads are absurd (issue 44: a table of 1e60 on a
/// traction of 1e60 ended the solve "non-finite", exit 3, where an absurd input is exit 2).
void requireFiniteProducts(const std::vector<double>& factors, double largest, const std::string& table,
                           const std::string& scaled) {
  for (size_t k = 0; k < factors.size(); ++k)
    core::requireInput(!(std::abs(factors[k]) * largest > core::kMaxMagnitude),
                       table + ": step " + std::to_string(k + 1) + "'s factor " + core::formatNumber(factors[k]) +
                           " times " + scaled + "'s largest value " + core::formatNumber(largest) +
                           " is beyond " + core::formatNumber(core::kMaxMagnitude) + " (absurd magnitudes)");
}

/// Load Steps: the number of steps, each named load's and displacement condition's factors (the
/// ramp k / N unless a Load Steps/<name> table gives them; the name must be a Loads/<name> or a
/// Boundary/<name>, the table's length N) and the steps' times.
void readLoadSteps(const ParameterList& list, const std::string& source, Scene& scene) {
  const int n = list.get<int>("Number Of Steps");
  scene.loadSteps = n;
  std::vector<double> ramp(n);
  for (int k = 0; k < n; ++k) ramp[k] = static_cast<double>(k + 1) / n;
  scene.loadFactors.assign(scene.namedLoads.size(), ramp);
  scene.displacementFactors.assign(scene.displacementConditions.size(), ramp);
  scene.conditionActive.assign(scene.displacementConditions.size(), std::vector<char>(static_cast<size_t>(n), 1));
  scene.stepTimes = ramp;
  auto sizeN = [&](const Teuchos::Array<double>& values, const std::string& where) {
    core::requireInput(static_cast<int>(values.size()) == n,
                       where + ": " + std::to_string(values.size()) + " values for Load Steps/Number Of Steps = " +
                           std::to_string(n));
  };
  const auto& times = list.get<Teuchos::Array<double>>("Times");
  if (!times.empty()) {
    sizeN(times, source + ": Load Steps/Times");
    for (size_t k = 1; k < times.size(); ++k)
      core::requireInput(times[k] > times[k - 1], source + ": Load Steps/Times must increase (step " +
                                                      std::to_string(k + 1) + ": " + core::formatNumber(times[k]) +
                                                      " after " + core::formatNumber(times[k - 1]) + ")");
    scene.stepTimes.assign(times.begin(), times.end());
  }
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (!list.entry(it).isList()) continue;
    const std::string name = list.name(it);
    const std::string where = source + ": Load Steps/" + name;
    const auto load = std::find_if(scene.namedLoads.begin(), scene.namedLoads.end(),
                                   [&](const auto& one) { return one.first == name; });
    const auto condition =
        std::find_if(scene.displacementConditions.begin(), scene.displacementConditions.end(),
                     [&](const feti::DisplacementCondition& one) { return one.name == name; });
    const bool isLoad = load != scene.namedLoads.end(), isCondition = condition != scene.displacementConditions.end();
    core::requireInput(isLoad || isCondition, where + ": no Loads/" + name + " or Boundary/" + name +
                                                  " of that name (give one, or take this table out)");
    core::requireInput(!(isLoad && isCondition), where + ": both Loads/" + name + " and Boundary/" + name +
                                                     " have that name (rename one so that the table names one)");
    const ParameterList& sub = list.sublist(name);
    const bool active = sub.isParameter("Active");
    core::requireInput(sub.isParameter("Factors") || active,
                       where + ": \"Factors\" is required" + (isCondition ? std::string(" (or Active)") : ""));
    core::requireInput(!(active && isLoad), where + "/Active: Loads/" + name + " is a load; Active switches "
                                                "Boundary conditions (a load is switched off by a factor 0)");
    if (active) {
      const auto& flags = sub.get<Teuchos::Array<int>>("Active");
      core::requireInput(static_cast<int>(flags.size()) == n,
                         where + "/Active: " + std::to_string(flags.size()) +
                             " values for Load Steps/Number Of Steps = " + std::to_string(n));
      auto& target = scene.conditionActive[static_cast<size_t>(condition - scene.displacementConditions.begin())];
      for (int k = 0; k < n; ++k) {
        core::requireInput(flags[k] == 0 || flags[k] == 1, where + "/Active: step " + std::to_string(k + 1) +
                                                               "'s value " + std::to_string(flags[k]) +
                                                               " (1: holds, 0: does not)");
        target[static_cast<size_t>(k)] = static_cast<char>(flags[k]);
      }
    }
    scene.loadHistory = true;
    if (!sub.isParameter("Factors")) continue;
    const auto& factors = sub.get<Teuchos::Array<double>>("Factors");
    sizeN(factors, where + "/Factors");
    auto& target = isLoad ? scene.loadFactors[load - scene.namedLoads.begin()]
                          : scene.displacementFactors[condition - scene.displacementConditions.begin()];
    target.assign(factors.begin(), factors.end());
    requireFiniteProducts(target, isLoad ? largestValue(load->second) : largestValue(*condition),
                          where + "/Factors", isLoad ? "Loads/" + name : "Boundary/" + name);
  }
  scene.loadHistory = scene.loadHistory || n > 1;
  core::requireInput(scene.loadHistory || list.get<std::string>("Restart From").empty(),
                     source + ": Load Steps/Restart From continues a load history, and the scene has none (give "
                              "Load Steps/Number Of Steps > 1 or a Factors table)");
}

/// "xyz", "x", "yz", ...: each of x, y, z at most once, at least one.
std::array<bool, 3> componentsFrom(const std::string& text, const std::string& where) {
  std::array<bool, 3> chosen{false, false, false};
  for (char ch : text) {
    const auto at = std::string("xyz").find(ch);
    core::requireInput(at != std::string::npos && !chosen[at],
                       where + "/Components: \"" + text + "\" must list each of x, y, z at most once (e.g. \"x\", "
                               "\"yz\", \"xyz\")");
    chosen[at] = true;
  }
  core::requireInput(chosen[0] || chosen[1] || chosen[2], where + "/Components: empty (give e.g. \"x\" or \"xyz\")");
  return chosen;
}

void readBoundary(const ParameterList& list, const std::string& source, bool paperDefaults, Scene& scene) {
  auto checkSet = [&](const std::string& name, const std::string& where) {
    try {
      scene.mesh.nodeSet(name);
    } catch (const InputError& e) {
      throw InputError(where + ": " + e.what());
    }
  };
  for (const auto& name : list.get<Teuchos::Array<std::string>>("Dirichlet Node Sets")) {
    checkSet(name, source + ": Boundary/Dirichlet Node Sets");
    scene.dirichletNodeSets.push_back(name);
  }
  for (auto it = list.begin(); it != list.end(); ++it) {
    if (!list.entry(it).isList()) continue;
    const std::string where = source + ": Boundary/" + list.name(it);
    const ParameterList& sub = list.sublist(list.name(it));
    feti::DisplacementCondition condition;
    condition.name = list.name(it);
    condition.nodeSet = getOr(sub, "Node Set", std::string());
    core::requireInput(!condition.nodeSet.empty(), where + ": \"Node Set\" is required");
    checkSet(condition.nodeSet, where + "/Node Set");
    condition.components = componentsFrom(getOr(sub, "Components", std::string("xyz")), where);
    if (sub.isParameter("Displacement")) condition.value = vector3(sub, "Displacement", where);
    scene.displacementConditions.push_back(condition);
  }
  if (paperDefaults && scene.dirichletNodeSets.empty() && scene.displacementConditions.empty())
    scene.dirichletNodeSets = {"dirichlet_aluminium", "dirichlet_steel"};  // the paper's clamps
}
}  // namespace

Scene buildScene(const ParameterList& tribos, const std::string& source, MPI_Comm comm) {
  Scene scene;
  scene.source = source;
  const ParameterList& meshList = tribos.sublist("Mesh");
  const bool twoBricks = meshGenerator(meshList) == MeshGenerator::TwoBricks;
  readMesh(meshList, source, comm, scene);
  readMaterials(tribos.sublist("Materials"), source, twoBricks, scene);
  readLoads(tribos.sublist("Loads"), source, twoBricks, scene);
  scene.zeroComponents =
      core::valueOf(feti::kZeroComponentNames, tribos.sublist("FETI").get<std::string>("Displacement Conditions"));

  readBoundary(tribos.sublist("Boundary"), source, twoBricks, scene);
  readLoadSteps(tribos.sublist("Load Steps"), source, scene);
  scene.contacts = readContactInterfaces(tribos.sublist("Contact"), source);
  readPretensions(tribos.sublist("Pretension"), source, scene);
  // A linear scene (no contact, or Bonded interfaces only) does not depend on the path; a
  // pretension section is solved as a history whatever the interfaces (its force by iterations).
  const bool tiedOnly = std::all_of(scene.contacts.begin(), scene.contacts.end(), [](const ContactInterface& one) {
    return one.law.tiesSurfaces();
  });
  const bool linear = tiedOnly && scene.pretensions.empty();
  core::requireInput(!scene.loadHistory || !linear,
                     source + ": Load Steps: the scene is linear (no contact, or only Bonded interfaces), so its "
                              "answer does not depend on the load path: give the last step's loads in one step");
  scene.pairingUpdates = tiedOnly ? 0 : tribos.sublist("Solver").get<int>("Pairing Updates");
  for (const auto& one : scene.contacts)
    for (const auto* name : {&one.rows.slaveSideSet, &one.rows.masterSideSet}) {
      try {
        mesh::requireSideSet(scene.mesh, *name);  // a node set of that name stands for its boundary faces
      } catch (const InputError& e) {
        throw InputError(source + ": " + one.rows.list() + ": " + e.what());
      }
    }
  return scene;
}

std::string meshFilePath(const ParameterList& tribos, const std::string& source) {
  return meshPath(tribos.sublist("Mesh"), source);
}

MeshGenerator meshGenerator(const ParameterList& meshList) {
  return core::valueOf(kMeshGeneratorNames, meshList.get<std::string>("Generator"));
}

}  // namespace tribos::stack
