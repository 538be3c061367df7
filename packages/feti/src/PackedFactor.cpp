#include "PackedFactor.hpp"

#include <cstring>

namespace tribos::feti {

namespace {
// The kernels are compiled for AVX-512, AVX2 and the baseline, picked once at load time
// (GCC function multiversioning): the default build targets any x86-64, and these loops are
// most of the cost of an F application. Every thread of a run uses the same version; the
// versions may differ from each other in the last bit (fused multiply-adds).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define TRIBOS_KERNEL __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define TRIBOS_KERNEL
#endif

// sum a_i b_i in eight interleaved partial sums, added pairwise: a fixed order that the
// compiler may vectorise (a single running sum it may not reorder).
template <class V>
inline __attribute__((always_inline)) double dot(const V* __restrict a, const double* __restrict b, LO n) {
  double s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  LO i = 0;
  for (; i + 8 <= n; i += 8)
    for (int k = 0; k < 8; ++k) s[k] += static_cast<double>(a[i + k]) * b[i + k];
  for (; i < n; ++i) s[0] += static_cast<double>(a[i]) * b[i];
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

// y -= alpha x
template <class V>
inline __attribute__((always_inline)) void subtractScaled(double* __restrict y, const V* __restrict x, double alpha,
                                                          LO n) {
  for (LO i = 0; i < n; ++i) y[i] -= alpha * static_cast<double>(x[i]);
}
}  // namespace

template <class V>
inline __attribute__((always_inline)) void PackedFactor::forwardWith(const V* values, LO first, LO last, double* x,
                                                                     double* panelWork, LO columnEnd,
                                                                     double* topUpdates) const {
  // L y = x, supernode by supernode: the diagonal triangle by columns, then the panel as
  // t = panel * x_d (one axpy per column into the contiguous t), scattered: x_rows -= t.
  const LO* rows = rows_.data();
  double* __restrict t = panelWork;
  for (LO k = first; k < last; ++k) {
    const Supernode& s = supernodes_[k];
    double* __restrict xd = x + s.firstColumn;
    const double* __restrict invDiagonal = inverseDiagonal_.data() + s.firstColumn;
    const V* triangle = values + s.triangleOffset;
    const LO nc = s.numColumns, nr = s.numPanelRows;
    for (LO j = 0; j < nc; ++j) {
      const double xj = xd[j] * invDiagonal[j];
      xd[j] = xj;
      subtractScaled(xd + j + 1, triangle, xj, nc - j - 1);
      triangle += nc - j - 1;
    }
    if (nr == 0) continue;
    const V* __restrict panel = values + s.panelOffset;
    for (LO r = 0; r < nr; ++r) t[r] = 0.0;
    for (LO j = 0; j < nc; ++j, panel += nr) subtractScaled(t, panel, -xd[j], nr);
    const LO* __restrict panelRows = rows + s.rowOffset;
    // Rows ascend: those of the subtree first, then its top rows (none when columnEnd = n).
    LO inside = nr;
    if (panelRows[nr - 1] >= columnEnd)
      inside = static_cast<LO>(std::lower_bound(panelRows, panelRows + nr, columnEnd) - panelRows);
    for (LO r = 0; r < inside; ++r) x[panelRows[r]] -= t[r];
    for (LO r = inside; r < nr; ++r) *topUpdates++ = t[r];
  }
}

template <class V>
inline __attribute__((always_inline)) void PackedFactor::backwardWith(const V* values, LO first, LO last, double* x,
                                                                      double* panelWork) const {
  // L^T y = x from the last supernode: gather the (solved) panel rows into t, one dot
  // product per panel column, then the transposed diagonal triangle.
  const LO* rows = rows_.data();
  double* __restrict t = panelWork;
  for (LO k = last - 1; k >= first; --k) {
    const Supernode& s = supernodes_[k];
    double* __restrict xd = x + s.firstColumn;
    const LO nc = s.numColumns, nr = s.numPanelRows;
    if (nr > 0) {
      const LO* __restrict panelRows = rows + s.rowOffset;
      for (LO r = 0; r < nr; ++r) t[r] = x[panelRows[r]];
      const V* __restrict panel = values + s.panelOffset;
      for (LO j = 0; j < nc; ++j, panel += nr) xd[j] -= dot(panel, t, nr);
    }
    const double* __restrict invDiagonal = inverseDiagonal_.data() + s.firstColumn;
    const V* triangle = values + s.triangleOffset;
    for (LO j = nc - 1; j >= 0; --j) {
      // Column j's strict lower part starts after the (nc - 1 - k) entries of columns k < j.
      const V* column = triangle + static_cast<long long>(j) * (nc - 1) - static_cast<long long>(j) * (j - 1) / 2;
      xd[j] = (xd[j] - dot(column, xd + j + 1, nc - j - 1)) * invDiagonal[j];
    }
  }
}

// Each kernel version (TRIBOS_KERNEL) holds both value types; the factor's decides.
TRIBOS_KERNEL void PackedFactor::forward(LO first, LO last, double* x, double* panelWork, LO columnEnd,
                                        double* topUpdates) const {
  if (single_)
    forwardWith(singleData_, first, last, x, panelWork, columnEnd, topUpdates);
  else
    forwardWith(valueData(), first, last, x, panelWork, columnEnd, topUpdates);
}

TRIBOS_KERNEL void PackedFactor::backward(LO first, LO last, double* x, double* panelWork) const {
  if (single_)
    backwardWith(singleData_, first, last, x, panelWork);
  else
    backwardWith(valueData(), first, last, x, panelWork);
}

void PackedFactor::applyTopUpdates(LO first, LO last, double* x, LO columnEnd, const double* topUpdates) const {
  // The subtractions that forward() left out, in its order: the same operations on every
  // entry of x as the serial forward substitution.
  for (LO k = first; k < last; ++k) {
    const Supernode& s = supernodes_[k];
    const LO nr = s.numPanelRows;
    if (nr == 0) continue;
    const LO* panelRows = rows_.data() + s.rowOffset;
    if (panelRows[nr - 1] < columnEnd) continue;
    const LO inside = static_cast<LO>(std::lower_bound(panelRows, panelRows + nr, columnEnd) - panelRows);
    for (LO r = inside; r < nr; ++r) x[panelRows[r]] -= *topUpdates++;
  }
}

void PackedFactor::solvePermuted(double* v, double* work) const {
  if (subtrees_) {
    solveSubtrees(v);
    return;
  }
  forward(0, numSupernodes(), v, work, size(), nullptr);
  backward(0, numSupernodes(), v, work);
}

void PackedFactor::solve(const double* b, double* x, double* work) const {
  const LO n = size();
  for (LO k = 0; k < n; ++k) work[k] = b[perm_[k]];
  solvePermuted(work, work + n);
  for (LO k = 0; k < n; ++k) x[perm_[k]] = work[k];
}

void PackedFactor::roundToSingle() {
  if (single_) return;
  const long long count = valueCount();
  if (adopted_ && resize_ && count > 0) {
    // In place, so that the doubles and the floats are never held side by side (the coarse
    // factor is the largest array at thousands of subdomains): float i goes to bytes
    // [4i, 4i + 4), which only doubles already read occupy (memcpy: no aliasing of the two
    // types). Then the array shrinks to the floats (realloc; in place for large blocks).
    char* bytes = reinterpret_cast<char*>(adopted_.get());
    for (long long i = 0; i < count; ++i) {
      double v;
      std::memcpy(&v, bytes + 8 * i, sizeof v);
      const float f = static_cast<float>(v);
      std::memcpy(bytes + 4 * i, &f, sizeof f);
    }
    void (*release)(void*) = adopted_.get_deleter();
    void* shrunk = resize_(adopted_.get(), static_cast<size_t>(count) * sizeof(float));
    void* kept = shrunk ? shrunk : adopted_.get();
    adopted_.release();
    singleAdopted_ = std::unique_ptr<float, void (*)(void*)>(static_cast<float*>(kept), release);
    singleData_ = singleAdopted_.get();
  } else {
    const double* values = valueData();
    singleValues_.resize(static_cast<size_t>(count));
    for (size_t i = 0; i < singleValues_.size(); ++i) singleValues_[i] = static_cast<float>(values[i]);
    adopted_.reset();
    std::vector<double>().swap(values_);
    singleData_ = singleValues_.data();
  }
  adoptedCount_ = 0;
  singleCount_ = count;
  single_ = true;
}

PackedFactor::Ranges PackedFactor::reach(const std::vector<LO>& columns) const {
  const LO ns = numSupernodes(), n = size();
  std::vector<LO> supernodeOfColumn(n);
  for (LO k = 0; k < ns; ++k)
    for (LO j = 0; j < supernodes_[k].numColumns; ++j) supernodeOfColumn[supernodes_[k].firstColumn + j] = k;
  std::vector<char> visited(ns, 0);
  for (LO c : columns) visited[supernodeOfColumn[c]] = 1;
  // The parent of a supernode holds its first panel row and comes after it; ascending, every
  // visited supernode has passed the mark on to its parent before the parent is looked at.
  for (LO k = 0; k < ns; ++k) {
    const Supernode& s = supernodes_[k];
    if (s.numPanelRows == 0) continue;
    const LO parent = supernodeOfColumn[rows_[s.rowOffset]];
    if (parent <= k) return {{0, ns}};  // not an elimination tree in this order: visit all
    if (visited[k]) visited[parent] = 1;
  }
  Ranges ranges;
  for (LO k = 0; k < ns; ++k) {
    if (!visited[k]) continue;
    if (!ranges.empty() && ranges.back().second == k)
      ++ranges.back().second;
    else
      ranges.push_back({k, k + 1});
  }
  return ranges;
}

void PackedFactor::solvePermutedOnReach(double* v, double* work, const Ranges& reach) const {
  // The forward substitution runs whole: skipping the same supernodes there made F slower
  // (10x5x5 / H/h 5, 2 threads: A_rho 7.5 -> 8.4 ms; the factor no longer streams in one
  // run), while the backward one over the reach alone saves about 3.5 % (doc/measurements/performance.md).
  forward(0, numSupernodes(), v, work, size(), nullptr);
  for (auto range = reach.rbegin(); range != reach.rend(); ++range) backward(range->first, range->second, v, work);
}

long long PackedFactor::substitutionBytes(LO first, LO last) const {
  long long bytes = 0;
  for (LO k = first; k < last; ++k) {
    const Supernode& s = supernodes_[k];
    const long long nc = s.numColumns, nr = s.numPanelRows;
    bytes += valueBytes() * (nc * (nc - 1) / 2 + nc * nr) + 8 * nc + 4 * nr + static_cast<long long>(sizeof(Supernode));
  }
  return bytes;
}

long long PackedFactor::solveBytes(const Ranges& reach) const {
  long long backward = 0;
  for (const auto& [first, last] : reach) backward += substitutionBytes(first, last);
  return substitutionBytes(0, numSupernodes()) + backward;
}

long long PackedFactor::solveBytes() const {
  const long long factor = valueBytes() * valueCount() + 8 * static_cast<long long>(inverseDiagonal_.size()) +
                           4 * static_cast<long long>(rows_.size()) +
                           static_cast<long long>(sizeof(Supernode) * supernodes_.size());
  return 2 * factor;
}

}  // namespace tribos::feti
