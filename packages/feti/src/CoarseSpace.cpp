// The coarse space (CoarseSpace.hpp): G = R^T B^T in the compact form of CoarseRows, G x and
// G^T a (paper Sec. 4.2), and the projector P with its coarse solves.
#include "CoarseSpace.hpp"

#include "CoarseProblem.hpp"

namespace tribos::feti {

void CoarseRows::geometric(const CoarseTerm& t, double* g) const {
  const size_t slot = t.code >> 2;
  const int d = static_cast<int>(t.code & 3u);
  if (d == 3) {
    std::copy(&full[6 * slot], &full[6 * slot] + 6, g);
    return;
  }
  geometricRow(d, &coords[3 * slot], g);
  for (int j = 0; j < 6; ++j) g[j] *= t.c;
}

void CoarseRows::rowG(LO rowOrderEntry, double* g) const {
  double geo[6];
  geometric(term[rowEntry[rowOrderEntry]], geo);
  transposedProduct(M(rowSubdomain[rowOrderEntry]), geo, g);
}

namespace {
using EntryData = Tpetra::MultiVector<Scalar, LO, GO>;

/// Builds the CoarseTerm of rows of blocks from their `data` (6 numbers, entrySource):
/// p~ of the node of a one-term row, g' of the others. One coordinate slot per (subdomain,
/// local node) and one full slot per (subdomain, row) of the rank (G x and G^T a share them).
class CoarseTermBuilder {
 public:
  explicit CoarseTermBuilder(CoarseRows& G) : G_(G) {}
  /// The term of row i of block b (subdomain s); index left to the caller.
  CoarseTerm operator()(int s, const SubdomainBlock& b, LO i, const double* data) {
    const LO first = b.rowPtr[i];
    if (b.rowPtr[i + 1] - first == 1) {
      const LO dof = b.dof[first];
      const auto key = std::make_pair(s, dof / 3);
      auto it = coordSlot_.find(key);
      if (it == coordSlot_.end()) {
        it = coordSlot_.emplace(key, static_cast<std::uint32_t>(G_.coords.size() / 3)).first;
        G_.coords.insert(G_.coords.end(), data, data + 3);
      }
      return {b.value[first], code(it->second, dof % 3), 0};
    }
    const auto key = std::make_pair(s, b.rows[i]);
    auto it = fullSlot_.find(key);
    if (it == fullSlot_.end()) {
      it = fullSlot_.emplace(key, static_cast<std::uint32_t>(G_.full.size() / 6)).first;
      G_.full.insert(G_.full.end(), data, data + 6);
    }
    return {0.0, code(it->second, 3), 0};
  }

