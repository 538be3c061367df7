#include "tribos/stack/RankData.hpp"

#include "ConditionSteps.hpp"

namespace tribos::stack {

namespace {
template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}
}  // namespace

void keepRankData(Scene& scene, feti::ConstraintMatrix& B, int rank, int numRanks) {
  auto& subdomains = scene.decomposition.subdomains;
  const int numSubdomains = static_cast<int>(subdomains.size());
  const int first = mesh::firstSubdomain(rank, numSubdomains, numRanks);
  const int end = mesh::firstSubdomain(rank + 1, numSubdomains, numRanks);
  feti::keepRankRows(B, rank, first, end);
  // The rows are built again on the deformed bodies, or for conditions switched between steps.
  if (scene.pairingUpdates > 0 || conditionRuns(scene).size() > 1) return;
  for (int s = 0; s < numSubdomains; ++s) {
    release(subdomains[s].elements);
    subdomains[s].localElements.release();
    if (s < first || s >= end) release(subdomains[s].nodes);
  }
  if (rank == 0) return;  // rank 0 writes the results on the global mesh
  scene.mesh.elements.release();
  release(scene.mesh.elementNumbers);
  release(scene.mesh.sideSets);
  release(scene.decomposition.elementPart);
}

HeldRows heldRows(const feti::ConstraintMatrix& B) {
  HeldRows held;
  for (const auto& block : B.blocks) {
    held.rows += static_cast<long long>(block.rows.size());
    held.nonzeros += static_cast<long long>(block.value.size());
  }
  return held;
}

}  // namespace tribos::stack
