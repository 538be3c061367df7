#include "tribos/feti/DistributedCoarseSolve.hpp"

#include <algorithm>
#include <numeric>

#include "PackedFactor.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/feti/SparseCholesky.hpp"

namespace tribos::feti {

namespace {
/// The plan as rank 0 broadcasts it: n, then per subtree first, last, columnBegin, columnEnd,
/// updates, owner.
constexpr int kPlanFields = 6;

/// The split of the greedy sequence with the least reads on the busiest rank: subtrees
/// assigned largest first to the least loaded rank; rank 0 then solves the top as well, after
/// every subtree's forward substitution (so the top adds to the slowest rank's time). Empty
/// when none takes at least a quarter off the serial solve's reads.
std::vector<long long> choosePlan(const PackedFactor& factor, int ranks) {
  const auto splits = factor.greedySplits(std::min(4 * ranks, 256));
  long long bestCost = 0;
  std::vector<long long> plan;
  for (const PackedFactor::TreeSplit& split : splits) {
    const int count = static_cast<int>(split.first.size());
    if (count < 2) continue;
    std::vector<int> order(count), owner(count);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return split.values[a] > split.values[b]; });
    std::vector<long long> load(ranks, 0);
    for (int i : order) {
      const int r = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
      owner[i] = r;
      load[r] += split.values[i];
    }
    const long long top = split.totalValues - std::accumulate(split.values.begin(), split.values.end(), 0LL);
    const long long cost = *std::max_element(load.begin(), load.end()) + top;
    if (4 * cost > 3 * split.totalValues || (!plan.empty() && cost >= bestCost)) continue;
    bestCost = cost;
    plan.assign(1, factor.size());
    for (int i = 0; i < count; ++i) {
      const LO columnEnd = factor.columnEndOf(split.last[i]);
      plan.insert(plan.end(), {split.first[i], split.last[i], factor.firstColumnOf(split.first[i]), columnEnd,
                               factor.topUpdateCount(split.first[i], split.last[i], columnEnd), owner[i]});
    }
  }
  return plan;
}

void sendBytes(const std::vector<char>& bytes, int to, MPI_Comm comm) {
  const unsigned long long size = bytes.size();
  MPI_Send(&size, 1, MPI_UNSIGNED_LONG_LONG, to, 0, comm);
  constexpr size_t kChunk = size_t{1} << 30;  // MPI counts are int
  for (size_t at = 0; at < bytes.size(); at += kChunk)
    MPI_Send(bytes.data() + at, static_cast<int>(std::min(kChunk, bytes.size() - at)), MPI_BYTE, to, 1, comm);
}

std::vector<char> receiveBytes(int from, MPI_Comm comm) {
  unsigned long long size = 0;
  MPI_Recv(&size, 1, MPI_UNSIGNED_LONG_LONG, from, 0, comm, MPI_STATUS_IGNORE);
  std::vector<char> bytes(static_cast<size_t>(size));
  constexpr size_t kChunk = size_t{1} << 30;
  for (size_t at = 0; at < bytes.size(); at += kChunk)
    MPI_Recv(bytes.data() + at, static_cast<int>(std::min(kChunk, bytes.size() - at)), MPI_BYTE, from, 1, comm,
             MPI_STATUS_IGNORE);
  return bytes;
}

/// Displacements of an MPI_*v call from its counts.
std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> displs(counts.size(), 0);
  for (size_t r = 1; r < counts.size(); ++r) displs[r] = displs[r - 1] + counts[r - 1];
  return displs;
}
}  // namespace

DistributedCoarseSolve::~DistributedCoarseSolve() = default;

std::unique_ptr<DistributedCoarseSolve> DistributedCoarseSolve::create(MPI_Comm comm, const SparseCholesky* whole,
                                                                       long long fromValues) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) return nullptr;
  const PackedFactor* factor = rank == 0 && whole ? whole->packedFactor() : nullptr;
  std::vector<long long> plan;
  if (factor && factor->storedValues() >= fromValues) plan = choosePlan(*factor, size);
  long long length = static_cast<long long>(plan.size());
  MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, comm);
  if (length == 0) return nullptr;
  plan.resize(static_cast<size_t>(length));
  MPI_Bcast(plan.data(), static_cast<int>(length), MPI_LONG_LONG, 0, comm);

  std::unique_ptr<DistributedCoarseSolve> solve(new DistributedCoarseSolve());
  solve->comm_ = comm;
  solve->rank_ = rank;
  solve->size_ = size;
  solve->n_ = static_cast<LO>(plan[0]);
  for (size_t at = 1; at + kPlanFields <= plan.size(); at += kPlanFields) {
    Subtree s;
    s.first = static_cast<LO>(plan[at]);
    s.last = static_cast<LO>(plan[at + 1]);
    s.columnBegin = static_cast<LO>(plan[at + 2]);
    s.columnEnd = static_cast<LO>(plan[at + 3]);
    s.updates = plan[at + 4];
    s.owner = static_cast<int>(plan[at + 5]);
    solve->subtrees_.push_back(s);
  }
  solve->distributeParts(factor);
  solve->planBuffers();
  return solve;
}