 private:
  static std::uint32_t code(std::uint32_t slot, int d) {
    TEUCHOS_TEST_FOR_EXCEPTION(slot >= (1u << 30), std::length_error, "tribos::feti: too many coarse slots on a rank");
    return 4 * slot + static_cast<std::uint32_t>(d);
  }
  CoarseRows& G_;
  std::map<std::pair<int, LO>, std::uint32_t> coordSlot_;
  std::map<std::pair<int, GO>, std::uint32_t> fullSlot_;
};

/// One entry (owned row, subdomain s) of G: the row (owned index), its row in B_s, its kind
/// (component d of a one-term row, 3 for several terms).
struct RowEntry {
  LO row;
  int subdomain;
  LO blockRow;
  int kind;
};

using Locals = std::vector<std::unique_ptr<OwnedSubdomain>>;

/// The frames (centre, scale, M_s: kFrame numbers) of the owned subdomains, by their owner
/// (which has R_s), zeros elsewhere; -0.0 made +0.0 so that the sum with the other ranks'
/// zeros keeps every bit.
std::vector<double> ownedFrames(const Locals& local, const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                                int numSubdomains) {
  std::vector<double> frames(kFrame * static_cast<size_t>(numSubdomains), 0.0);
  core::forEachSubdomain(static_cast<int>(local.size()), [&](int i) {
    const OwnedSubdomain& L = *local[i];
    double* frame = &frames[kFrame * static_cast<size_t>(L.subdomain)];
    subdomainFrame(mesh, decomposition.subdomains[L.subdomain].nodes, L.system.R, frame);
    for (int j = 0; j < kFrame; ++j) frame[j] += 0.0;
  });
  return frames;
}

/// The data of each entry of the owned subdomains, by their owner (the only rank that has
/// their nodes, stack::keepRankData): p~ of the node of a one-term row (3 numbers), g' of the
/// others (6), the terms in B's order.
void fillEntryData(const Locals& local, const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                   const std::vector<double>& frames, const std::vector<LO>& firstSource, EntryData& dataSource) {
  auto data = dataSource.getLocalViewHost(Tpetra::Access::OverwriteAll);
  core::forEachSubdomain(static_cast<int>(local.size()), [&](int i) {
    const OwnedSubdomain& L = *local[i];
    const SubdomainBlock& b = *L.block;
    const double* frame = &frames[kFrame * static_cast<size_t>(L.subdomain)];
    const auto& nodes = decomposition.subdomains[L.subdomain].nodes;
    for (LO r = 0; r < L.m(); ++r) {
      double g[6] = {}, v[6], p[3];
      if (b.rowPtr[r + 1] - b.rowPtr[r] == 1) {
        scaledPoint(frame, mesh.coords[nodes[b.dof[b.rowPtr[r]] / 3]], g);
      } else {
        for (LO k = b.rowPtr[r]; k < b.rowPtr[r + 1]; ++k) {
          scaledPoint(frame, mesh.coords[nodes[b.dof[k] / 3]], p);
          geometricRow(b.dof[k] % 3, p, v);
          for (int j = 0; j < 6; ++j) g[j] += b.value[k] * v[j];
        }
      }
      for (int j = 0; j < 6; ++j) data(firstSource[i] + r, j) = g[j];
    }
  });
}

/// The entries of the owned rows [firstRow, firstRow + numRows) of every block, ordered by
/// row, then subdomain (ascending: the order in which G G^T has always summed them).
std::vector<RowEntry> ownedRowEntries(const ConstraintMatrix& B, GO firstRow, LO numRows, int numSubdomains) {
  std::vector<RowEntry> entries;
  for (int s = 0; s < numSubdomains; ++s) {
    const auto& rows = B.blocks[s].rows;
    const auto lo = std::lower_bound(rows.begin(), rows.end(), firstRow);
    for (auto it = lo; it != rows.end() && *it < firstRow + numRows; ++it)
      entries.push_back({static_cast<LO>(*it - firstRow), s, static_cast<LO>(it - rows.begin()),
                         termKind(B.blocks[s], static_cast<LO>(it - rows.begin()))});
  }
  std::stable_sort(entries.begin(), entries.end(), [](const RowEntry& a, const RowEntry& b) { return a.row < b.row; });
  return entries;
}

template <class View>
void dataOf(const View& view, LO e, double* out) {
  for (int j = 0; j < 6; ++j) out[j] = view(e, j);
}

/// The row view (rowStart, rowSubdomain, rowEntry) and the stored order of the entries: by
/// chunk, then subdomain, then kind, then row (entries are in row order: a stable sort by
/// (chunk, subdomain, kind) keeps the rows ascending within a kind), with the runs and their
/// kind groups. `data`: each entry's 6 numbers (fillEntryData, imported to the row's owner).
void storeRowTerms(CoarseRows& G, const std::vector<RowEntry>& entries, const ConstraintMatrix& B,
                   const EntryData& data, CoarseTermBuilder& termOf) {
  G.rowStart.assign(G.numRows + 1, 0);
  G.rowSubdomain.resize(entries.size());
  for (size_t e = 0; e < entries.size(); ++e) {
    ++G.rowStart[entries[e].row + 1];
    G.rowSubdomain[e] = entries[e].subdomain;
  }
  for (LO r = 0; r < G.numRows; ++r) G.rowStart[r + 1] += G.rowStart[r];
  std::vector<LO> order(entries.size());
  for (size_t e = 0; e < order.size(); ++e) order[e] = static_cast<LO>(e);
  std::stable_sort(order.begin(), order.end(), [&](LO a, LO b) {
    const LO ca = entries[a].row / kRowChunk, cb = entries[b].row / kRowChunk;
    if (ca != cb) return ca < cb;
    if (entries[a].subdomain != entries[b].subdomain) return entries[a].subdomain < entries[b].subdomain;
    return entries[a].kind < entries[b].kind;
  });
  G.rowEntry.resize(entries.size());
  G.term.resize(entries.size());
  const auto view = data.getLocalViewHost(Tpetra::Access::ReadOnly);
  double numbers[6];
  const LO numChunks = (G.numRows + kRowChunk - 1) / kRowChunk;
  G.chunkRunStart.assign(numChunks + 1, 0);  // runs per chunk, then their prefix sums
  for (size_t k = 0; k < order.size(); ++k) {
    const RowEntry& entry = entries[order[k]];
    G.rowEntry[order[k]] = static_cast<LO>(k);
    dataOf(view, order[k], numbers);
    G.term[k] = termOf(entry.subdomain, B.blocks[entry.subdomain], entry.blockRow, numbers);
    G.term[k].index = entry.row;
    const LO chunk = entry.row / kRowChunk;
    if (k == 0 || chunk != entries[order[k - 1]].row / kRowChunk || entry.subdomain != entries[order[k - 1]].subdomain) {
      G.runStart.push_back(static_cast<LO>(k));
      G.runSubdomain.push_back(entry.subdomain);
      ++G.chunkRunStart[chunk + 1];
    }
  }
  G.runStart.push_back(static_cast<LO>(order.size()));
  for (LO c = 0; c < numChunks; ++c) G.chunkRunStart[c + 1] += G.chunkRunStart[c];
  const size_t numRuns = G.runSubdomain.size();
  G.runGroupStart.assign(4 * numRuns + 1, static_cast<LO>(order.size()));
  for (size_t j = 0; j < numRuns; ++j)
    for (int kind = 0; kind < 4; ++kind) {
      LO e = G.runStart[j];
      while (e < G.runStart[j + 1] && entries[order[e]].kind < kind) ++e;
      G.runGroupStart[4 * j + kind] = e;
    }
  G.rowSum.assign(G.numRows, 0.0);
}

/// G x's terms of the owned subdomains: their own blocks, every row (the same slots where
/// shared); by kind (component d = 0, 1, 2 of one-term rows, then the full entries), in
/// rowOrder within a kind. `data`: fillEntryData's.
void storeOwnedTerms(CoarseRows& G, const Locals& local, const std::vector<LO>& firstSource,
                     const EntryData& data, CoarseTermBuilder& termOf) {
  const auto view = data.getLocalViewHost(Tpetra::Access::ReadOnly);
  double numbers[6];
  G.ownedTerm.clear();
  G.ownedStart.clear();
  for (size_t i = 0; i < local.size(); ++i) {
    const OwnedSubdomain& L = *local[i];
    for (int kind = 0; kind < 4; ++kind) {
      G.ownedStart.push_back(static_cast<LO>(G.ownedTerm.size()));
      for (LO r : L.rowOrder) {
        if (termKind(*L.block, r) != kind) continue;
        dataOf(view, firstSource[i] + r, numbers);
        G.ownedTerm.push_back(termOf(L.subdomain, *L.block, r, numbers));
        G.ownedTerm.back().index = L.overlapIndex[r];
      }
    }
    G.ownedStart.push_back(static_cast<LO>(G.ownedTerm.size()));
    G.ownedStart.push_back(L.subdomain);
  }
  G.ownedTerm.shrink_to_fit();
}
}  // namespace

CoarseSpace::CoarseSpace(SubdomainSet& subdomains, const mesh::Mesh& mesh, const mesh::Decomposition& decomposition,
                         OperatorProfile& profile)
    : subdomains_(subdomains), profile_(profile) {
  // Entry (s, r) = row r of B in block s, global id r * numSubdomains + s: the same id on every
  // rank without any rank knowing the sizes of the blocks it does not own. Source: the entries
  // of the owned subdomains; target: the entries of the owned rows (the rank has those rows of
  // every block, feti::keepRankRows). One import of 6 numbers per entry (the data of its
  // CoarseTerm), also applyBlockwise's entry-wise sums (several ranks); M_s travels by one
  // all-reduce of kFrame numbers per subdomain.
  const auto& comm = subdomains_.comm();
  const ConstraintMatrix& B = subdomains_.constraints();
  const Locals& owned = subdomains_.all();
  const int numSubdomains = subdomains_.numSubdomains();
  const int rank = comm->getRank();
  const GO S = numSubdomains;
  std::vector<GO> ids;
  for (const auto& L : owned)
    for (GO row : L->block->rows) ids.push_back(row * S + L->subdomain);
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto source = Teuchos::rcp(new DualMap(invalid, Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm));
  std::vector<LO> firstSource(subdomains_.numOwned() + 1, 0);  // first source entry of each owned subdomain
  for (int i = 0; i < subdomains_.numOwned(); ++i) firstSource[i + 1] = firstSource[i] + owned[i]->m();
  std::vector<double> frames = ownedFrames(owned, mesh, decomposition, numSubdomains);
  EntryData dataSource(source, 6);
  fillEntryData(owned, mesh, decomposition, frames, firstSource, dataSource);
  if (comm->getSize() > 1) {
    std::vector<double> mine = frames;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, static_cast<int>(frames.size()), mine.data(), frames.data());
  }

