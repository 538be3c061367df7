#pragma once
/// \file Scene.hpp
/// A scene: the mesh, its decomposition into subdomains, materials, loads and boundary
/// parts, built from a validated parameter list. Every rank builds the whole (global) mesh
/// and decomposition — cheap next to the subdomain work — and then works on its own
/// subdomains (mesh::firstSubdomain); stack::keepRankData frees what the solve does not need.
#include <mpi.h>

#include <array>
#include <string>
#include <vector>

#include "tribos/contact/FrictionModel.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

/// Mesh/Generator and Mesh/Decomposition.
enum class MeshGenerator { TwoBricks, Exodus };
inline constexpr core::EnumNames<MeshGenerator, 2> kMeshGeneratorNames{
    {{"Two Bricks", MeshGenerator::TwoBricks}, {"Exodus", MeshGenerator::Exodus}}};
enum class MeshDecomposition { Structured, Metis };
inline constexpr core::EnumNames<MeshDecomposition, 2> kMeshDecompositionNames{
    {{"Structured", MeshDecomposition::Structured}, {"METIS", MeshDecomposition::Metis}}};

/// The validated Mesh list's generator.
MeshGenerator meshGenerator(const Teuchos::ParameterList& meshList);

/// One contact interface: the flat Contact list (one interface), or each Contact/<name>
/// sublist (several; readContactInterfaces in SceneParameters.hpp).
struct ContactInterface {
  feti::ContactInterfaceSpec rows;  ///< surfaces, t1, search, discretisation (tangentialRows from the law)
  contact::FrictionLaw law;
};

/// A bolt pretension section (Pretension/<name>): the two surfaces of a Bonded interface, a cut
/// through a bolt, pulled into each other along the interface's normal by a shortening s (the
/// tied normal rows read (u_slave - chi u_master) . nu = s instead of 0; stack/history/include/tribos/stack/Pretension.hpp).
struct PretensionSection {
  std::string name;
  size_t interface = 0;   ///< index into Scene::contacts (Bonded)
  bool byForce = true;    ///< Force given; else Shortening
  double target = 0.0;    ///< the force or the shortening at the end of `steps`
  int steps = 1;          ///< ramped k / steps over steps 1..steps, then locked
  double forceTolerance = 1e-6;  ///< Force Tolerance (relative to the force)
};

struct Scene {
  std::string source;                      ///< where the parameters came from (for messages)
  mesh::Mesh mesh;
  mesh::Decomposition decomposition;
  std::vector<fem::Material> materials;    ///< per element block
  fem::Loads loads;
  /// Each Loads/<name> on its own (a load history scales them separately), in the list's order.
  std::vector<std::pair<std::string, fem::Loads>> namedLoads;
  int loadSteps = 1;  ///< Load Steps/Number Of Steps
  bool loadHistory = false;  ///< several steps, or a load's Factors table (solved step by step)
  /// Per named load, its factor in each step (Load Steps/<name>/Factors, else the ramp k / N).
  std::vector<std::vector<double>> loadFactors;
  std::vector<std::string> dirichletNodeSets;  ///< all components zero
  std::vector<feti::DisplacementCondition> displacementConditions;  ///< Boundary/<name> sublists
  /// Per displacement condition, its factor in each step (Load Steps/<name>/Factors, else the
  /// ramp k / N).
  std::vector<std::vector<double>> displacementFactors;
  /// Per displacement condition, whether it holds in each step (Load Steps/<name>/Active, else
  /// every step): a condition that takes hold after step 1 holds its nodes where the step
  /// before left them (stack/solve/src/ConditionSteps.hpp).
  std::vector<std::vector<char>> conditionActive;
  /// Load Steps/Times: the time of each step in the results (default: the ramp k / N).
  std::vector<double> stepTimes;
  std::vector<ContactInterface> contacts;  ///< none: no contact
  std::vector<PretensionSection> pretensions;  ///< Pretension/<name> sublists (a load history)
  /// Solver/Pairing Updates for a contact problem; 0 for a linear scene.
  int pairingUpdates = 0;
  /// FETI/Displacement Conditions: which components prescribed to 0 leave K_s instead of
  /// getting rows of B (feti::ConstraintSpec::zeroComponents).
  feti::ZeroComponents zeroComponents = feti::ZeroComponents::Automatic;
  /// How the subdomain count was chosen where Mesh/Subdomains is 0 (empty where given).
  std::string subdomainChoice;
  double meshSeconds = 0.0, decompositionSeconds = 0.0;
};

/// Builds the scene from the "Tribos" list, which must already be validated against
/// sceneValidParameters() (defaults filled in). Throws core::InputError naming the
/// parameter, file or mesh entity on bad input. `source` names the XML file in messages.
/// With `comm`, a mesh read from a file is read on every rank of it or none, and compared
/// over them before it is partitioned (readMeshOnEveryRank): collective then.
Scene buildScene(const Teuchos::ParameterList& tribos, const std::string& source, MPI_Comm comm = MPI_COMM_NULL);

/// The mesh file the validated "Tribos" list reads (Mesh/File, a relative path taken from the
/// scene file's directory); empty for a generated mesh.
std::string meshFilePath(const Teuchos::ParameterList& tribos, const std::string& source);

}  // namespace tribos::stack