void DistributedCoarseSolve::distributeParts(const PackedFactor* whole) {
  // Rank 0 keeps the whole factor (the top and its own subtrees); every other rank gets the
  // supernodes of its subtrees, in one message, once per factorisation.
  auto rangesOf = [&](int r) {
    std::vector<std::pair<LO, LO>> ranges;
    for (const Subtree& s : subtrees_)
      if (s.owner == r) ranges.emplace_back(s.first, s.last);
    return ranges;
  };
  if (rank_ == 0) {
    whole_ = whole;
    factor_ = whole;
    for (int r = 1; r < size_; ++r) sendBytes(whole->serialize(rangesOf(r)), r, comm_);
  } else {
    part_ = std::make_unique<PackedFactor>(PackedFactor::deserialize(receiveBytes(0, comm_)));
    factor_ = part_.get();
  }
  // This rank's subtrees in the numbering of the factor it reads.
  LO next = 0;
  for (int i = 0; i < numSubtrees(); ++i) {
    const Subtree& s = subtrees_[i];
    if (s.owner != rank_) continue;
    Mine m;
    m.subtree = i;
    m.first = rank_ == 0 ? s.first : next;
    m.last = m.first + (s.last - s.first);
    next = m.last;
    mine_.push_back(m);
  }
}

void DistributedCoarseSolve::planBuffers() {
  // Work per subtree of this rank (its panel work, then its top updates), then rank 0's panel
  // work for the top.
  size_t work = 0, updates = 0;
  for (Mine& m : mine_) {
    LO maxRows = 0;
    for (LO k = m.first; k < m.last; ++k) maxRows = std::max(maxRows, factor_->supernodes_[k].numPanelRows);
    m.panelWork = work;
    work += static_cast<size_t>(maxRows);
    m.updateOffset = updates;
    updates += static_cast<size_t>(subtrees_[m.subtree].updates);
  }
  topPanelWork_ = work;
  if (rank_ == 0) work += static_cast<size_t>(whole_->maxPanelRows_);
  work_.assign(work, 0.0);
  updates_.assign(updates, 0.0);

  updateCounts_.assign(size_, 0);
  columnCounts_.assign(size_, 0);
  for (const Subtree& s : subtrees_) {
    updateCounts_[s.owner] += static_cast<int>(s.updates);
    columnCounts_[s.owner] += s.columnEnd - s.columnBegin;
  }
  updateDispls_ = displacements(updateCounts_);
  columnDispls_ = displacements(columnCounts_);
  // Where each subtree's updates land in the gathered array: its owner's block, in the
  // owner's (ascending) order.
  std::vector<size_t> next(updateDispls_.begin(), updateDispls_.end());
  for (const Subtree& s : subtrees_) {
    gatheredOffset_.push_back(next[s.owner]);
    next[s.owner] += static_cast<size_t>(s.updates);
  }
  std::vector<size_t> nextColumn(columnDispls_.begin(), columnDispls_.end());
  for (const Subtree& s : subtrees_) {
    gatheredColumns_.push_back(nextColumn[s.owner]);
    nextColumn[s.owner] += static_cast<size_t>(s.columnEnd - s.columnBegin);
  }
  if (rank_ == 0) {
    // Rank 0's order of work after the gather: subtrees (their updates) and top runs, in
    // supernode order.
    LO k = 0;
    for (int i = 0; i < numSubtrees(); ++i) {
      if (subtrees_[i].first > k) segments_.push_back({-1, {k, subtrees_[i].first}});
      segments_.push_back({i, {subtrees_[i].first, subtrees_[i].last}});
      k = subtrees_[i].last;
    }
    if (k < whole_->numSupernodes()) segments_.push_back({-1, {k, whole_->numSupernodes()}});
  }
  if (rank_ == 0) gathered_.assign(static_cast<size_t>(updateDispls_.back() + updateCounts_.back()), 0.0);

  // The top: the columns outside every subtree (subtrees are disjoint column ranges).
  std::vector<std::pair<LO, LO>> ranges;
  for (const Subtree& s : subtrees_) ranges.emplace_back(s.columnBegin, s.columnEnd);
  std::sort(ranges.begin(), ranges.end());
  LO column = 0;
  for (const auto& [begin, end] : ranges) {
    if (begin > column) topColumns_.emplace_back(column, begin);
    column = end;
  }
  if (column < n_) topColumns_.emplace_back(column, n_);
  for (const auto& [begin, end] : topColumns_) topCount_ += end - begin;

  v_.assign(static_cast<size_t>(n_), 0.0);
  top_.assign(static_cast<size_t>(topCount_), 0.0);
  columns_.assign(static_cast<size_t>(columnCounts_[rank_]), 0.0);
  allColumns_.assign(static_cast<size_t>(n_ - topCount_), 0.0);

  // Reads per solve on this rank (both substitutions read the same values).
  auto valuesOf = [&](const PackedFactor& f, LO first, LO last) {
    long long count = 0;
    for (LO k = first; k < last; ++k) {
      const auto& s = f.supernodes_[k];
      count += static_cast<long long>(s.numColumns) * (s.numColumns + 1) / 2 +
               static_cast<long long>(s.numColumns) * s.numPanelRows;
    }
    return count;
  };
  for (const Mine& m : mine_) valuesOnThisRank_ += valuesOf(*factor_, m.first, m.last);
  if (rank_ == 0) {
    long long inSubtrees = 0;
    for (const Subtree& s : subtrees_) inSubtrees += valuesOf(*whole_, s.first, s.last);
    valuesOnThisRank_ += valuesOf(*whole_, 0, whole_->numSupernodes()) - inSubtrees;
  }
}