  auto G = std::make_unique<CoarseRows>();
  G->firstRow = B.firstRowOfRank[rank];
  G->numRows = static_cast<LO>(B.firstRowOfRank[rank + 1] - G->firstRow);
  const std::vector<RowEntry> entries = ownedRowEntries(B, G->firstRow, G->numRows, numSubdomains);
  ids.resize(entries.size());
  for (size_t e = 0; e < entries.size(); ++e) ids[e] = (G->firstRow + entries[e].row) * S + entries[e].subdomain;
  auto target = Teuchos::rcp(new DualMap(invalid, Teuchos::ArrayView<const GO>(ids.data(), ids.size()), 0, comm));
  auto entryImport = Teuchos::rcp(new Tpetra::Import<LO, GO>(source, target));
  EntryData dataTarget(target, 6);
  dataTarget.doImport(dataSource, *entryImport, Tpetra::INSERT);
  if (!subdomains_.overlapIsOwned())  // applyBlockwise's entry-wise sums (several ranks)
    subdomains_.sumEntriesAtRowOwners(entryImport, Teuchos::rcp(new DualVector(source)),
                                      Teuchos::rcp(new DualVector(target)), firstSource, &G->rowStart);

  CoarseTermBuilder termOf(*G);
  storeRowTerms(*G, entries, B, dataTarget, termOf);
  storeOwnedTerms(*G, owned, firstSource, dataSource, termOf);
  G->basis.resize(36 * static_cast<size_t>(S));
  for (GO s = 0; s < S; ++s)
    std::copy(frames.data() + kFrame * s + 4, frames.data() + kFrame * (s + 1), G->basis.data() + 36 * s);
  G->coords.shrink_to_fit();
  G->full.shrink_to_fit();

