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
