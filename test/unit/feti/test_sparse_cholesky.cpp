// The sparse Cholesky factorisations behind makeSparseCholesky ("CHOLMOD", "Tacho"): the same
// contract for each (SparseCholesky.hpp): solves SPD systems with several right-hand sides,
// rejects matrices that are not positive definite, can be refactorised, and gives the same
// results on the threads of core::forEachSubdomain as alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/feti/SparseCholesky.hpp"
#include "RandomSpd.hpp"

using namespace tribos;
using test::randomSpd;
using test::randomVector;

namespace {

double norm(const double* v, size_t n) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += v[i] * v[i];
  return std::sqrt(s);
}

/// max_j ||A x_j - b_j|| / ||b_j|| over the columns.
double relativeResidual(const fem::CsrMatrix& A, const std::vector<double>& x, const std::vector<double>& b,
                        int nrhs) {
  const size_t n = static_cast<size_t>(A.n);
  std::vector<double> r(n);
  double worst = 0.0;
  for (int j = 0; j < nrhs; ++j) {
    A.apply(&x[j * n], r.data());
    for (size_t i = 0; i < n; ++i) r[i] -= b[j * n + i];
    worst = std::max(worst, norm(r.data(), n) / norm(&b[j * n], n));
  }
  return worst;
}

class SparseCholeskyTest : public ::testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(SparseCholeskyTest, solvesRandomSpdSystemsWithSeveralRightHandSides) {
  // m = 3: 81 dofs (Table 1's smallest subdomain); m = 8: 1536 dofs (above Tacho's default
  // dense threshold of 1024, so both code paths are sparse).
  for (int m : {1, 3, 8}) {
    const auto A = randomSpd(m, 0.1, 7u + m);
    auto chol = feti::makeSparseCholesky(GetParam());
    EXPECT_EQ(chol->name(), GetParam());
    chol->factorize(A);
    EXPECT_EQ(chol->size(), A.n);
    // The factor holds at least the lower triangle of A.
    EXPECT_GE(chol->factorNonzeros(), static_cast<long long>((A.colInd.size() + A.n) / 2));
    for (int nrhs : {1, 4}) {
      const auto b = randomVector(static_cast<size_t>(A.n) * nrhs, 11u * nrhs);
      std::vector<double> x(b.size());
      chol->solve(b.data(), x.data(), nrhs);
      EXPECT_LT(relativeResidual(A, x, b, nrhs), 1e-12) << GetParam() << " n = " << A.n << " nrhs = " << nrhs;
    }
  }
}

TEST_P(SparseCholeskyTest, refactorizesWithANewMatrix) {
  auto chol = feti::makeSparseCholesky(GetParam());
  chol->factorize(randomSpd(4, 0.5, 1u));
  const auto A = randomSpd(5, 0.5, 2u);  // another size and other values
  chol->factorize(A);
  const auto b = randomVector(A.n, 3u);
  std::vector<double> x(b.size());
  chol->solve(b.data(), x.data());
  EXPECT_LT(relativeResidual(A, x, b, 1), 1e-12);
}

TEST_P(SparseCholeskyTest, rejectsMatricesThatAreNotPositiveDefinite) {
  // Negative definite.
  auto A = randomSpd(4, 0.1, 5u);
  for (double& v : A.values) v = -v;
  auto chol = feti::makeSparseCholesky(GetParam());
  EXPECT_THROW(chol->factorize(A), std::runtime_error);
  // Indefinite with a single negative eigenvalue direction: one diagonal entry negative.
  auto B = randomSpd(4, 0.1, 6u);
  for (LO k = B.rowPtr[100]; k < B.rowPtr[101]; ++k)
    if (B.colInd[k] == 100) B.values[k] = -1.0;
  EXPECT_THROW(chol->factorize(B), std::runtime_error);
  // The object stays usable after a failure.
  const auto C = randomSpd(3, 1.0, 8u);
  chol->factorize(C);
  const auto b = randomVector(C.n, 9u);
  std::vector<double> x(b.size());
  chol->solve(b.data(), x.data());
  EXPECT_LT(relativeResidual(C, x, b, 1), 1e-12);
}