  // The bound of every term of G G^T (core::SumBins): the same on every layout.
  double gMax = 0.0, g[6];
  for (size_t e = 0; e < entries.size(); ++e) {
    G->rowG(static_cast<LO>(e), g);
    for (double v : g) gMax = std::max(gMax, std::abs(v));
  }
  gMax_ = core::globalMax(comm.get(), gMax);
  profile_.gEntries = static_cast<long long>(G->rowSubdomain.size());
  profile_.gRows = G->numRows;
  G_ = std::move(G);
  local_.assign(numCoarse(), 0.0);
  vector_.assign(numCoarse(), 0.0);
}


namespace {
/// The two coordinates of p~ that component D's rotation rows read: (e_k x p~)_D involves
/// p~_k' for k' != D only.
template <int D>
constexpr int kFirstOther = D == 0 ? 1 : 0;
template <int D>
constexpr int kSecondOther = D == 2 ? 1 : 2;

/// sum[0..2] = sums of w, w p~_a, w p~_b (a, b: kFirstOther, kSecondOther) over one-term
/// rows of component D, w = c x_r; two interleaved partial sums (shorter dependency chains),
/// added at the end: a fixed order for a fixed list of terms.
template <int D>
void sumComponent(const CoarseTerm* __restrict t, const CoarseTerm* end, const double* __restrict x,
                  const double* __restrict coords, double* sum) {
  constexpr int a = kFirstOther<D>, b = kSecondOther<D>;
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, u0 = 0.0, u1 = 0.0, u2 = 0.0;
  for (; t + 1 < end; t += 2) {
    const double w = t[0].c * x[t[0].index], v = t[1].c * x[t[1].index];
    const double* p = coords + 3 * static_cast<size_t>(t[0].code >> 2);
    const double* q = coords + 3 * static_cast<size_t>(t[1].code >> 2);
    s0 += w;
    s1 += w * p[a];
    s2 += w * p[b];
    u0 += v;
    u1 += v * q[a];
    u2 += v * q[b];
  }
  if (t < end) {
    const double w = t->c * x[t->index];
    const double* p = coords + 3 * static_cast<size_t>(t->code >> 2);
    s0 += w;
    s1 += w * p[a];
    s2 += w * p[b];
  }
  sum[0] = s0 + u0;
  sum[1] = s1 + u1;
  sum[2] = s2 + u2;
}

// (G x)_s of the i-th owned subdomain into gx[6 s, 6 s + 6) (applyGOwnedSubdomains).
void sumOwnedSubdomain(const CoarseRows& G, int i, const double* xOverlap, double* gx) {
  const CoarseTerm* t = G.ownedTerm.data();
  const LO* start = &G.ownedStart[6 * static_cast<size_t>(i)];
  const int subdomain = start[5];
  double s0[3], s1[3], s2[3], full[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  sumComponent<0>(t + start[0], t + start[1], xOverlap, G.coords.data(), s0);
  sumComponent<1>(t + start[1], t + start[2], xOverlap, G.coords.data(), s1);
  sumComponent<2>(t + start[2], t + start[3], xOverlap, G.coords.data(), s2);
  for (LO k = start[3]; k < start[4]; ++k) {
    const double xr = xOverlap[t[k].index];
    const double* g = &G.full[6 * static_cast<size_t>(t[k].code >> 2)];
    for (int j = 0; j < 6; ++j) full[j] += g[j] * xr;
  }
  // sum of w [e_d; (e_0 x p~)_d, (e_1 x p~)_d, (e_2 x p~)_d] (geometricRow): rotation 0
  // reads z~ of d = 1 and y~ of d = 2, rotation 1 z~ of d = 0 and x~ of d = 2, rotation 2
  // y~ of d = 0 and x~ of d = 1.
  const double geo[6] = {s0[0] + full[0],
                         s1[0] + full[1],
                         s2[0] + full[2],
                         (s2[2] - s1[2]) + full[3],
                         (s0[2] - s2[1]) + full[4],
                         (s1[1] - s0[1]) + full[5]};
  transposedProduct(G.M(subdomain), geo, gx + 6 * subdomain);
}
}  // namespace

void CoarseSpace::applyGOwnedSubdomains(const double* xOverlap, double* gx) const {
  // (G x)_s = M_s^T sum over the rows r of B_s of g'_{s,r} x_r, by the owner of s (threads
  // over the owned subdomains), in a fixed order of its terms (CoarseRows::ownedTerm): the same sum in
  // the same order on every layout. The other entries stay zero, so the all-reduce adds one
  // term and zeros (exact). A one-term row of component d adds w = c x_r times
  // [e_d; (e_k x p~)_d]: the sums of w and w p~ per component, combined at the end.
  std::fill(gx, gx + numCoarse(), 0.0);
  const CoarseRows& G = *G_;
  // A subdomain's sum is about a microsecond of work: the threads take up to kGxSubdomains
  // of them per task (at least 8 tasks per thread), so that the shared counter of the dynamic
  // schedule (a cache line that moves between the cores at every grab) is not touched 500
  // times per G x. Each subdomain writes only its own 6 entries: the same bits for any grouping.
  const int numOwned = subdomains_.numOwned();
  const int group = std::max(1, std::min(kGxSubdomains, numOwned / (8 * core::numThreads())));
  core::forEachSubdomain((numOwned + group - 1) / group, [&](int task) {
    const int end = std::min(numOwned, (task + 1) * group);
    for (int i = task * group; i < end; ++i) sumOwnedSubdomain(G, i, xOverlap, gx);
  });
}


void CoarseSpace::reduce(std::vector<double>& local, double* gx) const {
  const auto& comm = *subdomains_.comm();
  if (comm.getSize() == 1)
    std::copy(local.begin(), local.end(), gx);
  else
    Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, numCoarse(), local.data(), gx);
}

