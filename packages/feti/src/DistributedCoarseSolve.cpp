#include "tribos/feti/DistributedCoarseSolve.hpp"

#include <algorithm>
#include <map>
#include <numeric>

#include "PackedFactor.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/feti/SparseCholesky.hpp"

namespace tribos::feti {

namespace {
/// The fields of a task as rank 0 broadcasts them.
constexpr int kTaskFields = 9;
/// What one split level costs in latency (a gather and a broadcast over its ranks, ~30 µs on
/// one node), in values of the factor one core reads in that time (two passes of 8 bytes at
/// ~11 GB/s): the planner splits a subtree only where that pays.
constexpr double kLatencyValues = 20000.0;

/// Rank 0's choice of the task tree: for the whole factor and then for every subtree given
/// several ranks, among the greedy splits of its elimination tree (PackedFactor::greedyStates)
/// the one with the shortest estimated critical path, in values read: its top, plus the
/// slowest part, plus kLatencyValues; a part given one rank reads all its values, one given
/// several is planned the same way (memoised). Parts get ranks in proportion to their values
/// (each at least one) or, when there are as many parts as ranks or more, are dealt to the
/// least loaded rank, largest first.
class Planner {
 public:
  Planner(const PackedFactor& factor, int ranks) : factor_(factor), tree_(factor.supernodeTree()), ranks_(ranks) {}

  /// The tasks, or none when the factor is not a tree or no split pays (critical path above
  /// 3/4 of the serial solve's reads).
  std::vector<DistributedCoarseSolve::Task> plan() {
    std::vector<DistributedCoarseSolve::Task> tasks;
    if (tree_.empty() || ranks_ < 2) return tasks;
    const Decision whole = decide(tree_.roots, ranks_);
    if (whole.parts.empty() || 4.0 * whole.time > 3.0 * static_cast<double>(valuesOf(tree_.roots))) return tasks;
    emit(tasks, 0, factor_.numSupernodes(), 0, ranks_, -1, whole);
    return tasks;
  }

 private:
  struct Part {
    LO root;
    int rankOffset, rankCount;
  };
  struct Decision {
    double time = 0.0;
    std::vector<Part> parts;  ///< empty: not split
  };

  long long valuesOf(const std::vector<LO>& roots) const {
    long long sum = 0;
    for (LO root : roots) sum += tree_.subtreeValues[root];
    return sum;
  }

  const Decision& decided(LO root, int ranks) {
    const auto key = std::make_pair(root, ranks);
    auto it = memo_.find(key);
    if (it == memo_.end()) it = memo_.emplace(key, decide({root}, ranks)).first;
    return it->second;
  }

  Decision decide(const std::vector<LO>& start, int ranks) {
    const long long total = valuesOf(start);
    Decision best;
    best.time = static_cast<double>(total);
    if (ranks < 2) return best;
    for (const auto& state : PackedFactor::greedyStates(tree_, start, 2 * ranks, 4 * ranks + 32)) {
      const int count = static_cast<int>(state.size());
      if (count < 2) continue;
      Decision candidate;
      double slowest = 0.0;
      if (count >= ranks) {
        std::vector<int> order(count);
        std::iota(order.begin(), order.end(), 0);
        std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
          return tree_.subtreeValues[state[a]] > tree_.subtreeValues[state[b]];
        });
        std::vector<long long> load(ranks, 0);
        candidate.parts.resize(count);
        for (int i : order) {
          const int r = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
          load[r] += tree_.subtreeValues[state[i]];
          candidate.parts[i] = {state[i], r, 1};
        }
        slowest = static_cast<double>(*std::max_element(load.begin(), load.end()));
      } else {
        // One rank each, then one more at a time to the part with the most values per rank.
        std::vector<int> share(count, 1);
        for (int extra = ranks - count; extra > 0; --extra) {
          int most = 0;
          for (int i = 1; i < count; ++i)
            if (tree_.subtreeValues[state[i]] * share[most] > tree_.subtreeValues[state[most]] * share[i]) most = i;
          ++share[most];
        }
        int offset = 0;
        for (int i = 0; i < count; ++i) {
          candidate.parts.push_back({state[i], offset, share[i]});
          offset += share[i];
          const double time =
              share[i] > 1 ? decided(state[i], share[i]).time : static_cast<double>(tree_.subtreeValues[state[i]]);
          slowest = std::max(slowest, time);
        }
      }
      candidate.time = static_cast<double>(total - valuesOf(state)) + slowest + kLatencyValues;
      if (candidate.time < best.time) best = std::move(candidate);
    }
    return best;
  }

