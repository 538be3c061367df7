// PackedFactor's split of the elimination tree into independent subtrees (planSubtrees):
// the triangular solves of a large replicated factor (G G^T) on the threads of
// core::forEachSubdomain, with the same bits for any number of threads.
//
// In postorder a subtree is a contiguous range of supernodes, and its columns a contiguous
// range of columns; its panel rows are either its own columns or columns of its ancestors,
// which lie outside every subtree (the "top"). So:
//  - forward: the subtrees run concurrently, each updating its own rows in x and storing its
//    updates of top rows (t_r, one per panel row) in order; then, on the calling thread and
//    in supernode order, the stored updates of each subtree are subtracted and the top
//    supernodes solved. Top rows are only written while a subtree runs, never read, so every
//    entry of x sees the subtractions of the serial solve in the serial order;
//  - backward: the top supernodes first (calling thread), then the subtrees concurrently,
//    each reading top rows that no longer change.
// The bits are those of the serial solve, for any number of threads.
#include <algorithm>
#include <numeric>

#include "PackedFactor.hpp"
#include "tribos/core/Parallel.hpp"

namespace tribos::feti {

namespace {
/// The split stops at this many subtrees. Measured on G G^T at 20x10x10 / H/h 2
/// (doc/coarse_problem.md): four leave 14 % of the factor in the top, sixteen 49 % (in 3D the
/// separators hold much of the factor), and two threads get equal halves of the four.
constexpr int kTargetSubtrees = 4;
}  // namespace

struct PackedFactor::Subtrees {
  std::vector<LO> first, last;      ///< supernode range [first, last) of each subtree, ascending
  std::vector<LO> columnEnd;        ///< one past the last column of each subtree
  std::vector<int> schedule;        ///< the subtrees by decreasing size: the order of the tasks only
  /// The supernodes in order as segments: a subtree (index >= 0) or a top run [first, last).
  struct Segment {
    int subtree;
    LO first, last;
  };
  std::vector<Segment> segments;
  std::vector<size_t> panelOffset, updateOffset;  ///< per subtree, into work
  size_t topPanelOffset = 0;                      ///< panel work of the top supernodes
  double topShare = 0.0;
  mutable std::vector<double> work;  ///< per subtree: panel work, then its stored top updates
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
  long long subtreeValues = 0;
  size_t workSize = 0;
  for (LO root : chosen) {
    const LO first = firstDescendant[root], columnEnd = supernodes_[root].firstColumn + supernodes_[root].numColumns;
    LO maxRows = 0;
    size_t topUpdates = 0;
    for (LO k = first; k <= root; ++k) {
      const Supernode& s = supernodes_[k];
      maxRows = std::max(maxRows, s.numPanelRows);
      const LO* rows = rows_.data() + s.rowOffset;
      topUpdates += static_cast<size_t>(rows + s.numPanelRows - std::lower_bound(rows, rows + s.numPanelRows, columnEnd));
    }
    plan->first.push_back(first);
    plan->last.push_back(root + 1);
    plan->columnEnd.push_back(columnEnd);
    plan->panelOffset.push_back(workSize);
    plan->updateOffset.push_back(workSize + static_cast<size_t>(maxRows));
    workSize += static_cast<size_t>(maxRows) + topUpdates;
    subtreeValues += values[root];
  }
  LO maxTopRows = 0;
  for (LO k = 0, i = 0; k < ns;) {
    if (i < static_cast<LO>(chosen.size()) && k == plan->first[i]) {
      plan->segments.push_back({static_cast<int>(i), plan->first[i], plan->last[i]});
      k = plan->last[i++];
      continue;
    }
    if (plan->segments.empty() || plan->segments.back().subtree >= 0) plan->segments.push_back({-1, k, k});
    maxTopRows = std::max(maxTopRows, supernodes_[k].numPanelRows);
    plan->segments.back().last = ++k;
  }
  const int count = static_cast<int>(chosen.size());
  plan->schedule.resize(count);
  std::iota(plan->schedule.begin(), plan->schedule.end(), 0);
  std::stable_sort(plan->schedule.begin(), plan->schedule.end(),
                   [&](int a, int b) { return values[chosen[a]] > values[chosen[b]]; });
  plan->topPanelOffset = workSize;
  plan->work.assign(workSize + static_cast<size_t>(maxTopRows), 0.0);
  long long total = 0;
  for (LO root : roots) total += values[root];
  plan->topShare = total > 0 ? 1.0 - static_cast<double>(subtreeValues) / static_cast<double>(total) : 0.0;
  subtrees_ = std::move(plan);
  return true;
}

void PackedFactor::solveSubtrees(double* v) const {
  const Subtrees& p = *subtrees_;
  const int count = static_cast<int>(p.first.size());
  double* work = p.work.data();
  const LO n = size();
  // Forward: the subtrees (any thread), then in supernode order their stored top updates and
  // the top supernodes.
  core::forEachSubdomain(count, [&](int task) {
    const int i = p.schedule[task];
    forward(p.first[i], p.last[i], v, work + p.panelOffset[i], p.columnEnd[i], work + p.updateOffset[i]);
  });
  double* panelWork = work + p.topPanelOffset;
  for (const auto& segment : p.segments) {
    if (segment.subtree >= 0)
      applyTopUpdates(segment.first, segment.last, v, p.columnEnd[segment.subtree], work + p.updateOffset[segment.subtree]);
    else
      forward(segment.first, segment.last, v, panelWork, n, nullptr);
  }
  // Backward: the top from its last supernode, then the subtrees (any thread).
  for (auto segment = p.segments.rbegin(); segment != p.segments.rend(); ++segment)
    if (segment->subtree < 0) backward(segment->first, segment->last, v, panelWork);
  core::forEachSubdomain(count, [&](int task) {
    const int i = p.schedule[task];
    backward(p.first[i], p.last[i], v, work + p.panelOffset[i]);
  });
}

}  // namespace tribos::feti
