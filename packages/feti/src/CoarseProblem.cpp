// The coarse problem of T-FETI (CoarseProblem.hpp): G G^T's pattern, assembly on rank 0,
// factor and precision, and its solves.
#include "CoarseProblem.hpp"

#include "CoarseSpace.hpp"

#include <algorithm>
#include <cmath>

namespace tribos::feti {

CoarseProblem::CoarseProblem(const CoarseRows& G, int numSubdomains, GO numRowsOfB, double gMax,
                             double subdomainBytesPerF, Teuchos::RCP<const Teuchos::Comm<int>> comm,
                             const TotalFetiSettings& settings, OperatorProfile& profile, std::vector<char> pinnedModes)
    : G_(G),
      numSubdomains_(numSubdomains),
      pinned_(std::move(pinnedModes)),
      numRowsOfB_(numRowsOfB),
      gMax_(gMax),
      subdomainBytesPerF_(subdomainBytesPerF),
      comm_(std::move(comm)),
      settings_(settings),
      profile_(profile) {
  buildPattern();
}

CoarseProblem::~CoarseProblem() = default;

void CoarseProblem::buildPattern() {
  // Block (s, t) of G G^T is present when a row of B touches both s and t. Every row is owned
  // by one rank, which holds all its entries g_{s,r} (buildCoarseRows): the pairs of its owned
  // rows, gathered from every rank, are the whole pattern. The gathered lists are as long as
  // the pattern itself (which every rank holds in any case), not as long as B.
  const CoarseRows& G = G_;
  std::vector<long long> pairs;  // s * numSubdomains + t, sorted and unique
  for (LO r = 0; r < G.numRows; ++r)
    for (LO e = G.rowStart[r]; e < G.rowStart[r + 1]; ++e)
      for (LO f = G.rowStart[r]; f < G.rowStart[r + 1]; ++f)
        pairs.push_back(static_cast<long long>(G.rowSubdomain[e]) * numSubdomains_ + G.rowSubdomain[f]);
  // Every diagonal block, also of a subdomain no row touches (all its modes pinned).
  if (comm_->getRank() == 0)
    for (int s = 0; s < numSubdomains_; ++s) pairs.push_back(static_cast<long long>(s) * numSubdomains_ + s);
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  if (comm_->getSize() > 1) pairs = allGather(*comm_, pairs);
  std::vector<std::vector<int>> neighbours(numSubdomains_);
  for (long long key : pairs) neighbours[key / numSubdomains_].push_back(static_cast<int>(key % numSubdomains_));
  pairs.clear();
  pairs.shrink_to_fit();
  blockStart_.assign(numSubdomains_ + 1, 0);  // first block of block row s
  neighbours_.clear();
  for (int s = 0; s < numSubdomains_; ++s) {
    auto& t = neighbours[s];
    std::sort(t.begin(), t.end());
    t.erase(std::unique(t.begin(), t.end()), t.end());
    blockStart_[s + 1] = blockStart_[s] + static_cast<LO>(t.size());
    neighbours_.insert(neighbours_.end(), t.begin(), t.end());
  }
}

LO CoarseProblem::blockOf(int s, int t) const {
  const auto first = neighbours_.begin() + blockStart_[s], last = neighbours_.begin() + blockStart_[s + 1];
  return blockStart_[s] + static_cast<LO>(std::lower_bound(first, last, t) - first);
}

std::vector<LO> CoarseProblem::touchedBlocks(const std::vector<char>* ownedRowMask, std::vector<LO>& slotOf) const {
  const CoarseRows& G = G_;
  slotOf.assign(static_cast<size_t>(blockStart_[numSubdomains_]), -1);
  for (LO r = 0; r < G.numRows; ++r) {
    if (ownedRowMask && !(*ownedRowMask)[r]) continue;
    for (LO e = G.rowStart[r]; e < G.rowStart[r + 1]; ++e)
      for (LO f = G.rowStart[r]; f < G.rowStart[r + 1]; ++f)
        if (G.rowSubdomain[e] <= G.rowSubdomain[f]) slotOf[blockOf(G.rowSubdomain[e], G.rowSubdomain[f])] = 0;
  }
  std::vector<LO> touched;
  for (LO k = 0; k < static_cast<LO>(slotOf.size()); ++k)
    if (slotOf[k] == 0) {
      slotOf[k] = static_cast<LO>(touched.size());
      touched.push_back(k);
    }
  return touched;
}

std::vector<double> CoarseProblem::sumOwnedRows(const std::vector<char>* ownedRowMask,
                                                const std::vector<TotalFeti::RowCombination>* combinations,
                                                const std::vector<LO>& slotOf, size_t numTouched) const {
  // Reproducible sums (core::SumBins): the rows of a block are owned by different ranks on
  // different layouts. |g_s[a] g_t[c]| <= gMax^2; at most one term per row of B. The slots
  // hold exact sums, so rank 0 may add the ranks' slots in any order. Each row's g_{s,r} are
  // decoded once (rowG) for all its pairs.
  const CoarseRows& G = G_;
  const core::SumBins bins(gMax_ * gMax_, static_cast<long long>(numRowsOfB_));
  constexpr size_t kBlock = kSlots * 36;
  std::vector<double> local(kBlock * numTouched, 0.0);
  std::vector<double> g;  // the row's g_{s,r}, 6 per entry
  auto decode = [&G](LO r, std::vector<double>& out) {
    const LO first = G.rowStart[r], entries = G.rowStart[r + 1] - first;
    out.resize(6 * static_cast<size_t>(entries));
    for (LO e = 0; e < entries; ++e) G.rowG(first + e, &out[6 * static_cast<size_t>(e)]);
  };
  for (LO r = 0; r < G.numRows; ++r) {
    if (ownedRowMask && !(*ownedRowMask)[r]) continue;
    decode(r, g);
    depositOuterProduct(g, &G.rowSubdomain[G.rowStart[r]], G.rowStart[r + 1] - G.rowStart[r], bins, slotOf, local);
  }
  if (!combinations) return local;
  // g = w_a g_a + w_b g_b over the same subdomains; |g| <= sqrt(2) gMax, so (g / sqrt 2)(g /
  // sqrt 2)^T, whose terms stay within the bins' bound, is deposited twice.
  std::vector<double> gb;
  for (const auto& c : *combinations) {
    if (!sameSubdomains(c.a, c.b)) continue;
    decode(c.a, g);
    decode(c.b, gb);
    for (size_t i = 0; i < g.size(); ++i) g[i] = (c.wa * g[i] + c.wb * gb[i]) / std::sqrt(2.0);
    for (int twice = 0; twice < 2; ++twice)
      depositOuterProduct(g, &G.rowSubdomain[G.rowStart[c.a]], G.rowStart[c.a + 1] - G.rowStart[c.a], bins, slotOf,
                          local);
  }
  return local;
}

void CoarseProblem::depositOuterProduct(const std::vector<double>& g, const int* subdomains, LO entries,
                                        const core::SumBins& bins, const std::vector<LO>& slotOf,
                                        std::vector<double>& local) const {
  constexpr size_t kBlock = kSlots * 36;
  for (LO e = 0; e < entries; ++e)
    for (LO f = 0; f < entries; ++f) {
      const int s = subdomains[e], t = subdomains[f];
      if (s > t) continue;
      double* block = &local[kBlock * static_cast<size_t>(slotOf[blockOf(s, t)])];
      const double* gs = &g[6 * static_cast<size_t>(e)];
      const double* gt = &g[6 * static_cast<size_t>(f)];
      for (int a = 0; a < 6; ++a)
        for (int c = 0; c < 6; ++c) bins.deposit(gs[a] * gt[c], block + kSlots * (a * 6 + c));
    }
}

bool CoarseProblem::sameSubdomains(LO a, LO b) const {
  const CoarseRows& G = G_;
  return std::equal(G.rowSubdomain.begin() + G.rowStart[a], G.rowSubdomain.begin() + G.rowStart[a + 1],
                    G.rowSubdomain.begin() + G.rowStart[b], G.rowSubdomain.begin() + G.rowStart[b + 1]);
}

void CoarseProblem::pinRows(fem::CsrMatrix& GGt) const {
  if (std::find(pinned_.begin(), pinned_.end(), 1) == pinned_.end()) return;
  double largest = 0.0;
  for (LO i = 0; i < GGt.n; ++i)
    if (!pinned_[i]) largest = std::max(largest, GGt.at(i, i));
  for (LO i = 0; i < GGt.n; ++i)
    if (pinned_[i])
      for (LO k = GGt.rowPtr[i]; k < GGt.rowPtr[i + 1]; ++k)
        if (GGt.colInd[k] == i) GGt.values[k] = largest > 0.0 ? largest : 1.0;
}

fem::CsrMatrix CoarseProblem::matrixFromSlots(const std::vector<double>& slots) const {
  // Each value combined from its slots straight into the matrix (no array of the blocks in
  // between); a block (s, t) below the diagonal is the upper block (t, s) read transposed.
  fem::CsrMatrix GGt;
  GGt.n = 6 * numSubdomains_;
  GGt.rowPtr.assign(GGt.n + 1, 0);
  GGt.colInd.reserve(slots.size() / kSlots);
  GGt.values.reserve(slots.size() / kSlots);
  for (int s = 0; s < numSubdomains_; ++s)
    for (int a = 0; a < 6; ++a) {
      for (LO k = blockStart_[s]; k < blockStart_[s + 1]; ++k) {
        const int t = neighbours_[k];
        const LO stored = s <= t ? k : blockOf(t, s);
        for (int c = 0; c < 6; ++c) {
          const int entry = s <= t ? a * 6 + c : c * 6 + a;
          GGt.colInd.push_back(6 * t + c);
          GGt.values.push_back(core::SumBins::combine(&slots[kSlots * (36 * static_cast<size_t>(stored) + entry)]));
        }
      }
      GGt.rowPtr[6 * s + a + 1] = static_cast<LO>(GGt.colInd.size());
    }
  pinRows(GGt);
  return GGt;
}

fem::CsrMatrix CoarseProblem::assemble(const std::vector<char>* ownedRowMask,
                                       const std::vector<TotalFeti::RowCombination>* combinations) const {
  // (G G^T)_{st} = sum over rows r touching both s and t of g_{s,r} g_{t,r}^T: 6x6 blocks
  // for subdomains that share a row of B (buildPattern; with a mask the same pattern, the
  // blocks of the rows left out stay zero). Each rank adds the products of its owned rows
  // into the blocks they touch, in row order; rank 0 adds every rank's blocks into the whole
  // pattern and builds the matrix, which only it factorises. No rank but 0 holds an array
  // the size of the pattern (at 4 000 subdomains 62 MB of slots and a 47 MB matrix, which
  // were the transient peak of every rank on 16 ranks, doc/measurements/scalability.md).
  // Only the blocks (s, t) with s <= t are summed: (t, s) is (s, t)^T, the same products
  // (g_t[c] g_s[a] = g_s[a] g_t[c] exactly) in the same exact slot sums, so the matrix reads
  // them transposed with the bits of summing them itself.
  std::vector<LO> slotOf;  // block -> its index among `touched`
  // A combination touches the blocks of its rows.
  std::vector<char> counted;
  if (combinations && ownedRowMask) {
    counted = *ownedRowMask;
    for (const auto& c : *combinations)
      if (sameSubdomains(c.a, c.b)) counted[c.a] = 1;
  }
  const std::vector<LO> touched = touchedBlocks(counted.empty() ? ownedRowMask : &counted, slotOf);
  std::vector<double> local = sumOwnedRows(ownedRowMask, combinations, slotOf, touched.size());
  std::vector<LO>().swap(slotOf);
  std::vector<double> slots;  // rank 0: the whole pattern's (upper blocks filled)
  addBlocksOnRoot(touched, local, slots);
  if (comm_->getRank() != 0) return fem::CsrMatrix{};
  return matrixFromSlots(slots);
}

void CoarseProblem::addBlocksOnRoot(const std::vector<LO>& blocks, std::vector<double>& values,
                                std::vector<double>& sum) const {
  // Rank 0 receives the ranks' blocks one rank at a time (its transient: one rank's share, not
  // all of them at once) and adds them to its own.
  constexpr size_t kBlock = kSlots * 36;
  auto add = [&](const LO* which, size_t count, const double* v) {
    for (size_t i = 0; i < count; ++i)
      for (size_t j = 0; j < kBlock; ++j) sum[kBlock * static_cast<size_t>(which[i]) + j] += v[kBlock * i + j];
  };
  const int rank = comm_->getRank(), size = comm_->getSize();
  if (rank == 0) {
    sum.assign(kBlock * static_cast<size_t>(blockStart_.back()), 0.0);
    add(blocks.data(), blocks.size(), values.data());
    std::vector<double>().swap(values);
  }
  if (size == 1) return;
  const MPI_Comm raw = rawComm(*comm_);
  if (rank != 0) {
    int count = static_cast<int>(blocks.size());
    MPI_Send(&count, 1, MPI_INT, 0, 0, raw);
    MPI_Send(blocks.data(), count, MPI_INT, 0, 1, raw);
    // Block by block bounds the int count of one message (kBlock doubles each).
    for (int i = 0; i < count; i += 1 << 20) {
      const int n = std::min(count - i, 1 << 20);
      MPI_Send(values.data() + kBlock * static_cast<size_t>(i), n * static_cast<int>(kBlock), MPI_DOUBLE, 0, 2, raw);
    }
    return;
  }
  std::vector<LO> theirs;
  std::vector<double> theirValues;
  for (int from = 1; from < size; ++from) {
    int count = 0;
    MPI_Recv(&count, 1, MPI_INT, from, 0, raw, MPI_STATUS_IGNORE);
    theirs.resize(static_cast<size_t>(count));
    theirValues.resize(kBlock * static_cast<size_t>(count));
    MPI_Recv(theirs.data(), count, MPI_INT, from, 1, raw, MPI_STATUS_IGNORE);
    for (int i = 0; i < count; i += 1 << 20) {
      const int n = std::min(count - i, 1 << 20);
      MPI_Recv(theirValues.data() + kBlock * static_cast<size_t>(i), n * static_cast<int>(kBlock), MPI_DOUBLE, from, 2,
               raw, MPI_STATUS_IGNORE);
    }
    add(theirs.data(), theirs.size(), theirValues.data());
  }
}

void CoarseProblem::factorize() {
  // G G^T is assembled on rank 0 from every rank's blocks and factorised there
  // (onRootThenBroadcast): its assembled matrix lives only as long as the factorisation.
  core::Stopwatch watch;
  fem::CsrMatrix GGt = assemble(nullptr);
  // Rounded to single (1), the gate's error, and two coarse solves' bytes over those of F's
  // subdomain solves (with the double factor).
  std::vector<double> single(3, 0.0);
  onRootThenBroadcast(
      *comm_,       single,
      [&] {
        auto factor = makeSparseCholesky(settings_.factorization, settings_.factorOptions);
        factor->setSubtreeSolve(true);  // solved on the main thread of rank 0
        try {
          factor->factorizeConsuming(std::move(GGt));
        } catch (const std::exception& e) {
          throw core::InputError(std::string("the constraints do not fix every rigid body mode of every subdomain "
                                             "(G G^T is singular: ") +
                                 e.what() + "); check Boundary/Dirichlet Node Sets and the contact surfaces");
        }
        factor_ = std::move(factor);
        profile_.coarseFactorNonzeros = factor_->factorNonzeros();
        profile_.coarseSubtrees = factor_->subtreeCount();
        single[2] = 2.0 * static_cast<double>(factor_->solveBytes()) / subdomainBytesPerF_;
        if (singlePays(single[2]) && !singleRejected_) {
          const auto [rounded, error] = roundToSingle();
          single[0] = rounded ? 1.0 : 0.0;
          single[1] = error;
        }
      },
      [](const std::string& message) { throw core::InputError(message); });
  profile_.coarseSingleError = single[1];
  profile_.coarseToFBytes = single[2];
  if (single[0] != 0.0 && !(single[1] <= settings_.singleCoarseGate)) {
    // Too inaccurate for this G G^T (kappa ~ 1e4 and more; NaN too): factorised again in
    // double, on every rank alike (the flags came from rank 0).
    singleRejected_ = true;
    factor_.reset();
    profile_.coarseFactorSeconds += watch.seconds();
    factorize();
    profile_.coarseSingleError = single[1];  // the error that sent it back
    return;
  }
  single_ = single[0] != 0.0;
  profile_.coarseSingle = single_;
  // Collective: the subtrees of its elimination tree to the ranks that will solve them.
  distributed_ = DistributedCoarseSolve::create(rawComm(*comm_), factor_.get(), settings_.distributedCoarseFromValues);
  profile_.coarseRankSubtrees = distributed_ ? distributed_->numLeaves() : 0;
  profile_.coarseSplitDepth = distributed_ ? distributed_->depth() : 0;
  profile_.coarseValuesPerSolve =
      distributed_ ? distributed_->valuesOnThisRank() : (factor_ ? factor_->factorNonzeros() : 0);
  factored_ = true;
  ++profile_.coarseFactorizations;
  profile_.coarseFactorSeconds += watch.seconds();
}

bool CoarseProblem::singlePays(double coarseToFBytes) const {
  // Rank 0, with the factor: "Auto" rounds where the two coarse solves of an A_rho product
  // read at least as many bytes as the subdomain solves of its F application
  // (subdomainBytesPerF_: the same on every rank layout, so that the choice, and with it
  // every bit of the run, is too): there the rounding saves a quarter or more of the
  // product's traffic.
  // Elsewhere the double factor keeps the exact projector's path: on symmetric scenes (the
  // paper's bricks) pairs of constraints reach their bounds in the same step only with it,
  // and any perturbation of P beyond ~1e-11 costs up to 20 % more F applications there
  // (doc/measurements/coarse_problem.md, "The coarse factor in single precision").
  switch (settings_.coarsePrecision) {
    case CoarsePrecision::Single: return true;
    case CoarsePrecision::Double: return false;
    case CoarsePrecision::Auto: break;
  }
  return coarseToFBytes >= 1.0;
}

std::pair<bool, double> CoarseProblem::roundToSingle() {
  // One solve of a fixed right-hand side before and after the rounding: the relative change
  // is about kappa(G G^T) 1e-7, the size of the perturbation the rounding makes to P.
  const LO n = factor_->size();
  std::vector<double> b(static_cast<size_t>(n)), exact(b.size()), rounded(b.size());
  std::uint32_t state = 12345u;
  for (double& v : b) {
    state = 1664525u * state + 1013904223u;  // a fixed sequence (LCG), spread over [-1, 1)
    v = static_cast<double>(state) / 2147483648.0 - 1.0;
  }
  factor_->solve(b.data(), exact.data());
  if (!factor_->roundToSingle()) return {false, 0.0};
  factor_->solve(b.data(), rounded.data());
  double difference = 0.0, norm = 0.0;
  for (size_t i = 0; i < b.size(); ++i) {
    difference += (rounded[i] - exact[i]) * (rounded[i] - exact[i]);
    norm += exact[i] * exact[i];
  }
  return {true, std::sqrt(difference / norm)};  // NaN or Inf: rejected by the gate
}

void CoarseProblem::solveExactly(std::vector<double>& a, const Product& product) {
  if (!factored_) factorize();
  if (!single_) {
    solve(a);
    return;
  }
  // Iterative refinement: x += C~^{-1} (b - G G^T x) contracts by about the gate's error per
  // step (at most 1e-3: 1e-16 in five steps); it stops when the correction reaches round-off
  // (1e-16 of x) or stops shrinking, and is accepted when the last correction was below 1e-10
  // of x. The same numbers on every rank (coarse vectors are replicated), so the same
  // decisions.
  const std::vector<double> b = a;
  solve(a);
  std::vector<double> r;
  double previous = std::numeric_limits<double>::infinity(), correction = 0.0, norm = 0.0;
  for (int k = 0; k < kMaxCoarseRefinements; ++k) {
    product(a, r);
    for (size_t i = 0; i < r.size(); ++i) r[i] = b[i] - r[i];
    solve(r);
    ++profile_.coarseRefinementSteps;
    correction = 0.0;
    norm = 0.0;
    for (size_t i = 0; i < r.size(); ++i) {
      a[i] += r[i];
      correction += r[i] * r[i];
      norm += a[i] * a[i];
    }
    if (correction <= 1e-32 * norm || correction >= previous) break;
    previous = correction;
  }
  if (correction <= 1e-20 * norm) return;
  // Not refined to round-off (not seen): the double factor after all, for every later
  // coarse solve too; the summary keeps the gate's error (coarse_single false with an error:
  // sent back to double).
  const double error = profile_.coarseSingleError;
  singleRejected_ = true;
  release();
  a = b;
  solve(a);
  profile_.coarseSingleError = error;
}

void CoarseProblem::release() {
  distributed_.reset();  // it reads factor_ on rank 0
  factor_.reset();
  factored_ = false;
}

void CoarseProblem::solve(std::vector<double>& a) {
  core::Stopwatch watch;
  ++profile_.coarseSolves;
  if (!factored_) factorize();  // released (releaseCoarseFactor): the same factor again
  // Over the ranks when the factor is large (the bits of the serial solve), else on rank 0
  // alone, then broadcast: with every rank solving, the R ranks of a node streamed R copies
  // of the factor at once (16 ranks at 4 000 subdomains: doc/measurements/scalability.md).
  rhs_.assign(a.begin(), a.end());
  if (distributed_)
    distributed_->solve(rhs_.data(), a.data());
  else
    onRootThenBroadcast(
      *comm_,         a, [&] { factor_->solve(rhs_.data(), a.data()); },
        [](const std::string& message) { throw std::runtime_error(message); });
  profile_.coarseSolveSeconds += watch.seconds();
}


void onRootThenBroadcast(const Teuchos::Comm<int>& comm, std::vector<double>& v, const std::function<void()>& work,
                         const std::function<void(const std::string&)>& fail) {
  if (comm.getSize() == 1) {
    work();  // its exceptions as they are
    return;
  }
  // Every rank reaches both broadcasts, also when rank 0's work failed: then every rank
  // throws, with rank 0's message (a rank left waiting in a collective would hang the job).
  int failed = 0;
  std::string message;
  if (comm.getRank() == 0) {
    try {
      work();
    } catch (const std::exception& e) {
      failed = 1;
      message = e.what();
    }
  }
  Teuchos::broadcast(comm, 0, 1, &failed);
  if (failed) {
    int length = static_cast<int>(message.size());
    Teuchos::broadcast(comm, 0, 1, &length);
    message.resize(static_cast<size_t>(length));
    if (length > 0) Teuchos::broadcast(comm, 0, length, message.data());
    fail(message);
    throw std::logic_error("tribos::feti::onRootThenBroadcast: `fail` must throw");
  }
  if (!v.empty()) Teuchos::broadcast(comm, 0, static_cast<int>(v.size()), v.data());
}

}  // namespace tribos::feti