void CoarseSpace::applyG(const DualVector& x, std::vector<double>& gx) const {
  applyGOwnedSubdomains(subdomains_.overlapValues(x), local_.data());
  gx.resize(numCoarse());
  reduce(local_, gx.data());
}

namespace detail {
// rowSum[r] += c (b0 + ba p~_a + bb p~_b) over the one-term entries [first, end) of component
// D of one run (distinct rows: no chain between consecutive updates).
template <int D>
void addComponent(const CoarseRows& G, LO first, LO end, double b0, double ba, double bb,
                  double* __restrict rowSum) {
  constexpr int a = kFirstOther<D>, b = kSecondOther<D>;
  const CoarseTerm* __restrict t = G.term.data();
  const double* __restrict coords = G.coords.data();
  for (LO e = first; e < end; ++e) {
    const double* p = coords + 3 * static_cast<size_t>(t[e].code >> 2);
    rowSum[t[e].index] += t[e].c * (b0 + (ba * p[a] + bb * p[b]));
  }
}

// y_r = x_r - sum over the entries of row r of g_{s,r} . a_s, for the owned rows (y may be
// x: each row reads its x_r before writing y_r).
void subtractGt(const CoarseRows& G, const double* a, const double* x, double* y) {
  core::forEachSubdomain(G.numChunks(), [&](int c) {
    const LO first = c * kRowChunk, end = std::min<LO>(G.numRows, first + kRowChunk);
    double* __restrict rowSum = G.rowSum.data();
    std::fill(rowSum + first, rowSum + end, 0.0);
    // Runs in ascending subdomain order: each row adds its terms in ascending subdomain
    // order (the rows of one run are distinct: no chain between consecutive updates).
    for (int run = G.chunkRunStart[c]; run < G.chunkRunStart[c + 1]; ++run) {
      // g_{s,r} . a_s = g'_{s,r} . b with b = M_s a_s: c (b[d] + (b_rot x p~)_d) for a
      // one-term row of component d.
      const int s = G.runSubdomain[run];
      const double* M = G.M(s);
      const double* as = a + 6 * s;
      double b[6];
      for (int i = 0; i < 6; ++i) {
        double sum = 0.0;
        for (int j = 0; j < 6; ++j) sum += M[6 * i + j] * as[j];
        b[i] = sum;
      }
      // (b_rot x p~)_d = sum_k b[3 + k] (e_k x p~)_d (geometricRow): per component the
      // coefficients of its two coordinates.
      const LO* group = &G.runGroupStart[4 * static_cast<size_t>(run)];
      addComponent<0>(G, group[0], group[1], b[0], -b[5], b[4], rowSum);
      addComponent<1>(G, group[1], group[2], b[1], b[5], -b[3], rowSum);
      addComponent<2>(G, group[2], group[3], b[2], -b[4], b[3], rowSum);
      for (LO e = group[3]; e < group[4]; ++e) {
        const CoarseTerm& t = G.term[e];
        const double* g = &G.full[6 * static_cast<size_t>(t.code >> 2)];
        rowSum[t.index] += (g[0] * b[0] + g[1] * b[1]) + (g[2] * b[2] + g[3] * b[3]) + (g[4] * b[4] + g[5] * b[5]);
      }
    }
    for (LO r = first; r < end; ++r) y[r] = x[r] - rowSum[r];
  });
}
}  // namespace detail