  void emit(std::vector<DistributedCoarseSolve::Task>& tasks, LO first, LO last, int rankBegin, int rankEnd,
            int parent, const Decision& decision) {
    DistributedCoarseSolve::Task task;
    task.first = first;
    task.last = last;
    task.columnBegin = factor_.firstColumnOf(first);
    task.columnEnd = factor_.columnEndOf(last);
    task.rankBegin = rankBegin;
    task.rankEnd = rankEnd;
    task.parent = parent;
    task.split = !decision.parts.empty();
    task.updates = factor_.topUpdateCount(first, last, task.columnEnd);
    const int id = static_cast<int>(tasks.size());
    tasks.push_back(task);
    for (const Part& part : decision.parts) {
      const Decision unsplit;
      const Decision& sub = part.rankCount > 1 ? decided(part.root, part.rankCount) : unsplit;
      emit(tasks, tree_.firstDescendant[part.root], part.root + 1, rankBegin + part.rankOffset,
           rankBegin + part.rankOffset + part.rankCount, id, sub);
    }
  }

  const PackedFactor& factor_;
  const PackedFactor::SupernodeTree tree_;
  const int ranks_;
  std::map<std::pair<LO, int>, Decision> memo_;
};

/// The columns of a task outside its parts (a split's top; a leaf's own columns).
std::vector<std::pair<LO, LO>> columnsOutsideParts(const std::vector<DistributedCoarseSolve::Task>& tasks, int t) {
  std::vector<std::pair<LO, LO>> gaps;
  LO column = tasks[t].columnBegin;
  for (size_t c = 0; c < tasks.size(); ++c) {
    if (tasks[c].parent != t) continue;  // parts are emitted in supernode (and column) order
    if (tasks[c].columnBegin > column) gaps.emplace_back(column, tasks[c].columnBegin);
    column = tasks[c].columnEnd;
  }
  if (column < tasks[t].columnEnd) gaps.emplace_back(column, tasks[t].columnEnd);
  return gaps;
}

void sendBytes(const void* data, size_t size, int to, int tag, MPI_Comm comm) {
  const unsigned long long length = size;
  MPI_Send(&length, 1, MPI_UNSIGNED_LONG_LONG, to, tag, comm);
  constexpr size_t kChunk = size_t{1} << 30;  // MPI counts are int
  const char* bytes = static_cast<const char*>(data);
  for (size_t at = 0; at < size; at += kChunk)
    MPI_Send(bytes + at, static_cast<int>(std::min(kChunk, size - at)), MPI_BYTE, to, tag, comm);
}

std::vector<char> receiveBytes(int from, int tag, MPI_Comm comm) {
  unsigned long long length = 0;
  MPI_Recv(&length, 1, MPI_UNSIGNED_LONG_LONG, from, tag, comm, MPI_STATUS_IGNORE);
  std::vector<char> bytes(static_cast<size_t>(length));
  constexpr size_t kChunk = size_t{1} << 30;
  for (size_t at = 0; at < bytes.size(); at += kChunk)
    MPI_Recv(bytes.data() + at, static_cast<int>(std::min(kChunk, bytes.size() - at)), MPI_BYTE, from, tag, comm,
             MPI_STATUS_IGNORE);
  return bytes;
}

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> displs(counts.size(), 0);
  for (size_t r = 1; r < counts.size(); ++r) displs[r] = displs[r - 1] + counts[r - 1];
  return displs;
}
}  // namespace

