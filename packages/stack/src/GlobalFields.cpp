#include "tribos/stack/GlobalFields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "tribos/stack/LinearFetiSolve.hpp"

namespace tribos::stack {

GlobalDisplacement gatherDisplacement(const Scene& scene, int firstOwned, const std::vector<std::vector<double>>& u,
                                      MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const size_t numNodes = static_cast<size_t>(scene.mesh.numNodes());
  // Per node: sum of the copies (3) and their count; min and max per component.
  std::vector<double> sum(4 * numNodes, 0.0);
  std::vector<double> lo(3 * numNodes, std::numeric_limits<double>::max());
  std::vector<double> hi(3 * numNodes, std::numeric_limits<double>::lowest());
  for (size_t i = 0; i < u.size(); ++i) {
    const auto& nodes = scene.decomposition.subdomains[firstOwned + static_cast<int>(i)].nodes;
    for (size_t k = 0; k < nodes.size(); ++k) {
      const size_t g = static_cast<size_t>(nodes[k]);
      for (int c = 0; c < 3; ++c) {
        const double v = u[i][3 * k + c];
        sum[4 * g + c] += v;
        lo[3 * g + c] = std::min(lo[3 * g + c], v);
        hi[3 * g + c] = std::max(hi[3 * g + c], v);
      }
      sum[4 * g + 3] += 1.0;
    }
  }
  const bool root = rank == 0;
  std::vector<double> sumAll(root ? sum.size() : 0), loAll(root ? lo.size() : 0), hiAll(root ? hi.size() : 0);
  MPI_Reduce(sum.data(), sumAll.data(), static_cast<int>(sum.size()), MPI_DOUBLE, MPI_SUM, 0, comm);
  MPI_Reduce(lo.data(), loAll.data(), static_cast<int>(lo.size()), MPI_DOUBLE, MPI_MIN, 0, comm);
  MPI_Reduce(hi.data(), hiAll.data(), static_cast<int>(hi.size()), MPI_DOUBLE, MPI_MAX, 0, comm);
  GlobalDisplacement out;
  if (!root) return out;
  out.value.assign(numNodes, {0.0, 0.0, 0.0});
  for (size_t g = 0; g < numNodes; ++g) {
    const double copies = sumAll[4 * g + 3];
    if (copies <= 0) continue;
    for (int c = 0; c < 3; ++c) {
      out.value[g][c] = sumAll[4 * g + c] / copies;
      out.maxCopyJump = std::max(out.maxCopyJump, hiAll[3 * g + c] - loAll[3 * g + c]);
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

/// The contact forces that a support takes directly. A contact row drops the prescribed
/// components of its nodes (feti/ConstraintMatrix.hpp), so K u = f - B^T lambda never applies
/// its force -B_full lambda to them, yet the body is pressed there all the same and the
/// support holds that component: its reaction gains + B_full,ri lambda_r (B_full: the row
/// before dropping, weight 1 on the slave and -w_j on master j, times the direction and the
/// row's scale). Without this, reactions and load would not balance where a contact surface
/// meets a symmetry plane.
void addDroppedContactForces(const feti::ConstraintMatrix& B, const std::vector<char>& prescribed, GO first, GO end,
                             const std::vector<double>& ownedLambda, std::vector<double>& reaction) {
  for (const auto& node : B.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;  // its rows are on another rank
    std::vector<std::pair<LO, double>> sides{{node.slaveNode, 1.0}};
    for (size_t j = 0; j < node.masterNodes.size(); ++j) sides.push_back({node.masterNodes[j], -node.masterWeights[j]});
    const std::array<double, 3>* directions[3] = {&node.normal, &node.t1, &node.t2};
    for (int d = 0; d < 3; ++d) {
      const GO row = d == 0 ? node.normalRow : node.tangentialRow(d - 1);
      if (row < 0) continue;
      const double scale = d == 0 ? node.rowScale : node.tangentialScale[d - 1];
      const double lambda = ownedLambda[row - first];
      for (const auto& [g, weight] : sides)
        for (int c = 0; c < 3; ++c)
          if (prescribed[3 * static_cast<size_t>(g) + c])
            reaction[3 * static_cast<size_t>(g) + c] += weight * (*directions[d])[c] * scale * lambda;
    }
  }
}
}  // namespace

std::vector<std::array<double, 3>> gatherReactions(const Scene& scene, const feti::ConstraintMatrix& B,
                                                   const std::vector<double>& ownedLambda, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  const size_t numNodes = static_cast<size_t>(scene.mesh.numNodes());
  std::vector<double> local(3 * numNodes, 0.0);
  // From the displacement conditions, not from the Dirichlet rows: a rank holds the rows of
  // its own subdomains only (feti::keepRankRows), and an owned contact row may reach a node
  // that no owned subdomain has.
  const std::vector<char> prescribed = feti::prescribedComponents(scene.mesh, constraintSpec(scene));
  forEachDirichletEntry(scene, B, [&](GO row, LO node, int component, double value) {
    if (row >= first && row < end) local[3 * static_cast<size_t>(node) + component] -= value * ownedLambda[row - first];
  });
  addDroppedContactForces(B, prescribed, first, end, ownedLambda, local);
  std::vector<double> all(rank == 0 ? local.size() : 0);
  MPI_Reduce(local.data(), all.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_SUM, 0, comm);
  std::vector<std::array<double, 3>> out;
  if (rank != 0) return out;
  out.resize(numNodes);
  for (size_t n = 0; n < numNodes; ++n) out[n] = {all[3 * n], all[3 * n + 1], all[3 * n + 2]};
  return out;
}

std::array<double, 3> totalLoad(const std::vector<fem::SubdomainSystem>& owned, MPI_Comm comm) {
  std::array<double, 3> local{0.0, 0.0, 0.0}, global{0.0, 0.0, 0.0};
  for (const auto& s : owned)
    for (size_t i = 0; i < s.f.size(); ++i) local[i % 3] += s.f[i];
  MPI_Allreduce(local.data(), global.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

std::vector<double> tributaryArea(const mesh::Mesh& mesh, const std::string& sideSet) {
  std::vector<double> area(mesh.numNodes(), 0.0);
  const auto& set = mesh.sideSet(sideSet);
  for (size_t f = 0; f < set.elements.size(); ++f) {
    const auto& tet = mesh.tets[set.elements[f]];
    const auto n = mesh.faceNormal(set.elements[f], set.sides[f]);
    const double third = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) / 6.0;  // |n| = 2 area
    for (int v : mesh::kTetFaceVertices[set.sides[f]]) area[tet[v]] += third;
  }
  return area;
}

}  // namespace tribos::stack