void CoarseSpace::applyGt(const std::vector<double>& a, DualVector& y) const {
  // y = G^T a = 0 - (-G^T a) (set-up only: lambda_Im)
  std::vector<double> minusA(a.size());
  for (size_t i = 0; i < a.size(); ++i) minusA[i] = -a[i];
  y.putScalar(0.0);
  double* yd = readWrite(y);
  subtractGt(*G_, minusA.data(), yd, yd);
}


CoarseSpace::~CoarseSpace() = default;

void CoarseSpace::setUpProblem(double subdomainBytesPerF, const TotalFetiSettings& settings,
                               std::vector<char> pinnedModes) {
  problem_ = std::make_unique<CoarseProblem>(*G_, subdomains_.numSubdomains(), subdomains_.constraints().numRows,
                                             gMax_, subdomainBytesPerF, subdomains_.comm(), settings, profile_,
                                             std::move(pinnedModes));
  problem_->factorize();
}

void CoarseSpace::solve(std::vector<double>& a) const { problem_->solve(a); }

void CoarseSpace::solveExactly(std::vector<double>& a) const {
  // Products G G^T x as G (G^T x) for the refinement of a single-precision factor's solves.
  problem_->solveExactly(a, [this](const std::vector<double>& x, std::vector<double>& y) {
    DualVector v(subdomains_.dualMap());
    applyGt(x, v);
    applyG(v, y);
  });
}