DistributedCoarseSolve::~DistributedCoarseSolve() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized) return;
  for (Split& s : splits_)
    if (s.comm != MPI_COMM_NULL) MPI_Comm_free(&s.comm);
}

std::unique_ptr<DistributedCoarseSolve> DistributedCoarseSolve::create(MPI_Comm comm, const SparseCholesky* whole,
                                                                       long long fromValues) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (size == 1) return nullptr;
  const PackedFactor* factor = rank == 0 && whole ? whole->packedFactor() : nullptr;
  std::vector<long long> plan;
  if (factor && factor->storedValues() >= fromValues) {
    const std::vector<Task> tasks = Planner(*factor, size).plan();
    if (!tasks.empty()) plan.push_back(factor->size());
    for (const Task& t : tasks)
      plan.insert(plan.end(), {t.first, t.last, t.columnBegin, t.columnEnd, t.rankBegin, t.rankEnd, t.parent,
                               t.split ? 1 : 0, t.updates});
  }
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
  for (size_t at = 1; at + kTaskFields <= plan.size(); at += kTaskFields) {
    Task t;
    t.first = static_cast<LO>(plan[at]);
    t.last = static_cast<LO>(plan[at + 1]);
    t.columnBegin = static_cast<LO>(plan[at + 2]);
    t.columnEnd = static_cast<LO>(plan[at + 3]);
    t.rankBegin = static_cast<int>(plan[at + 4]);
    t.rankEnd = static_cast<int>(plan[at + 5]);
    t.parent = static_cast<int>(plan[at + 6]);
    t.split = plan[at + 7] != 0;
    t.updates = plan[at + 8];
    solve->tasks_.push_back(t);
  }
  solve->buildSplits();
  solve->receiveParts(factor);
  solve->planBuffers();
  return solve;
}

void DistributedCoarseSolve::buildSplits() {
  // The chain of splits that hold this rank, from the whole factor down, each with a
  // communicator over its ranks (split from its parent's: every rank of the parent calls
  // MPI_Comm_split once for it).
  MPI_Comm current = MPI_COMM_NULL;
  MPI_Comm_dup(comm_, &current);
  int t = 0;
  for (;;) {
    Split s;
    s.task = t;
    s.comm = current;
    s.leader = rank_ == tasks_[t].rankBegin;
    for (int c = 0; c < static_cast<int>(tasks_.size()); ++c)
      if (tasks_[c].parent == t) s.parts.push_back(c);
    LO k = tasks_[t].first;
    for (int i = 0; i < static_cast<int>(s.parts.size()); ++i) {
      const Task& part = tasks_[s.parts[i]];
      if (part.first > k) s.segments.push_back({-1, k, part.first, 0});
      s.segments.push_back({i, part.first, part.last, 0});
      k = part.last;
    }
    if (k < tasks_[t].last) s.segments.push_back({-1, k, tasks_[t].last, 0});
    int next = -1;
    for (int c : s.parts)
      if (tasks_[c].split && rank_ >= tasks_[c].rankBegin && rank_ < tasks_[c].rankEnd) next = c;
    splits_.push_back(std::move(s));
    MPI_Comm child = MPI_COMM_NULL;
    MPI_Comm_split(current, next >= 0 ? next : MPI_UNDEFINED, rank_, &child);
    if (next < 0) break;
    current = child;
    t = next;
  }
  for (int c = 0; c < static_cast<int>(tasks_.size()); ++c)
    if (!tasks_[c].split && tasks_[c].rankBegin == rank_) leaves_.push_back(c);
}

LO DistributedCoarseSolve::local(LO k) const {
  if (rank_ == 0) return k;
  const auto it = std::upper_bound(partRanges_.begin(), partRanges_.end(), std::make_pair(k, LO{0}),
                                   [](const auto& a, const auto& b) { return a.first < b.first; });
  const size_t i = static_cast<size_t>(it - partRanges_.begin()) - 1;
  return partStart_[i] + (k - partRanges_[i].first);
}

