// PackedFactor's elimination tree (supernodeTree, greedyStates) and its split into independent
// subtrees (planSubtrees): the triangular solves of a large factor solved alone (G G^T on
// rank 0) on the threads of core::forEachSubdomain, with the same bits for any number of
// threads. Also the parts of the factor that DistributedCoarseSolve sends to other ranks
// (serialize, deserialize).
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
#include <cstring>
#include <numeric>
#include <stdexcept>

#include "PackedFactor.hpp"
#include "tribos/core/Parallel.hpp"

namespace tribos::feti {

namespace {
/// The split stops at this many subtrees. Measured on G G^T at 20x10x10 / H/h 2
/// (doc/measurements/coarse_problem.md): four leave 14 % of the factor in the top, sixteen 49 % (in 3D the
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

PackedFactor::SupernodeTree PackedFactor::supernodeTree() const {
  const LO ns = numSupernodes(), n = size();
  SupernodeTree tree;
  // The parent of a supernode holds its first panel row (the parent of its last column in
  // the elimination tree).
  std::vector<LO> supernodeOfColumn(n);
  for (LO k = 0; k < ns; ++k)
    for (LO j = 0; j < supernodes_[k].numColumns; ++j) supernodeOfColumn[supernodes_[k].firstColumn + j] = k;
  std::vector<LO> parent(ns, -1), firstDescendant(ns), subtreeSize(ns, 1);
  std::vector<long long> values(ns, 0), subtreeValues(ns, 0);
  std::iota(firstDescendant.begin(), firstDescendant.end(), 0);
  for (LO k = 0; k < ns; ++k) {
    const Supernode& s = supernodes_[k];
    values[k] = static_cast<long long>(s.numColumns) * (s.numColumns + 1) / 2 +
                static_cast<long long>(s.numColumns) * s.numPanelRows;
    subtreeValues[k] += values[k];
    if (s.numPanelRows == 0) continue;
    const LO p = supernodeOfColumn[rows_[s.rowOffset]];
    if (p <= k) return tree;  // not an elimination tree in this order
    parent[k] = p;
    firstDescendant[p] = std::min(firstDescendant[p], firstDescendant[k]);
    subtreeSize[p] += subtreeSize[k];
    subtreeValues[p] += subtreeValues[k];
  }
  // Postorder: every subtree is the contiguous range [firstDescendant, k].
  for (LO k = 0; k < ns; ++k)
    if (subtreeSize[k] != k - firstDescendant[k] + 1) return tree;
  tree.children.resize(ns);
  for (LO k = 0; k < ns; ++k) (parent[k] < 0 ? tree.roots : tree.children[parent[k]]).push_back(k);
  tree.parent = std::move(parent);
  tree.firstDescendant = std::move(firstDescendant);
  tree.values = std::move(values);
  tree.subtreeValues = std::move(subtreeValues);
  return tree;
}

std::vector<std::vector<LO>> PackedFactor::greedyStates(const SupernodeTree& tree, std::vector<LO> start,
                                                        int maxCount, int maxSteps) {
  std::vector<std::vector<LO>> states;
  auto record = [&](std::vector<LO> chosen) {
    std::sort(chosen.begin(), chosen.end());
    states.push_back(std::move(chosen));
  };
  std::vector<LO> chosen = std::move(start);
  record(chosen);
  for (int step = 0; step < maxSteps && static_cast<int>(chosen.size()) < maxCount; ++step) {
    auto largest = chosen.end();
    for (auto it = chosen.begin(); it != chosen.end(); ++it)
      if (!tree.children[*it].empty() &&
          (largest == chosen.end() || tree.subtreeValues[*it] > tree.subtreeValues[*largest]))
        largest = it;
    if (largest == chosen.end()) break;
    const LO k = *largest;
    chosen.erase(largest);
    chosen.insert(chosen.end(), tree.children[k].begin(), tree.children[k].end());
    record(chosen);
  }
  return states;
}

std::vector<PackedFactor::TreeSplit> PackedFactor::greedySplits(int maxCount) const {
  const SupernodeTree tree = supernodeTree();
  std::vector<TreeSplit> splits;
  if (tree.empty()) return splits;
  long long total = 0;
  for (LO root : tree.roots) total += tree.subtreeValues[root];
  for (const auto& roots : greedyStates(tree, tree.roots, maxCount, numSupernodes())) {
    TreeSplit split;
    split.totalValues = total;
    for (LO root : roots) {
      split.first.push_back(tree.firstDescendant[root]);
      split.last.push_back(root + 1);
      split.values.push_back(tree.subtreeValues[root]);
    }
    splits.push_back(std::move(split));
  }
  return splits;
}

std::vector<LO> PackedFactor::topUpdateRows(LO first, LO last, LO columnEnd) const {
  std::vector<LO> out;
  for (LO k = first; k < last; ++k) {
    const Supernode& s = supernodes_[k];
    const LO* rows = rows_.data() + s.rowOffset;
    out.insert(out.end(), std::lower_bound(rows, rows + s.numPanelRows, columnEnd), rows + s.numPanelRows);
  }
  return out;
}

long long PackedFactor::topUpdateCount(LO first, LO last, LO columnEnd) const {
  long long count = 0;
  for (LO k = first; k < last; ++k) {
    const Supernode& s = supernodes_[k];
    const LO* rows = rows_.data() + s.rowOffset;
    count += rows + s.numPanelRows - std::lower_bound(rows, rows + s.numPanelRows, columnEnd);
  }
  return count;
}

bool PackedFactor::planSubtrees(long long fromValues) {
  subtrees_.reset();
  const LO ns = numSupernodes();
  if (storedValues() < fromValues || ns < 2) return false;
  const std::vector<TreeSplit> splits = greedySplits(kTargetSubtrees);
  if (splits.empty()) return false;
  const TreeSplit& split = splits.back();  // the first with kTargetSubtrees, or the finest there is
  if (split.first.size() < 2) return false;

  auto plan = std::make_unique<Subtrees>();
  const int count = static_cast<int>(split.first.size());
  long long subtreeValues = 0;
  size_t workSize = 0;
  for (int i = 0; i < count; ++i) {
    const LO first = split.first[i], last = split.last[i], columnEnd = columnEndOf(last);
    LO maxRows = 0;
    for (LO k = first; k < last; ++k) maxRows = std::max(maxRows, supernodes_[k].numPanelRows);
    plan->first.push_back(first);
    plan->last.push_back(last);
    plan->columnEnd.push_back(columnEnd);
    plan->panelOffset.push_back(workSize);
    plan->updateOffset.push_back(workSize + static_cast<size_t>(maxRows));
    workSize += static_cast<size_t>(maxRows) + static_cast<size_t>(topUpdateCount(first, last, columnEnd));
    subtreeValues += split.values[i];
  }
  LO maxTopRows = 0;
  for (LO k = 0, i = 0; k < ns;) {
    if (i < count && k == plan->first[i]) {
      plan->segments.push_back({static_cast<int>(i), plan->first[i], plan->last[i]});
      k = plan->last[i++];
      continue;
    }
    if (plan->segments.empty() || plan->segments.back().subtree >= 0) plan->segments.push_back({-1, k, k});
    maxTopRows = std::max(maxTopRows, supernodes_[k].numPanelRows);
    plan->segments.back().last = ++k;
  }
  plan->schedule.resize(count);
  std::iota(plan->schedule.begin(), plan->schedule.end(), 0);
  std::stable_sort(plan->schedule.begin(), plan->schedule.end(),
                   [&](int a, int b) { return split.values[a] > split.values[b]; });
  plan->topPanelOffset = workSize;
  plan->work.assign(workSize + static_cast<size_t>(maxTopRows), 0.0);
  const long long total = split.totalValues;
  plan->topShare = total > 0 ? 1.0 - static_cast<double>(subtreeValues) / static_cast<double>(total) : 0.0;
  subtrees_ = std::move(plan);
  return true;
}

namespace {
void appendCount(std::vector<char>& bytes, size_t count) {
  const unsigned long long n = count;
  const char* header = reinterpret_cast<const char*>(&n);
  bytes.insert(bytes.end(), header, header + sizeof n);
}

template <class T>
void appendItems(std::vector<char>& bytes, const T* data, size_t count) {
  const char* begin = reinterpret_cast<const char*>(data);
  bytes.insert(bytes.end(), begin, begin + sizeof(T) * count);
}

template <class T>
void appendArray(std::vector<char>& bytes, const T* data, size_t count) {
  appendCount(bytes, count);
  appendItems(bytes, data, count);
}

template <class T>
std::vector<T> readArray(const std::vector<char>& bytes, size_t& at) {
  unsigned long long n = 0;
  if (at + sizeof n > bytes.size()) throw std::runtime_error("tribos::feti::PackedFactor::deserialize: truncated");
  std::memcpy(&n, bytes.data() + at, sizeof n);
  at += sizeof n;
  if (n > (bytes.size() - at) / sizeof(T)) throw std::runtime_error("tribos::feti::PackedFactor::deserialize: truncated");
  std::vector<T> v(static_cast<size_t>(n));
  if (n > 0) std::memcpy(v.data(), bytes.data() + at, sizeof(T) * v.size());
  at += sizeof(T) * v.size();
  return v;
}
}  // namespace

std::vector<char> PackedFactor::serialize(const std::vector<std::pair<LO, LO>>& ranges) const {
  // The layout of deserialize: supernodes (offsets into the part's arrays), row indices,
  // whether the values are single, the values (triangle then panel, supernode by supernode), reciprocal diagonal, permutation,
  // maxPanelRows.
  std::vector<Supernode> parts;
  size_t rows = 0, values = 0;
  LO maxRows = 0;
  for (const auto& [first, last] : ranges)
    for (LO k = first; k < last; ++k) {
      Supernode s = supernodes_[k];
      const long long triangle = static_cast<long long>(s.numColumns) * (s.numColumns - 1) / 2;
      s.rowOffset = static_cast<LO>(rows);
      s.triangleOffset = static_cast<long long>(values);
      s.panelOffset = s.triangleOffset + triangle;
      rows += static_cast<size_t>(s.numPanelRows);
      values += static_cast<size_t>(triangle + static_cast<long long>(s.numColumns) * s.numPanelRows);
      maxRows = std::max(maxRows, s.numPanelRows);
      parts.push_back(s);
    }
  std::vector<char> bytes;
  bytes.reserve(sizeof(Supernode) * parts.size() + sizeof(LO) * rows + static_cast<size_t>(valueBytes()) * values +
                (sizeof(double) + sizeof(LO)) * perm_.size() + 64);
  appendArray(bytes, parts.data(), parts.size());
  appendCount(bytes, rows);
  for (const auto& [first, last] : ranges)
    for (LO k = first; k < last; ++k)
      appendItems(bytes, rows_.data() + supernodes_[k].rowOffset, static_cast<size_t>(supernodes_[k].numPanelRows));
  const int single = single_ ? 1 : 0;
  appendArray(bytes, &single, 1);
  appendCount(bytes, values);
  auto appendValues = [&](const auto* all) {
    for (const auto& [first, last] : ranges)
      for (LO k = first; k < last; ++k) {
        const Supernode& s = supernodes_[k];
        appendItems(bytes, all + s.triangleOffset, static_cast<size_t>(s.numColumns) * (s.numColumns - 1) / 2);
        appendItems(bytes, all + s.panelOffset, static_cast<size_t>(s.numColumns) * s.numPanelRows);
      }
  };
  if (single_)
    appendValues(singleData_);
  else
    appendValues(valueData());
  appendArray(bytes, inverseDiagonal_.data(), inverseDiagonal_.size());
  appendArray(bytes, perm_.data(), perm_.size());
  appendArray(bytes, &maxRows, 1);
  return bytes;
}

PackedFactor PackedFactor::deserialize(const std::vector<char>& bytes) {
  PackedFactor f;
  size_t at = 0;
  f.supernodes_ = readArray<Supernode>(bytes, at);
  f.rows_ = readArray<LO>(bytes, at);
  const std::vector<int> single = readArray<int>(bytes, at);
  f.single_ = !single.empty() && single[0] != 0;
  if (f.single_) {
    f.singleValues_ = readArray<float>(bytes, at);
    f.singleData_ = f.singleValues_.data();
    f.singleCount_ = static_cast<long long>(f.singleValues_.size());
  } else
    f.values_ = readArray<double>(bytes, at);
  f.inverseDiagonal_ = readArray<double>(bytes, at);
  f.perm_ = readArray<LO>(bytes, at);
  const std::vector<LO> maxRows = readArray<LO>(bytes, at);
  f.maxPanelRows_ = maxRows.empty() ? 0 : maxRows[0];
  return f;
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