void CoarseSpace::release() const {
  if (!keep_) problem_->release();
}

void CoarseSpace::project(const DualVector& x, DualVector& y, CoarseCoordinates* ofX) const {
  // y = x - G^T (G G^T)^{-1} G x on the owned rows: x on the overlap rows (several ranks),
  // one all-reduce of length l, no allocation.
  ++profile_.projections;
  core::Stopwatch watch;
  applyGOwnedSubdomains(subdomains_.overlapValues(x), local_.data());
  profile_.gSeconds += watch.seconds();
  watch.restart();
  reduce(local_, vector_.data());
  profile_.coarseReduceSeconds += watch.seconds();
  if (ofX) ofX->gx.assign(vector_.begin(), vector_.end());
  solve(vector_);
  if (ofX) ofX->a.assign(vector_.begin(), vector_.end());
  watch.restart();
  const double* xd = readOnly(x);
  double* yd = &x == &y ? readWrite(y) : y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
  if (&x == &y) xd = yd;
  subtractGt(*G_, vector_.data(), xd, yd);
  profile_.gSeconds += watch.seconds();
}

void CoarseSpace::projectExactly(const DualVector& x, DualVector& y) const {
  if (!problem_->single()) {
    project(x, y);  // exact already
    return;
  }
  std::vector<double> a;
  applyG(x, a);
  solveExactly(a);
  DualVector gta(subdomains_.dualMap());
  applyGt(a, gta);
  y.update(1.0, x, -1.0, gta, 0.0);
}

void CoarseSpace::coordinates(const DualVector& x, std::vector<double>& gx, std::vector<double>& a) const {
  ++profile_.coarseCoordinates;
  applyG(x, gx);
  a = gx;
  solve(a);
}


}  // namespace tribos::feti