void DistributedCoarseSolve::receiveParts(const PackedFactor* whole) {
  // What each rank reads: its leaves and the top runs of the splits it leads; the leader of a
  // split also needs the rows of its parts' updates. Rank 0 keeps the whole factor.
  auto rangesOf = [&](int r) {
    std::vector<std::pair<LO, LO>> ranges;
    for (size_t t = 0; t < tasks_.size(); ++t) {
      if (tasks_[t].rankBegin != r) continue;
      if (!tasks_[t].split) {
        ranges.emplace_back(tasks_[t].first, tasks_[t].last);
        continue;
      }
      LO k = tasks_[t].first;
      for (size_t c = 0; c < tasks_.size(); ++c) {
        if (tasks_[c].parent != static_cast<int>(t)) continue;
        if (tasks_[c].first > k) ranges.emplace_back(k, tasks_[c].first);
        k = tasks_[c].last;
      }
      if (k < tasks_[t].last) ranges.emplace_back(k, tasks_[t].last);
    }
    std::sort(ranges.begin(), ranges.end());
    return ranges;
  };
  // The rows of the updates of every part of every split led by r, in task order.
  auto partRowsOf = [&](int r) {
    std::vector<LO> rows;
    for (size_t t = 0; t < tasks_.size(); ++t) {
      const Task& part = tasks_[t];
      if (part.parent < 0 || tasks_[part.parent].rankBegin != r) continue;
      const std::vector<LO> mine = whole->topUpdateRows(part.first, part.last, part.columnEnd);
      rows.insert(rows.end(), mine.begin(), mine.end());
    }
    return rows;
  };
  std::vector<LO> rows;
  if (rank_ == 0) {
    whole_ = whole;
    factor_ = whole;
    for (int r = 1; r < size_; ++r) {
      const std::vector<char> bytes = whole->serialize(rangesOf(r));
      sendBytes(bytes.data(), bytes.size(), r, 0, comm_);
      const std::vector<LO> partRows = partRowsOf(r);
      sendBytes(partRows.data(), sizeof(LO) * partRows.size(), r, 1, comm_);
    }
    rows = partRowsOf(0);
  } else {
    part_ = std::make_unique<PackedFactor>(PackedFactor::deserialize(receiveBytes(0, 0, comm_)));
    factor_ = part_.get();
    partRanges_ = rangesOf(rank_);
    LO start = 0;
    for (const auto& [first, last] : partRanges_) {
      partStart_.push_back(start);
      start += last - first;
    }
    const std::vector<char> bytes = receiveBytes(0, 1, comm_);
    rows.resize(bytes.size() / sizeof(LO));
    std::copy(bytes.begin(), bytes.end(), reinterpret_cast<char*>(rows.data()));
  }
  // Split the rows over the parts of the splits this rank leads (task order, as sent).
  size_t at = 0;
  std::map<int, std::vector<LO>> rowsOfPart;
  for (size_t t = 0; t < tasks_.size(); ++t) {
    const Task& part = tasks_[t];
    if (part.parent < 0 || tasks_[part.parent].rankBegin != rank_) continue;
    rowsOfPart[static_cast<int>(t)].assign(rows.begin() + static_cast<long>(at),
                                           rows.begin() + static_cast<long>(at + static_cast<size_t>(part.updates)));
    at += static_cast<size_t>(part.updates);
  }
  for (Split& s : splits_)
    if (s.leader)
      for (int c : s.parts) s.partRows.push_back(std::move(rowsOfPart[c]));
}

