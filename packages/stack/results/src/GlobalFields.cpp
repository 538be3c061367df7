#include "tribos/stack/GlobalFields.hpp"

#include <Teuchos_DefaultMpiComm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "tribos/core/ReproducibleSum.hpp"
#include "tribos/geometry/MortarCoupling.hpp"
#include "tribos/stack/RootGather.hpp"

namespace tribos::stack {

GlobalDisplacement gatherDisplacement(const Scene& scene, int firstOwned, const std::vector<std::vector<double>>& u,
                                      MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  // One record per copy of a node in an owned subdomain: its global id and u there.
  Records mine;
  mine.width = 3;
  for (size_t i = 0; i < u.size(); ++i) {
    const auto& nodes = scene.decomposition.subdomains[firstOwned + static_cast<int>(i)].nodes;
    for (size_t k = 0; k < nodes.size(); ++k) mine.add(nodes[k], &u[i][3 * k]);
  }
  const Records all = gatherToRoot(mine, comm);
  GlobalDisplacement out;
  if (rank != 0) return out;
  // Per node: the sum of the copies (in subdomain order, whatever the number of ranks), their
  // count, and min and max per component.
  const size_t numNodes = static_cast<size_t>(scene.mesh.numNodes());
  out.value.assign(numNodes, {0.0, 0.0, 0.0});
  std::vector<int> copies(numNodes, 0);
  std::vector<std::array<double, 3>> lo(numNodes), hi(numNodes);
  for (size_t k = 0; k < all.size(); ++k) {
    const size_t g = static_cast<size_t>(all.index[k]);
    const double* v = &all.values[3 * k];
    for (int c = 0; c < 3; ++c) {
      out.value[g][c] += v[c];
      lo[g][c] = copies[g] == 0 ? v[c] : std::min(lo[g][c], v[c]);
      hi[g][c] = copies[g] == 0 ? v[c] : std::max(hi[g][c], v[c]);
    }
    ++copies[g];
  }
  for (size_t g = 0; g < numNodes; ++g) {
    if (copies[g] == 0) continue;
    for (int c = 0; c < 3; ++c) {
      out.value[g][c] /= copies[g];
      out.maxCopyJump = std::max(out.maxCopyJump, hi[g][c] - lo[g][c]);
    }
  }
  return out;
}

namespace {
/// Calls f(row, node, component, value) for every entry of a Dirichlet row (one per row).
template <class F>
void forEachDirichletEntry(const Scene& scene, const feti::ConstraintMatrix& B, F&& f) {
  // Every row lives in the blocks of the subdomains it touches; a Dirichlet row touches one.
  for (size_t s = 0; s < B.blocks.size(); ++s) {
    const auto& block = B.blocks[s];
    const auto& nodes = scene.decomposition.subdomains[s].nodes;
    for (size_t i = 0; i < block.rows.size(); ++i) {
      if (B.kind[block.rows[i]] != feti::RowKind::Dirichlet) continue;
      for (LO k = block.rowPtr[i]; k < block.rowPtr[i + 1]; ++k)
        f(block.rows[i], nodes[block.dof[k] / 3], block.dof[k] % 3, block.value[k]);
    }
  }
}

/// Whether component c of a node is prescribed, from the displacement conditions (their node
/// sets are sorted): a rank holds the Dirichlet rows of its own subdomains only
/// (feti::keepRankRows), and an owned contact row may reach a node that none of them has.
class PrescribedComponents {
 public:
  explicit PrescribedComponents(const Scene& scene) {
    for (const auto& name : scene.dirichletNodeSets) sets_.push_back({&scene.mesh.nodeSet(name).nodes, {true, true, true}});
    for (const auto& condition : scene.displacementConditions)
      sets_.push_back({&scene.mesh.nodeSet(condition.nodeSet).nodes, condition.components});
  }
  bool operator()(LO node, int c) const {
    for (const auto& [nodes, components] : sets_)
      if (components[c] && std::binary_search(nodes->begin(), nodes->end(), node)) return true;
    return false;
  }

