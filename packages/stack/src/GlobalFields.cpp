#include "tribos/stack/GlobalFields.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

std::vector<std::array<double, 3>> gatherReactions(const Scene& scene, const feti::ConstraintMatrix& B,
                                                   const std::vector<double>& ownedLambda, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  const size_t numNodes = static_cast<size_t>(scene.mesh.numNodes());
  std::vector<double> local(3 * numNodes, 0.0);
  // Every row lives in the blocks of the subdomains it touches; a Dirichlet row touches one.
  for (size_t s = 0; s < B.blocks.size(); ++s) {
    const auto& block = B.blocks[s];
    const auto& nodes = scene.decomposition.subdomains[s].nodes;
    for (size_t i = 0; i < block.rows.size(); ++i) {
      const GO row = block.rows[i];
      if (row < first || row >= end || B.kind[row] != feti::RowKind::Dirichlet) continue;
      for (LO k = block.rowPtr[i]; k < block.rowPtr[i + 1]; ++k) {
        const LO dof = block.dof[k];
        local[3 * static_cast<size_t>(nodes[dof / 3]) + dof % 3] -= block.value[k] * ownedLambda[row - first];
      }
    }
  }
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