void DistributedCoarseSolve::planBuffers() {
  const LO maxRows = factor_->maxPanelRows_;
  work_.assign(static_cast<size_t>(maxRows) * (leaves_.size() + 1), 0.0);
  output_.assign(tasks_.size(), {});
  auto valuesOf = [&](LO first, LO last) {
    long long count = 0;
    for (LO k = local(first), end = local(first) + (last - first); k < end; ++k) {
      const auto& s = factor_->supernodes_[k];
      count += static_cast<long long>(s.numColumns) * (s.numColumns + 1) / 2 +
               static_cast<long long>(s.numColumns) * s.numPanelRows;
    }
    return count;
  };
  for (int leaf : leaves_) {
    output_[leaf].assign(static_cast<size_t>(tasks_[leaf].updates), 0.0);
    valuesOnThisRank_ += valuesOf(tasks_[leaf].first, tasks_[leaf].last);
  }
  for (Split& s : splits_) {
    const Task& task = tasks_[s.task];
    int commSize = 0, commRank = 0;
    MPI_Comm_size(s.comm, &commSize);
    MPI_Comm_rank(s.comm, &commRank);
    // Gather: each part's updates come from its first rank, in part order.
    s.counts.assign(commSize, 0);
    for (int c : s.parts) s.counts[tasks_[c].rankBegin - task.rankBegin] += static_cast<int>(tasks_[c].updates);
    s.displs = displacements(s.counts);
    s.send.assign(static_cast<size_t>(s.counts[commRank]), 0.0);
    std::vector<size_t> next(s.displs.begin(), s.displs.end());
    for (int c : s.parts) {
      s.partOffset.push_back(next[tasks_[c].rankBegin - task.rankBegin]);
      next[tasks_[c].rankBegin - task.rankBegin] += static_cast<size_t>(tasks_[c].updates);
    }
    s.topColumns = columnsOutsideParts(tasks_, s.task);
    for (const auto& [begin, end] : s.topColumns) s.topCount += end - begin;
    s.top.assign(static_cast<size_t>(s.topCount), 0.0);
    if (!s.leader) continue;
    s.gathered.assign(static_cast<size_t>(s.displs.back() + s.counts.back()), 0.0);
    output_[s.task].assign(static_cast<size_t>(task.updates), 0.0);
    for (auto& segment : s.segments)
      if (segment.part < 0) {
        const LO first = local(segment.first);
        segment.updates = factor_->topUpdateCount(first, first + (segment.last - segment.first), task.columnEnd);
        valuesOnThisRank_ += valuesOf(segment.first, segment.last);
      }
  }
  // The final all-gather: each column from the rank that solved it (a leaf's first rank, a
  // split's leader for its top), every rank's ranges in task order.
  ownedColumns_.assign(size_, {});
  columnCounts_.assign(size_, 0);
  for (int t = 0; t < static_cast<int>(tasks_.size()); ++t) {
    const auto ranges = columnsOutsideParts(tasks_, t);
    for (const auto& range : ranges) {
      ownedColumns_[tasks_[t].rankBegin].push_back(range);
      columnCounts_[tasks_[t].rankBegin] += range.second - range.first;
    }
  }
  columnDispls_ = displacements(columnCounts_);
  v_.assign(static_cast<size_t>(n_), 0.0);
  columns_.assign(static_cast<size_t>(columnCounts_[rank_]), 0.0);
  allColumns_.assign(static_cast<size_t>(columnDispls_.back() + columnCounts_.back()), 0.0);
}

int DistributedCoarseSolve::numLeaves() const {
  return static_cast<int>(std::count_if(tasks_.begin(), tasks_.end(), [](const Task& t) { return !t.split; }));
}

int DistributedCoarseSolve::depth() const {
  int deepest = 0;
  for (const Task& t : tasks_) {
    int d = 0;
    for (int p = t.parent; p >= 0; p = tasks_[p].parent) ++d;
    deepest = std::max(deepest, d);
  }
  return deepest;
}

void DistributedCoarseSolve::forwardLeaves(double* v) const {
  // The leaves (on this rank's threads), their updates of rows above them kept.
  const size_t maxRows = static_cast<size_t>(factor_->maxPanelRows_);
  core::forEachSubdomain(static_cast<int>(leaves_.size()), [&](int i) {
    const Task& t = tasks_[leaves_[i]];
    const LO first = local(t.first);
    factor_->forward(first, first + (t.last - t.first), v, work_.data() + maxRows * i, t.columnEnd,
                     outputOf(leaves_[i]).data());
  });
}

