// qp/ on a distributed map (run on 2 ranks): the rows of small QPs are split between the
// ranks (blocks kept whole, as SeparableSet requires); the same problem is solved on every
// rank alone (MPI_COMM_SELF) as the one-rank reference. The power method, MPGP and SMALSE-M
// must give the same answer, and the same counts (they differ only by the order of the
// sums in the global reductions).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "DenseQp.hpp"
#include "tribos/qp/Mpgp.hpp"
#include "tribos/qp/SmalseM.hpp"

using namespace tribos;
using test::Dense;

namespace {
/// A map over the world's ranks whose boundaries fall on block starts.
Teuchos::RCP<const qp::Map> blockAlignedMap(const test::BlockSet& blocks, int n) {
  const auto comm = test::worldComm();
  const int size = comm->getSize(), rank = comm->getRank();
  std::vector<int> cuts{0};
  for (int p = 1; p < size; ++p) {
    const int target = n * p / size;
    int cut = n;
    for (int s : blocks.blockStarts)
      if (s >= target) {
        cut = s;
        break;
      }
    cuts.push_back(std::max(cut, cuts.back()));
  }
  cuts.push_back(n);
  return test::makeMapWithLocalSize(n, cuts[rank + 1] - cuts[rank], comm);
}

struct Problem {
  test::EqualityQp qp;
  test::BlockSet blocks;
};

Problem makeProblem(unsigned seed, int n) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Dense M = test::randomSpd(n, 100.0, seed + 7);
  std::vector<double> b(n), x0(n);
  for (double& v : b) v = 3.0 * u(gen);
  Problem p;
  p.blocks = test::randomBlocks(n, gen, {1.5, 2, 1, 1, 0.3, 0.15}, 30.0);
  for (double& v : x0) v = u(gen);
  p.blocks.project(x0);
  Dense G(2, std::vector<double>(n));
  const double xx = test::norm2(x0) * test::norm2(x0);
  for (auto& row : G) {
    for (double& v : row) v = u(gen);
    double d = 0.0;
    for (int i = 0; i < n; ++i) d += row[i] * x0[i];
    for (int i = 0; i < n; ++i) row[i] -= d / xx * x0[i];
  }
  p.qp = test::makeEqualityQp(M, G, b);
  return p;
}
}  // namespace

TEST(SmalseM, distributedMatchesOneRank) {
  ASSERT_GE(test::worldComm()->getSize(), 2) << "run under mpirun -np 2";
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const int n = 24;
    const auto problem = makeProblem(seed, n);
    const auto distributed = blockAlignedMap(problem.blocks, n);
    const auto alone = test::makeMap(n, test::selfComm());
    // Every rank owns a part.
    EXPECT_GT(distributed->getNodeNumElements(), 0u);

    qp::SmalseSettings settings;
    settings.tolerance = 1e-10;
    settings.rho = 10.0;
    settings.M0 = 1.0;
    settings.betaM = 0.5;
    struct Result {
      std::vector<double> mpgp, smalse;
      qp::MpgpCounters mpgpCounters;
      qp::SmalseCounters smalseCounters;
      double normA;
    };
    auto solve = [&](const Teuchos::RCP<const qp::Map>& map) {
      Result r;
      test::DenseOperator A(problem.qp.A), M(problem.qp.M);
      test::DenseProjector Q(problem.qp.Q);
      r.normA = qp::powerMethod(M, *map, 30, 0.0, nullptr);
      // MPGP on min 1/2 x^T M x - b^T x over Omega (no equality).
      auto omega = problem.blocks.build(*map);
      qp::Vector b(map), x(map), g(map);
      test::scatter(problem.qp.b, b);
      r.mpgpCounters =
          qp::Mpgp().solve(M, b, omega, 101.0, x, g, [](double gp, const qp::Vector&) { return gp <= 1e-11; });
      r.mpgp = test::gather(x);
      // SMALSE-M with the equality.
      qp::Vector c(map), mu(map);
      test::scatter(problem.qp.c, c);
      r.smalseCounters = qp::SmalseM(settings).solve(A, Q, c, omega, mu);
      r.smalse = test::gather(mu);
      return r;
    };
    const auto d = solve(distributed), s = solve(alone);
    EXPECT_NEAR(d.normA, s.normA, 1e-13 * s.normA);
    EXPECT_TRUE(d.mpgpCounters.converged);
    EXPECT_TRUE(d.smalseCounters.converged);
    EXPECT_LE(test::maxDifference(d.mpgp, s.mpgp), 1e-10) << "seed " << seed;
    EXPECT_LE(test::maxDifference(d.smalse, s.smalse), 1e-10) << "seed " << seed;
    // Counts within 2 % (issue 11's bound) and one outer iteration: the reductions sum in
    // another order on two ranks, and MPGP's step choices (the proportioning test, the
    // acceptance of a chopped-gradient step) compare round-off-close numbers.
    auto near = [](double a, double b) { return std::abs(a - b) <= 0.02 * std::max(a, b) + 1.0; };
    EXPECT_PRED2(near, d.mpgpCounters.iterations, s.mpgpCounters.iterations) << "seed " << seed;
    EXPECT_LE(std::abs(d.smalseCounters.outerIterations - s.smalseCounters.outerIterations), 1) << "seed " << seed;
    // SMALSE-M's products within 10 %: its ||A|| estimate (Lanczos, stopped at a 1e-4 change)
    // may stop one step apart on the two layouts, and alpha_bar, rho and M follow it. The
    // Table 1 driver runs give identical counts on 1/2 ranks x 1/2 threads
    // (integration.tribosDriver.sameIterationCountsOnEveryRankAndThreadLayout).
    auto within10 = [](double a, double b) { return std::abs(a - b) <= 0.10 * std::max(a, b); };
    EXPECT_PRED2(within10, d.smalseCounters.operatorApplications, s.smalseCounters.operatorApplications)
        << "seed " << seed;
    // The one-rank solutions agree between the ranks too (each solved it alone).
    const auto comm = test::worldComm();
    double local = s.smalse[seed % n], maxv = 0.0, minv = 0.0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &local, &maxv);
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MIN, 1, &local, &minv);
    EXPECT_EQ(maxv, minv);
  }
}
