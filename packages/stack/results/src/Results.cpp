#include "tribos/stack/Results.hpp"

#include <algorithm>
#include <cmath>

#include "tribos/fem/ElementKernels.hpp"
#include "tribos/fem/SolidElements.hpp"
#include "PatchRecovery.hpp"

namespace tribos::stack {

namespace {
double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

/// The body whose elements a node's mean stress is taken over: the first block that holds it.
std::vector<int> nodeBody(const mesh::Mesh& mesh) {
  std::vector<int> body(mesh.numNodes(), -1);
  for (int b = 0; b < mesh.numBlocks(); ++b)
    for (LO e = mesh.blocks[b].first; e < mesh.blocks[b].first + mesh.blocks[b].count; ++e)
      for (LO n : mesh.elementNodes(e))
        if (body[n] < 0) body[n] = b;
  return body;
}

/// Sums each element's stresses at its nodes (ElementStress::atNodes), weighted by the
/// element's volume, into the nodes of its body: `weight` gathers the volumes.
void addAtNodes(const mesh::Mesh& mesh, LO e, const std::vector<int>& body, int b, const fem::ElementStress& stress,
                std::vector<double>& weight, StressResults& r) {
  const auto nodes = mesh.elementNodes(e);
  for (int v = 0; v < nodes.size(); ++v) {
    const LO n = nodes[v];
    if (body[n] != b) continue;
    weight[n] += stress.volume;
    for (int k = 0; k < 6; ++k) r.nodal[k][n] += stress.volume * stress.atNodes[v][k];
  }
}

/// Divides the sums by the weights and takes the nodes' von Mises stresses.
void finishNodalMeans(const std::vector<double>& weight, StressResults& r) {
  r.nodalVonMises.assign(weight.size(), 0.0);
  for (size_t n = 0; n < weight.size(); ++n) {
    if (!(weight[n] > 0.0)) continue;  // a node of no element
    double sigma[6];
    for (int k = 0; k < 6; ++k) sigma[k] = r.nodal[k][n] /= weight[n];
    r.nodalVonMises[n] = fem::vonMisesStress(sigma);
  }
}
}  // namespace

StressResults evaluateStresses(const Scene& scene, const std::vector<std::array<double, 3>>& displacement) {
  const auto& mesh = scene.mesh;
  StressResults r;
  for (auto& c : r.element) c.assign(mesh.numElements(), 0.0);
  r.elementVonMises.assign(mesh.numElements(), 0.0);
  for (auto& c : r.nodal) c.assign(mesh.numNodes(), 0.0);
  const auto body = nodeBody(mesh);
  std::vector<double> weight(mesh.numNodes(), 0.0);
  for (int b = 0; b < mesh.numBlocks(); ++b) {
    const auto& material = scene.materials[b];
    for (LO e = mesh.blocks[b].first; e < mesh.blocks[b].first + mesh.blocks[b].count; ++e) {
      double x[mesh::kMaxElementNodes][3], u[fem::kMaxElementDofs];
      const auto nodes = mesh.elementNodes(e);
      for (int v = 0; v < nodes.size(); ++v)
        for (int c = 0; c < 3; ++c) {
          x[v][c] = mesh.coords[nodes[v]][c];
          u[3 * v + c] = displacement[nodes[v]][c];
        }
      const fem::ElementStress stress = fem::solidStress(mesh.elementType(e), x, u, material.lambda, material.mu);
      if (!(stress.volume > 0.0)) continue;  // Mesh::validate rejects these; never read garbage
      for (int k = 0; k < 6; ++k) r.element[k][e] = stress.sigma[k];
      r.elementVonMises[e] = fem::vonMisesStress(stress.sigma);
      r.strainEnergy += stress.strainEnergy;
      addAtNodes(mesh, e, body, b, stress, weight, r);
    }
  }
  finishNodalMeans(weight, r);
  recoverLinearElementStresses(scene, displacement, body, r);
  return r;
}

ForceBalance forceBalance(const Scene& scene, const std::vector<std::array<double, 3>>& nodalReaction,
                          const std::array<double, 3>& appliedLoad, double appliedLoadMagnitude) {
  ForceBalance out;
  out.appliedLoad = appliedLoad;
  auto sumOver = [&](const std::string& name, const std::string& nodeSet, const std::array<bool, 3>& components) {
    ConditionReaction r{name, {0.0, 0.0, 0.0}};
    for (LO n : scene.mesh.nodeSet(nodeSet).nodes)
      for (int c = 0; c < 3; ++c)
        if (components[c]) r.force[c] += nodalReaction[n][c];
    out.reactions.push_back(r);
  };
  for (const auto& set : scene.dirichletNodeSets) sumOver(set, set, {true, true, true});
  for (const auto& condition : scene.displacementConditions)
    sumOver(condition.name, condition.nodeSet, condition.components);

  double reactionMagnitude = 0.0;
  for (const auto& r : nodalReaction) {
    for (int c = 0; c < 3; ++c) out.totalReaction[c] += r[c];
    reactionMagnitude += norm(r);
  }
  const std::array<double, 3> residual{out.totalReaction[0] + appliedLoad[0], out.totalReaction[1] + appliedLoad[1],
                                       out.totalReaction[2] + appliedLoad[2]};
  const double scale = std::max({norm(appliedLoad), appliedLoadMagnitude, reactionMagnitude});
  out.relativeImbalance = scale > 0.0 ? norm(residual) / scale : 0.0;
  return out;
}

}  // namespace tribos::stack