void DistributedCoarseSolve::forwardSplits(double* v) const {
  // From the deepest up: gather the parts' updates to the leader, which subtracts those
  // inside the split and solves its top, in supernode order.
  double* splitWork = work_.data() + static_cast<size_t>(factor_->maxPanelRows_) * leaves_.size();
  for (auto s = splits_.rbegin(); s != splits_.rend(); ++s) {
    const Task& task = tasks_[s->task];
    double* send = s->send.data();
    for (int c : s->parts)
      if (tasks_[c].rankBegin == rank_) send = std::copy(outputOf(c).begin(), outputOf(c).end(), send);
    int commRank = 0;
    MPI_Comm_rank(s->comm, &commRank);
    MPI_Gatherv(s->send.data(), s->counts[commRank], MPI_DOUBLE, s->gathered.data(), s->counts.data(),
                s->displs.data(), MPI_DOUBLE, 0, s->comm);
    if (!s->leader) continue;
    double* out = outputOf(s->task).data();
    for (const auto& segment : s->segments) {
      if (segment.part >= 0) {
        const double* in = s->gathered.data() + s->partOffset[segment.part];
        const std::vector<LO>& rows = s->partRows[segment.part];
        for (size_t i = 0; i < rows.size(); ++i) {
          if (rows[i] < task.columnEnd)
            v[rows[i]] -= in[i];
          else
            *out++ = in[i];
        }
      } else {
        const LO first = local(segment.first);
        factor_->forward(first, first + (segment.last - segment.first), v, splitWork, task.columnEnd, out);
        out += segment.updates;
      }
    }
  }
}

void DistributedCoarseSolve::backward(double* v) const {
  // From the whole factor down, each leader solves its top and broadcasts it; then the leaves.
  const size_t maxRows = static_cast<size_t>(factor_->maxPanelRows_);
  double* splitWork = work_.data() + maxRows * leaves_.size();
  for (const Split& s : splits_) {
    if (s.leader) {
      for (auto segment = s.segments.rbegin(); segment != s.segments.rend(); ++segment)
        if (segment->part < 0) {
          const LO first = local(segment->first);
          factor_->backward(first, first + (segment->last - segment->first), v, splitWork);
        }
      double* out = s.top.data();
      for (const auto& [begin, end] : s.topColumns) out = std::copy(v + begin, v + end, out);
    }
    MPI_Bcast(s.top.data(), static_cast<int>(s.topCount), MPI_DOUBLE, 0, s.comm);
    if (!s.leader) {
      const double* in = s.top.data();
      for (const auto& [begin, end] : s.topColumns) {
        std::copy(in, in + (end - begin), v + begin);
        in += end - begin;
      }
    }
  }
  core::forEachSubdomain(static_cast<int>(leaves_.size()), [&](int i) {
    const Task& t = tasks_[leaves_[i]];
    const LO first = local(t.first);
    factor_->backward(first, first + (t.last - t.first), v, work_.data() + maxRows * i);
  });
}

void DistributedCoarseSolve::shareColumns(double* v) const {
  // Every rank's solved columns to every rank.
  double* out = columns_.data();
  for (const auto& [begin, end] : ownedColumns_[rank_]) out = std::copy(v + begin, v + end, out);
  MPI_Allgatherv(columns_.data(), columnCounts_[rank_], MPI_DOUBLE, allColumns_.data(), columnCounts_.data(),
                 columnDispls_.data(), MPI_DOUBLE, comm_);
  const double* in = allColumns_.data();
  for (int r = 0; r < size_; ++r)
    for (const auto& [begin, end] : ownedColumns_[r]) {
      std::copy(in, in + (end - begin), v + begin);
      in += end - begin;
    }
}

void DistributedCoarseSolve::solve(const double* b, double* x) const {
  const std::vector<LO>& perm = factor_->permutation();
  double* v = v_.data();
  for (LO k = 0; k < n_; ++k) v[k] = b[perm[k]];
  forwardLeaves(v);
  forwardSplits(v);
  backward(v);
  shareColumns(v);
  for (LO k = 0; k < n_; ++k) x[perm[k]] = v[k];
}

}  // namespace tribos::feti