TEST_P(SparseCholeskyTest, threadsGiveTheSequentialResults) {
  // 12 independent factorisations on the threads of forEachSubdomain (the test runs with
  // OMP_NUM_THREADS=2), against one thread. Serial OpenBLAS is not thread-safe, so this
  // also guards the BLAS serialisation (SparseCholeskyImpl.hpp): unguarded, 6-25 % of
  // concurrent supernodal factorisations at these sizes came out wrong. Four right-hand
  // sides: multi-column solves (trsm/gemm) are where the race shows most often.
  const int count = 12;
  std::vector<fem::CsrMatrix> matrices;
  for (int i = 0; i < count; ++i) matrices.push_back(randomSpd(6 + i % 3, 0.1, 100u + i));
  auto run = [&](int threads) {
    core::setNumThreads(threads);
    std::vector<std::vector<double>> out(count);
    core::forEachSubdomain(count, [&](int i) {
      auto chol = feti::makeSparseCholesky(GetParam());
      chol->factorize(matrices[i]);
      const auto b = randomVector(static_cast<size_t>(matrices[i].n) * 4, i);
      out[i].resize(b.size());
      chol->solve(b.data(), out[i].data(), 4);
    });
    core::setNumThreads(0);
    return out;
  };
  const auto one = run(1), two = run(2);
  for (int i = 0; i < count; ++i) {
    double diff = 0.0;
    for (size_t k = 0; k < one[i].size(); ++k) diff = std::max(diff, std::abs(one[i][k] - two[i][k]));
    // Tacho does the same operations on either thread count (bitwise); CHOLMOD is simplicial
    // inside a team and supernodal alone: the same factor up to rounding.
    EXPECT_LE(diff, 1e-13 * norm(one[i].data(), one[i].size())) << GetParam() << " matrix " << i;
    const auto b = randomVector(static_cast<size_t>(matrices[i].n) * 4, i);
    EXPECT_LT(relativeResidual(matrices[i], two[i], b, 4), 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Implementations, SparseCholeskyTest, ::testing::ValuesIn(feti::sparseCholeskyNames()),
                         [](const auto& info) { return info.param; });

TEST(SparseCholesky, subtreeSolvesGiveTheSameBitsOnAnyThreadCountAndSolveTheSystem) {
  // The replicated coarse factor's concurrent solves (setSubtreeSolve): the elimination
  // tree split into subtrees solved on the threads of forEachSubdomain, with the bits of the
  // serial solve. From any size here
  // (the threshold at 0, FETI/Subtree Solve From), on a supernodal factor (>= 4000 rows) and a
  // simplicial one (merged into supernodes by tribos), each split into at least three subtrees.
  for (int m : {8, 12}) {
    const fem::CsrMatrix A = randomSpd(m, 0.1, 7u + m);
    feti::SparseCholeskyOptions fromAnySize;
    fromAnySize.subtreeSolveFromValues = 0;
    auto serial = feti::makeSparseCholesky("CHOLMOD", fromAnySize), split = feti::makeSparseCholesky("CHOLMOD", fromAnySize);
    split->setSubtreeSolve(true);
    serial->factorize(A);
    split->factorize(A);
    EXPECT_EQ(serial->subtreeCount(), 0);
    EXPECT_GE(split->subtreeCount(), 3) << "m = " << m;
    const auto b = randomVector(static_cast<size_t>(A.n), 3u + m);
    std::vector<double> reference(b.size());
    serial->solve(b.data(), reference.data());
    std::vector<double> first;
    for (int threads : {1, 2, 3, 1}) {
      core::setNumThreads(threads);
      std::vector<double> x(b.size());
      split->solve(b.data(), x.data());
      if (first.empty()) first = x;
      EXPECT_EQ(std::memcmp(x.data(), first.data(), sizeof(double) * x.size()), 0) << threads << " threads, m = " << m;
      EXPECT_LT(relativeResidual(A, x, b, 1), 1e-12);
      // In place, in the factor's order: the same bits as solve().
      std::vector<double> v(b.size());
      const auto& perm = split->permutation();
      for (size_t k = 0; k < v.size(); ++k) v[k] = b[perm[k]];
      split->solveInPlace(v.data());
      for (size_t k = 0; k < v.size(); ++k) EXPECT_EQ(v[k], x[perm[k]]);
    }
    core::setNumThreads(0);
    // The subtractions of the serial solve in its order: its bits.
    EXPECT_EQ(std::memcmp(first.data(), reference.data(), sizeof(double) * first.size()), 0) << "m = " << m;
  }
}

// roundToSingle (G G^T's factor for SMALSE-M's projections, TotalFeti's "Coarse Factor
// Precision"): on a simplicial and a supernodal factor (the latter rounded in place in
// CHOLMOD's array), split into subtrees. The solves read about half the bytes; they differ
// from the double ones (rounded: not zero) by about the rounding times the condition number
// (below 1e-4 on these matrices); they give the same bits on 1-3 threads; and iterative
// refinement with them converges to the double solution, as TotalFeti's exact solves do.
TEST(SparseCholesky, roundedToSingleItHalvesTheBytesAndRefinesToTheDoubleSolution) {
  for (int m : {8, 12}) {
    const fem::CsrMatrix A = randomSpd(m, 0.1, 7u + m);
    feti::SparseCholeskyOptions fromAnySize;
    fromAnySize.subtreeSolveFromValues = 0;
    auto exact = feti::makeSparseCholesky("CHOLMOD", fromAnySize), rounded = feti::makeSparseCholesky("CHOLMOD", fromAnySize);
    rounded->setSubtreeSolve(true);
    exact->factorize(A);
    rounded->factorize(A);
    const long long values = rounded->factorNonzeros(), bytes = rounded->solveBytes();
    ASSERT_TRUE(rounded->roundToSingle());
    EXPECT_EQ(rounded->factorNonzeros(), values);
    EXPECT_LT(rounded->solveBytes(), 0.62 * static_cast<double>(bytes)) << "m = " << m;
    EXPECT_GT(rounded->solveBytes(), 0.45 * static_cast<double>(bytes)) << "m = " << m;
    const auto b = randomVector(static_cast<size_t>(A.n), 5u + m);
    std::vector<double> x(b.size()), first;
    exact->solve(b.data(), x.data());
    for (int threads : {1, 2, 3}) {
      core::setNumThreads(threads);
      std::vector<double> y(b.size());
      rounded->solve(b.data(), y.data());
      if (first.empty()) first = y;
      EXPECT_EQ(std::memcmp(y.data(), first.data(), sizeof(double) * y.size()), 0) << threads << " threads, m = " << m;
    }
    core::setNumThreads(0);
    std::vector<double> difference(b.size());
    for (size_t i = 0; i < b.size(); ++i) difference[i] = first[i] - x[i];
    const double error = norm(difference.data(), b.size()) / norm(x.data(), x.size());
    EXPECT_GT(error, 1e-12) << "m = " << m;
    EXPECT_LT(error, 1e-4) << "m = " << m;
    // z += C~^-1 (b - A z): contracts by about `error` per step.
    std::vector<double> z = first, r(b.size()), d(b.size());
    for (int step = 0; step < 6; ++step) {
      A.apply(z.data(), r.data());
      for (size_t i = 0; i < r.size(); ++i) r[i] = b[i] - r[i];
      rounded->solve(r.data(), d.data());
      for (size_t i = 0; i < z.size(); ++i) z[i] += d[i];
    }
    for (size_t i = 0; i < b.size(); ++i) difference[i] = z[i] - x[i];
    EXPECT_LT(norm(difference.data(), b.size()) / norm(x.data(), x.size()), 1e-13) << "m = " << m;
  }
}

// setSparseColumns / solveInPlaceOnColumns, as F uses them (the dofs of B_s: a subdomain's
// surface): for a right-hand side that vanishes off the surface of the m^3 grid, the solution
// on the surface has the bits of the whole solve; "CHOLMOD" reads less of the factor for it
// (its backward substitution skips what the surface does not reach: the interior's subtrees),
// Tacho solves whole.
TEST_P(SparseCholeskyTest, solvesOnColumnsGiveTheWholeSolvesBitsThere) {
  for (int m : {8, 12}) {  // simplicial and supernodal CHOLMOD factors
    const fem::CsrMatrix A = randomSpd(m, 0.1, 21u + m);
    auto chol = feti::makeSparseCholesky(GetParam());
    chol->factorize(A);
    const auto& perm = chol->permutation();
    std::vector<LO> position(perm.size());
    for (size_t k = 0; k < perm.size(); ++k) position[perm[k]] = static_cast<LO>(k);
    std::vector<LO> surface;
    for (int k = 0; k < m; ++k)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          if (std::min({i, j, k}) > 0 && std::max({i, j, k}) < m - 1) continue;
          for (int c = 0; c < 3; ++c) surface.push_back(position[3 * (i + m * (j + m * k)) + c]);
        }
    chol->setSparseColumns(surface);
    const auto values = randomVector(surface.size(), 5u + m);
    std::vector<double> whole(perm.size(), 0.0);
    for (size_t q = 0; q < surface.size(); ++q) whole[surface[q]] = values[q];
    std::vector<double> onColumns = whole;
    chol->solveInPlace(whole.data());
    chol->solveInPlaceOnColumns(onColumns.data());
    for (LO column : surface) EXPECT_EQ(onColumns[column], whole[column]) << "m = " << m << ", column " << column;
    if (GetParam() == "CHOLMOD") {
      EXPECT_LT(chol->solveBytesOnColumns(), chol->solveBytes()) << "m = " << m;
      EXPECT_GT(chol->solveBytesOnColumns(), chol->solveBytes() / 2) << "m = " << m;  // forward whole
    } else {
      EXPECT_EQ(chol->solveBytesOnColumns(), chol->solveBytes());
    }
  }
}

TEST_P(SparseCholeskyTest, factorizeConsumingGivesTheBitsOfFactorizeAndEmptiesTheMatrix) {
  // The replicated coarse matrices are handed over (factorizeConsuming) so that the matrix,
  // the factor and its packed copy are not all alive at once (CHOLMOD: the upper triangle
  // kept after the ordering, supernodal values packed in CHOLMOD's own array). The factor
  // must be the same: a simplicial (m = 8, 1 536 rows) and a supernodal (m = 12, 5 184 rows)
  // CHOLMOD factor, the same solution bits and stored entries as factorize().
  for (int m : {8, 12}) {
    const fem::CsrMatrix A = randomSpd(m, 0.1, 11u + m);
    auto kept = feti::makeSparseCholesky(GetParam()), consumed = feti::makeSparseCholesky(GetParam());
    kept->factorize(A);
    fem::CsrMatrix copy = A;
    consumed->factorizeConsuming(std::move(copy));
    EXPECT_TRUE(copy.values.empty() && copy.colInd.empty()) << "m = " << m;
    EXPECT_EQ(kept->factorNonzeros(), consumed->factorNonzeros()) << "m = " << m;
    const auto b = randomVector(static_cast<size_t>(A.n), 5u + m);
    std::vector<double> x(b.size()), y(b.size());
    kept->solve(b.data(), x.data());
    consumed->solve(b.data(), y.data());
    EXPECT_EQ(std::memcmp(x.data(), y.data(), sizeof(double) * x.size()), 0) << "m = " << m;
    EXPECT_LT(relativeResidual(A, y, b, 1), 1e-12) << "m = " << m;
  }
}

TEST(SparseCholesky, unknownNameIsAnInputErrorListingTheValidNames) {
  try {
    feti::makeSparseCholesky("NoSuchSolver");
    FAIL() << "no exception";
  } catch (const core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("FETI/Factorization"), std::string::npos) << what;
    EXPECT_NE(what.find("NoSuchSolver"), std::string::npos) << what;
    for (const auto& name : feti::sparseCholeskyNames()) EXPECT_NE(what.find(name), std::string::npos) << what;
  }
}