 private:
  std::vector<std::pair<const std::vector<LO>*, std::array<bool, 3>>> sets_;
};

/// The contact forces that a support takes directly. A contact row drops the prescribed
/// components of its nodes (feti/ConstraintMatrix.hpp), so K u = f - B^T lambda never applies
/// its force -B_full lambda to them, yet the body is pressed there all the same and the
/// support holds that component: its reaction gains + B_full,ri lambda_r (B_full: the row
/// before dropping, weight 1 on the slave and -w_j on master j, times the direction and the
/// row's scale). Without this, reactions and load would not balance where a contact surface
/// meets a symmetry plane. One record (3 node + component, force) per term.
void addDroppedContactForces(const feti::ConstraintMatrix& B, const PrescribedComponents& prescribed, GO first,
                             GO end, const std::vector<double>& ownedLambda, Records& reaction) {
  for (const auto& node : B.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;  // its rows are on another rank
    const std::vector<std::pair<LO, double>> sides = node.sides();
    for (int d = 0; d < 3; ++d) {
      const GO row = node.row(d);
      if (row < 0) continue;
      const double lambda = ownedLambda[row - first];
      for (const auto& [g, weight] : sides)
        for (int c = 0; c < 3; ++c)
          if (prescribed(g, c)) {
            const double force = weight * node.direction(d)[c] * node.scale(d) * lambda;
            reaction.add(3 * static_cast<long long>(g) + c, &force);
          }
    }
  }
}
}  // namespace

std::vector<std::array<double, 3>> gatherReactions(const Scene& scene, const feti::ConstraintMatrix& B,
                                                   const std::vector<feti::EliminatedReaction>& eliminated,
                                                   const std::vector<double>& ownedLambda, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  // Records (3 node + component, force) of this rank's rows, summed on rank 0 in rank order.
  Records mine;
  forEachDirichletEntry(scene, B, [&](GO row, LO node, int component, double value) {
    if (row < first || row >= end) return;
    const double force = -(value * ownedLambda[row - first]);
    mine.add(3 * static_cast<long long>(node) + component, &force);
  });
  addDroppedContactForces(B, PrescribedComponents(scene), first, end, ownedLambda, mine);
  for (const auto& r : eliminated) {
    const LO node = scene.decomposition.subdomains[r.subdomain].nodes[r.dof / 3];
    mine.add(3 * static_cast<long long>(node) + r.dof % 3, &r.force);
  }
  const Records all = gatherToRoot(mine, comm);
  std::vector<std::array<double, 3>> out;
  if (rank != 0) return out;
  out.assign(static_cast<size_t>(scene.mesh.numNodes()), {0.0, 0.0, 0.0});
  for (size_t k = 0; k < all.size(); ++k) out[all.index[k] / 3][all.index[k] % 3] += all.values[k];
  return out;
}

std::array<double, 3> totalLoad(const std::vector<fem::SubdomainSystem>& owned, MPI_Comm comm) {
  std::array<double, 3> local{0.0, 0.0, 0.0}, global{0.0, 0.0, 0.0};
  for (const auto& s : owned)
    for (size_t i = 0; i < s.f.size(); ++i) local[i % 3] += s.f[i];
  MPI_Allreduce(local.data(), global.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

double loadMagnitude(const std::vector<fem::SubdomainSystem>& owned, MPI_Comm comm) {
  std::vector<double> terms;
  for (const auto& s : owned)
    for (size_t i = 0; i + 2 < s.f.size(); i += 3) terms.push_back(std::hypot(s.f[i], s.f[i + 1], s.f[i + 2]));
  long long mine = static_cast<long long>(terms.size()), count = 0;
  MPI_Allreduce(&mine, &count, 1, MPI_LONG_LONG, MPI_SUM, comm);
  const Teuchos::MpiComm<int> teuchosComm(comm);
  return core::reproducibleSum(&teuchosComm, terms.data(), terms.size(), count);  // the same on every layout
}

std::vector<double> tributaryArea(const mesh::Mesh& mesh, const std::string& sideSet) {
  std::vector<double> area(mesh.numNodes(), 0.0);
  const auto& set = mesh.sideSet(sideSet);
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const auto n = mesh.faceNormal(set.elements[f], set.sides[f]);
    const mesh::FaceNodes face = mesh.faceNodes(set.elements[f], set.sides[f]);
    const auto vertices = face.vertices();
    const double twiceArea = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);  // |n| = 2 area
    if (face.numNodes == 6) {  // int phi~ of the transformed basis (geometry/MortarCoupling.hpp), flat face
      const double alpha = geometry::kQuadraticTransformAlpha;
      for (int k = 0; k < 6; ++k) area[face.node[k]] += (k < 3 ? 2.0 * alpha : 1.0 - 2.0 * alpha) / 6.0 * twiceArea;
      continue;
    }
    const double share = twiceArea / (2.0 * vertices.size());
    for (LO v : vertices) area[v] += share;
  }
  return area;
}

}  // namespace tribos::stack
