#pragma once
/// \file ReproducibleSum.hpp
/// Sums across ranks whose bits do not depend on the order of the addends, hence not on how
/// they are split over ranks and threads (issue 11: the same counts and energy bits on 1, 2,
/// 3, 4 ranks). Plain floating-point addition is not associative: a dual vector's rows owned
/// by other ranks are summed in another grouping, and over a few thousand MPGP steps the
/// round-off decides a different active set somewhere.
///
/// Method (pre-rounding, after Rump-Ogita-Oishi's ExtractScalar and Demmel-Nguyen's binned
/// sums; written here): every addend x, |x| <= M, of a sum of at most N addends is split on
/// fixed quanta into kSlices parts. With 2^e > M, L = ceil(log2 N) and k_1 = e + L + 1, the
/// first slice is x rounded to a multiple of u_1 = 2^(k_1 - 52), obtained exactly as
/// q = (x + sigma) - sigma with sigma = 1.5 * 2^k_1; the remainder x - q (exact, at most
/// u_1 / 2) goes to the next slice, whose k is k_1 - (52 - L), and so on. A slice's sum
/// is a sum of at most N multiples of u_j each below 2^(k_j - 1) / N, so every partial sum,
/// in any order and on any rank, is exact in double; so is the all-reduce of the slices.
/// The slices are then added in a fixed order. M and N must be the same on every rank (a MAX
/// all-reduce, exact, and a count that does not depend on the layout).
///
/// Accuracy: the dropped remainder is at most N u_K / 2 = 2^(e + 3L - 104) with K = kSlices = 2,
/// and M >= 2^(e - 1), N > 2^(L - 1), so |result - exact sum| <= 2^(2L - 102) N M + eps |exact
/// sum| (eps = 2^-52, the final additions): for N up to 2^25 well below recursive summation's
/// bound (N - 1) 2^-53 sum |x_i| when the x_i are of one size; for N = 10^5, 2^-68 N M. Quanta below the
/// smallest normal double are raised to it (remainders under 2^-1021 per addend are dropped);
/// when 2^(k_1 + 1) would overflow (N M beyond ~1e307) or M is not finite, the sum falls back
/// to plain addition (not reproducible; a non-finite input gives a non-finite result as before).
///
/// The callers' addends (products x_i y_i included) must be rounded the same way on every
/// layout: the files that deposit are compiled with -ffp-contract=off (no fused multiply-add
/// in one loop version and not in another).
#include <cstddef>
#include <vector>

namespace Teuchos {
template <class Ordinal>
class Comm;
}

namespace tribos::core {

/// The fixed quanta for addends |x| <= bound, at most `count` of them in any one sum.
class SumBins {
 public:
  static constexpr int kSlices = 2;
  SumBins(double bound, long long count);
  /// slots[0..kSlices) += the slices of x (exact; order-free).
  void deposit(double x, double* slots) const {
    for (int j = 0; j < kSlices; ++j) {
      const double q = (x + sigma_[j]) - sigma_[j];
      slots[j] += q;
      x -= q;
    }
  }
  /// The sum from its slots, added in a fixed order (smallest slice first).
  static double combine(const double* slots) {
    double s = slots[kSlices - 1];
    for (int j = kSlices - 2; j >= 0; --j) s += slots[j];
    return s;
  }
  /// False when the bound forced plain addition (see the file comment).
  bool reproducible() const { return reproducible_; }
  /// sigma of slice j (1.5 * 2^k_j; 0 for plain addition).
  double sigma(int j) const { return sigma_[j]; }

 private:
  double sigma_[kSlices];
  bool reproducible_ = true;
};

/// Global max of `local` over the ranks of comm (nullptr: this process alone).
double globalMax(const Teuchos::Comm<int>* comm, double local);
/// Adds `slots` element-wise over the ranks (in place; exact for slots filled by deposit).
void allReduceSlots(const Teuchos::Comm<int>* comm, std::vector<double>& slots);

/// sum_i x_i over all ranks' x[0..n); `count` >= the global number of addends, the same on
/// every rank.
double reproducibleSum(const Teuchos::Comm<int>* comm, const double* x, std::size_t n, long long count);
/// sum_i a_i b_i over all ranks (each product rounded once, then summed reproducibly).
double reproducibleDot(const Teuchos::Comm<int>* comm, const double* a, const double* b, std::size_t n,
                       long long count);
/// Two dot products with one MAX and one SUM all-reduce: {a.b, c.d} (the same n for both).
void reproducibleDots(const Teuchos::Comm<int>* comm, const double* a, const double* b, const double* c,
                      const double* d, std::size_t n, long long count, double out[2]);
/// k dot products out[i] = a[i] . b[i] (the same n for all) with one MAX and one SUM
/// all-reduce. Each keeps its own bound, hence its own quanta: out[i] has the bits of
/// reproducibleDot(comm, a[i], b[i], n, count) alone.
void reproducibleDots(const Teuchos::Comm<int>* comm, const double* const* a, const double* const* b, int k,
                      std::size_t n, long long count, double* out);

}  // namespace tribos::core