void DistributedCoarseSolve::solve(const double* b, double* x) const {
  const std::vector<LO>& perm = factor_->permutation();
  double* v = v_.data();
  for (LO k = 0; k < n_; ++k) v[k] = b[perm[k]];
  // Forward: this rank's subtrees (on its threads), their top updates kept.
  core::forEachSubdomain(static_cast<int>(mine_.size()), [&](int i) {
    const Mine& m = mine_[i];
    factor_->forward(m.first, m.last, v, work_.data() + m.panelWork, subtrees_[m.subtree].columnEnd,
                     updates_.data() + m.updateOffset);
  });
  MPI_Gatherv(updates_.data(), updateCounts_[rank_], MPI_DOUBLE, gathered_.data(), updateCounts_.data(),
              updateDispls_.data(), MPI_DOUBLE, 0, comm_);
  if (rank_ == 0) {
    // In supernode order: each subtree's updates of the top rows, in its order, and the top
    // supernodes; then the top backward. The subtractions of the serial solve in its order.
    double* panel = work_.data() + topPanelWork_;
    for (const auto& [i, range] : segments_) {
      if (i >= 0)
        whole_->applyTopUpdates(range.first, range.second, v, subtrees_[i].columnEnd, gathered_.data() + gatheredOffset_[i]);
      else
        whole_->forward(range.first, range.second, v, panel, n_, nullptr);
    }
    for (auto it = segments_.rbegin(); it != segments_.rend(); ++it)
      if (it->first < 0) whole_->backward(it->second.first, it->second.second, v, panel);
    double* out = top_.data();
    for (const auto& [begin, end] : topColumns_) out = std::copy(v + begin, v + end, out);
  }
  MPI_Bcast(top_.data(), static_cast<int>(topCount_), MPI_DOUBLE, 0, comm_);
  if (rank_ != 0) {
    const double* in = top_.data();
    for (const auto& [begin, end] : topColumns_) {
      std::copy(in, in + (end - begin), v + begin);
      in += end - begin;
    }
  }
  // Backward: this rank's subtrees, reading the top's solution; then every rank's columns.
  core::forEachSubdomain(static_cast<int>(mine_.size()), [&](int i) {
    const Mine& m = mine_[i];
    factor_->backward(m.first, m.last, v, work_.data() + m.panelWork);
  });
  double* out = columns_.data();
  for (const Mine& m : mine_) {
    const Subtree& s = subtrees_[m.subtree];
    out = std::copy(v + s.columnBegin, v + s.columnEnd, out);
  }
  MPI_Allgatherv(columns_.data(), columnCounts_[rank_], MPI_DOUBLE, allColumns_.data(), columnCounts_.data(),
                 columnDispls_.data(), MPI_DOUBLE, comm_);
  for (int i = 0; i < numSubtrees(); ++i) {
    const Subtree& s = subtrees_[i];
    const double* in = allColumns_.data() + gatheredColumns_[i];
    std::copy(in, in + (s.columnEnd - s.columnBegin), v + s.columnBegin);
  }
  for (LO k = 0; k < n_; ++k) x[perm[k]] = v[k];
}

}  // namespace tribos::feti
