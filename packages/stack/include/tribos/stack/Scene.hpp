#pragma once
/// \file Scene.hpp
/// A scene: the mesh, its decomposition into subdomains, materials, loads and boundary
/// parts, built from a validated parameter list. Every rank builds the whole (global) mesh
/// and decomposition — cheap next to the subdomain work — and then works on its own
/// subdomains (mesh::firstSubdomain); stack::keepRankData frees what the solve does not need.
#include <array>
#include <string>
#include <vector>

#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/Mesh.hpp"

namespace Teuchos {
class ParameterList;
}

namespace tribos::stack {

struct ContactSettings {
  std::string frictionModel;  ///< None | Tresca | Coulomb | Bonded
  double F1 = 0.0, F2 = 0.0;  ///< friction coefficients along t1, t2
  std::string slaveSideSet, masterSideSet;
  std::array<double, 3> t1Direction{1.0, 0.0, 0.0};
  double searchDistance = 1e-6;
  std::string discretization = "Mortar";  ///< Mortar | Node To Surface
  bool hasContact() const { return !slaveSideSet.empty(); }
};

struct Scene {
  std::string source;                      ///< where the parameters came from (for messages)
  mesh::Mesh mesh;
  mesh::Decomposition decomposition;
  std::vector<fem::Material> materials;    ///< per element block
  fem::Loads loads;
  std::vector<std::string> dirichletNodeSets;  ///< all components zero
  std::vector<feti::DisplacementCondition> displacementConditions;  ///< Boundary/<name> sublists
  ContactSettings contact;
  double meshSeconds = 0.0, decompositionSeconds = 0.0;
};

/// Builds the scene from the "Tribos" list, which must already be validated against
/// sceneValidParameters() (defaults filled in). Throws core::InputError naming the
/// parameter, file or mesh entity on bad input. `source` names the XML file in messages.
Scene buildScene(const Teuchos::ParameterList& tribos, const std::string& source);

/// The mesh file the validated "Tribos" list reads (Mesh/File, a relative path taken from the
/// scene file's directory); empty for a generated mesh.
std::string meshFilePath(const Teuchos::ParameterList& tribos, const std::string& source);

}  // namespace tribos::stack
