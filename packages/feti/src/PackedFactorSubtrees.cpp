// PackedFactor's split of the elimination tree into independent subtrees (planSubtrees):
// the triangular solves of a large replicated factor (G G^T) on the threads of
// core::forEachSubdomain, with the same bits for any number of threads.
//
// In postorder a subtree is a contiguous range of supernodes, and its columns a contiguous
// range of columns; its panel rows are either its own columns or columns of its ancestors,
// which lie outside every subtree (the "top"). So:
//  - forward: the subtrees run concurrently, each updating its own rows in x and summing
//    its updates of top rows into its own buffer; the buffers are then subtracted from x in
//    subtree order, and the top supernodes solved in order on the calling thread;
//  - backward: the top supernodes first (calling thread), then the subtrees concurrently,
//    each reading top rows that no longer change.
// Which thread runs which subtree does not enter any sum, so the bits do not depend on the
// number of threads; the same buffered sums run on one thread.
#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "PackedFactor.hpp"
#include "tribos/core/Parallel.hpp"

namespace tribos::feti {

namespace {
/// The split stops at this many subtrees: enough for the dynamic schedule to balance two to
/// sixteen threads, few enough that the top (the separators above them) stays a small share.
constexpr int kTargetSubtrees = 4;
}  // namespace

struct PackedFactor::Subtrees {
  std::vector<LO> first, last;      ///< supernode range [first, last) of each subtree, ascending
  std::vector<LO> columnEnd;        ///< one past the last column of each subtree
  std::vector<int> schedule;        ///< the subtrees by decreasing size: the order of the tasks only
  std::vector<std::pair<LO, LO>> topRuns;  ///< ranges of supernodes outside every subtree
  std::vector<LO> topColumns;       ///< columns of the top supernodes, ascending
  std::vector<LO> topIndex;         ///< column -> its index in topColumns (-1: not a top column)
  std::vector<size_t> workOffset;   ///< per subtree: its panel work (maxPanelRows) and top updates
  size_t workStride = 0;
  double topShare = 0.0;
  mutable std::vector<double> work;  ///< per subtree, workStride entries
};

PackedFactor::PackedFactor() = default;
PackedFactor::~PackedFactor() = default;
PackedFactor::PackedFactor(PackedFactor&&) noexcept = default;
PackedFactor& PackedFactor::operator=(PackedFactor&&) noexcept = default;

int PackedFactor::numSubtrees() const { return subtrees_ ? static_cast<int>(subtrees_->first.size()) : 0; }
double PackedFactor::topShare() const { return subtrees_ ? subtrees_->topShare : 0.0; }

bool PackedFactor::planSubtrees(long long fromValues) {
  subtrees_.reset();
  const LO ns = numSupernodes(), n = size();
  if (storedValues() < fromValues || ns < 2) return false;
  // Supernode tree: the parent of a supernode holds its first panel row (the parent of its
  // last column in the elimination tree).
  std::vector<LO> supernodeOfColumn(n);
  for (LO k = 0; k < ns; ++k)
    for (LO j = 0; j < supernodes_[k].numColumns; ++j) supernodeOfColumn[supernodes_[k].firstColumn + j] = k;
  std::vector<LO> parent(ns, -1), firstDescendant(ns), subtreeSize(ns, 1);
  std::vector<long long> values(ns, 0);
  std::iota(firstDescendant.begin(), firstDescendant.end(), 0);
  for (LO k = 0; k < ns; ++k) {
    const Supernode& s = supernodes_[k];
    values[k] += static_cast<long long>(s.numColumns) * (s.numColumns + 1) / 2 +
                 static_cast<long long>(s.numColumns) * s.numPanelRows;
    if (s.numPanelRows == 0) continue;
    const LO p = supernodeOfColumn[rows_[s.rowOffset]];
    if (p <= k) return false;  // not an elimination tree in this order
    parent[k] = p;
    firstDescendant[p] = std::min(firstDescendant[p], firstDescendant[k]);
    subtreeSize[p] += subtreeSize[k];
    values[p] += values[k];
  }
  // Postorder: every subtree is the contiguous range [firstDescendant, k].
  for (LO k = 0; k < ns; ++k)
    if (subtreeSize[k] != k - firstDescendant[k] + 1) return false;
  std::vector<std::vector<LO>> children(ns);
  std::vector<LO> roots;
  for (LO k = 0; k < ns; ++k) (parent[k] < 0 ? roots : children[parent[k]]).push_back(k);

  // Greedy: replace the largest subtree that has children by its children (its root joins
  // the top) until there are kTargetSubtrees of them.
  std::vector<LO> chosen = roots;
  for (int guard = 0; guard < ns && static_cast<int>(chosen.size()) < kTargetSubtrees; ++guard) {
    auto largest = chosen.end();
    for (auto it = chosen.begin(); it != chosen.end(); ++it)
      if (!children[*it].empty() && (largest == chosen.end() || values[*it] > values[*largest])) largest = it;
    if (largest == chosen.end()) break;
    const LO k = *largest;
    chosen.erase(largest);
    chosen.insert(chosen.end(), children[k].begin(), children[k].end());
  }
  if (chosen.size() < 2) return false;
  std::sort(chosen.begin(), chosen.end());

  auto plan = std::make_unique<Subtrees>();
  std::vector<char> inSubtree(ns, 0);
  long long subtreeValues = 0;
  LO maxRows = 0;
  for (LO root : chosen) {
    plan->first.push_back(firstDescendant[root]);
    plan->last.push_back(root + 1);
    plan->columnEnd.push_back(supernodes_[root].firstColumn + supernodes_[root].numColumns);
    subtreeValues += values[root];
    for (LO k = firstDescendant[root]; k <= root; ++k) {
      inSubtree[k] = 1;
      maxRows = std::max(maxRows, supernodes_[k].numPanelRows);
    }
  }
  plan->topIndex.assign(n, -1);
  for (LO k = 0; k < ns; ++k) {
    if (inSubtree[k]) continue;
    if (plan->topRuns.empty() || plan->topRuns.back().second != k) plan->topRuns.push_back({k, k});
    plan->topRuns.back().second = k + 1;
    for (LO j = 0; j < supernodes_[k].numColumns; ++j) {
      plan->topIndex[supernodes_[k].firstColumn + j] = static_cast<LO>(plan->topColumns.size());
      plan->topColumns.push_back(supernodes_[k].firstColumn + j);
    }
  }
  const int count = static_cast<int>(chosen.size());
  plan->schedule.resize(count);
  std::iota(plan->schedule.begin(), plan->schedule.end(), 0);
  std::stable_sort(plan->schedule.begin(), plan->schedule.end(),
                   [&](int a, int b) { return values[chosen[a]] > values[chosen[b]]; });
  plan->workStride = static_cast<size_t>(maxRows) + plan->topColumns.size();
  plan->work.assign(plan->workStride * count, 0.0);
  long long total = 0;
  for (LO root : roots) total += values[root];
  plan->topShare = total > 0 ? 1.0 - static_cast<double>(subtreeValues) / static_cast<double>(total) : 0.0;
  subtrees_ = std::move(plan);
  return true;
}

void PackedFactor::solveSubtrees(double* v) const {
  const Subtrees& p = *subtrees_;
  const int count = static_cast<int>(p.first.size());
  const size_t numTop = p.topColumns.size();
  double* work = p.work.data();
  const LO n = size();
  // Forward: the subtrees (any thread), their top updates in subtree order, then the top.
  core::forEachSubdomain(count, [&](int task) {
    const int i = p.schedule[task];
    double* panelWork = work + p.workStride * i;
    double* updates = panelWork + (p.workStride - numTop);
    std::fill(updates, updates + numTop, 0.0);
    forward(p.first[i], p.last[i], v, panelWork, p.columnEnd[i], p.topIndex.data(), updates);
  });
  for (int i = 0; i < count; ++i) {
    const double* updates = work + p.workStride * i + (p.workStride - numTop);
    for (size_t j = 0; j < numTop; ++j) v[p.topColumns[j]] -= updates[j];
  }
  for (const auto& run : p.topRuns) forward(run.first, run.second, v, work, n, nullptr, nullptr);
  // Backward: the top from its last supernode, then the subtrees (any thread).
  for (auto run = p.topRuns.rbegin(); run != p.topRuns.rend(); ++run) backward(run->first, run->second, v, work);
  core::forEachSubdomain(count, [&](int task) {
    const int i = p.schedule[task];
    backward(p.first[i], p.last[i], v, work + p.workStride * i);
  });
}

}  // namespace tribos::feti
