// qp/VectorOps and SeparableSet's threaded loops (issue 9): every result has the bits of the
// Tpetra passes they replace (update, assign, normInf), on 1 and 2 threads, for
// vectors of several chunks (core::kVectorChunk) and sets of several chunks of blocks.
#include <gtest/gtest.h>

#include <Tpetra_Vector.hpp>

#include <cstring>
#include <functional>
#include <random>
#include <vector>

#include "DenseQp.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/qp/SeparableSet.hpp"
#include "tribos/qp/VectorOps.hpp"

using namespace tribos;
using qp::Vector;

namespace {
// Three chunks and a tail, on this process alone.
const int kLength = 3 * static_cast<int>(core::kVectorChunk) + 37;

// A map of its own for each vector (a static one would outlive Kokkos); all have kLength
// entries on this process.
Teuchos::RCP<const qp::Map> map() { return test::makeMap(kLength, test::selfComm()); }

// Random entries of both signs over several binades, with +0, -0, and (optionally) inf.
Vector randomVector(unsigned seed, bool withInfinity = false) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), e(-20.0, 20.0);
  Vector v(map());
  auto view = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (int i = 0; i < kLength; ++i) {
    view(i, 0) = u(rng) * std::ldexp(1.0, static_cast<int>(e(rng)));
    if (i % 101 == 0) view(i, 0) = 0.0;
    if (i % 103 == 0) view(i, 0) = -0.0;
    if (withInfinity && i % 997 == 0) view(i, 0) = std::numeric_limits<double>::infinity();
  }
  return v;
}

Vector copyOf(const Vector& v) {
  Vector c(map());
  c.assign(v);
  return c;
}

// Bitwise equality of the local entries (NaNs of the same bits compare equal).
bool sameBits(const Vector& a, const Vector& b) {
  const auto av = a.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto bv = b.getLocalViewHost(Tpetra::Access::ReadOnly);
  return std::memcmp(av.data(), bv.data(), sizeof(double) * a.getLocalLength()) == 0;
}

// Runs check() on 1 and on 2 threads.
void onOneAndTwoThreads(const std::function<void()>& check) {
  for (int threads : {1, 2}) {
    SCOPED_TRACE(std::to_string(threads) + " thread(s)");
    core::setNumThreads(threads);
    check();
  }
  core::setNumThreads(0);
}

const double kCoefficients[] = {0.0, -0.0, 1.0, -1.0, 0.37, -2.5e3};
}  // namespace

TEST(VectorOps, haveTheBitsOfTpetrasUpdateAndAssign) {
  const Vector x = randomVector(1, true), y = randomVector(2), z = randomVector(3);
  onOneAndTwoThreads([&] {
    for (double a : kCoefficients)
      for (double b : kCoefficients) {
        SCOPED_TRACE("a = " + std::to_string(a) + ", b = " + std::to_string(b));
        Vector mine = copyOf(y), theirs = copyOf(y);
        qp::axpby(a, x, b, mine);
        theirs.update(a, x, b);
        EXPECT_TRUE(sameBits(mine, theirs)) << "axpby";
        for (double c : kCoefficients) {
          Vector mine3 = copyOf(z), theirs3 = copyOf(z);
          qp::update(a, x, b, y, c, mine3);
          theirs3.update(a, x, b, y, c);
          EXPECT_TRUE(sameBits(mine3, theirs3)) << "update, c = " << c;
        }
      }
    Vector mine(map()), theirs(map());
    qp::assign(mine, x);
    theirs.assign(x);
    EXPECT_TRUE(sameBits(mine, theirs));
  });
}

TEST(VectorOps, fusedStepsHaveTheBitsOfTheirSeparatePasses) {
  const Vector p = randomVector(4), q = randomVector(5), x0 = randomVector(6), g0 = randomVector(7);
  onOneAndTwoThreads([&] {
    for (double alpha : {0.0, -0.0, 0.81, -3.0}) {
      Vector x = copyOf(x0), g = copyOf(g0), xRef = copyOf(x0), gRef = copyOf(g0);
      qp::stepAlong(alpha, p, q, x, g);
      xRef.update(-alpha, p, 1.0);
      gRef.update(-alpha, q, 1.0);
      EXPECT_TRUE(sameBits(x, xRef));
      EXPECT_TRUE(sameBits(g, gRef));
      Vector savedX(map()), savedG(map());
      x = copyOf(x0);
      qp::saveAndStep(alpha, p, x, g0, savedX, savedG);
      EXPECT_TRUE(sameBits(savedX, x0));
      EXPECT_TRUE(sameBits(savedG, g0));
      EXPECT_TRUE(sameBits(x, xRef));
    }
  });
}

namespace {
// Bounds on every 7th entry, ellipses (discs, flat ellipses, segments, points, one absent
// row) on pairs elsewhere: more than one chunk of blocks of each kind. `interior`: a vector
// that every block holds as it is (above the bounds, at the centres).
qp::SeparableSet manyBlocks(Vector& interior) {
  qp::SeparableSet set;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-1.0, 1.0), axis(0.01, 2.0);
  auto v = interior.getLocalViewHost(Tpetra::Access::ReadWrite);
  for (int i = 0; i + 2 < kLength; i += 7) {
    set.addBound(i, 0.1 * u(rng));
    v(i, 0) = 1.0;
    std::array<double, 2> a{axis(rng), axis(rng)};
    const int kind = (i / 7) % 9;
    if (kind == 0) a[1] = a[0];
    if (kind == 1) a[0] = 0.0;
    if (kind == 2) a = {0.0, 0.0};
    const std::array<double, 2> centre{0.3 * u(rng), 0.3 * u(rng)};
    set.addEllipse({i + 1, kind == 3 ? -1 : i + 2}, centre, a);
    v(i + 1, 0) = centre[0];
    if (kind != 3) v(i + 2, 0) = centre[1];
  }
  return set;
}

// What MPGP's test with Tpetra decided: trial = x; project(x); (x - trial).normInf() > 0.
bool movedByTpetraPasses(const qp::SeparableSet& set, Vector& x) {
  Vector trial = copyOf(x);
  set.project(x);
  trial.update(1.0, x, -1.0);
  return trial.normInf() > 0.0;
}
}  // namespace

TEST(SeparableSet, threadedLoopsHaveTheBitsOfTheTpetraPasses) {
  Vector interior = randomVector(15);
  const auto set = manyBlocks(interior);
  ASSERT_GT(set.numBounds(), 2048);
  ASSERT_GT(set.numEllipses(), 2048);
  // A feasible x with blocks on their boundaries (projected from far out) and inside.
  Vector x = randomVector(10);
  x.scale(1e-6);
  Vector far = randomVector(11);
  far.scale(1e6);
  x.update(1.0, far, 1.0);
  set.project(x);
  Vector inside = randomVector(12);
  inside.scale(1e-9);
  x.update(1.0, inside, 0.5);
  set.project(x);
  const Vector g = randomVector(13), phi0 = randomVector(14);
  std::vector<Vector> reference;
  double referenceStep[2] = {0.0, 0.0};
  bool first = true;
  onOneAndTwoThreads([&] {
    // phi~ = (x - P(x - alpha phi)) / alpha: the three Tpetra passes it replaces.
    const double alpha = 0.37;
    Vector reduced(map()), theirs(map());
    set.reducedFreeGradient(x, phi0, alpha, reduced);
    theirs.update(1.0, x, -alpha, phi0, 0.0);
    set.project(theirs);
    theirs.update(1.0 / alpha, x, -1.0 / alpha);
    EXPECT_TRUE(sameBits(reduced, theirs)) << "reducedFreeGradient";
    // splitGradient, both variants, and the feasible steps: the same on 1 and 2 threads.
    Vector phi(map()), beta(map()), phiSlide(map()), betaSlide(map());
    set.splitGradient(x, g, phi, beta, false);
    set.splitGradient(x, g, phiSlide, betaSlide, true);
    const double steps[2] = {set.maxFeasibleStep(x, g, false), set.maxFeasibleStep(x, g, true)};
    if (first) {
      for (const Vector* v : {&phi, &beta, &phiSlide, &betaSlide}) reference.push_back(copyOf(*v));
      referenceStep[0] = steps[0];
      referenceStep[1] = steps[1];
      first = false;
    } else {
      EXPECT_TRUE(sameBits(phi, reference[0]));
      EXPECT_TRUE(sameBits(beta, reference[1]));
      EXPECT_TRUE(sameBits(phiSlide, reference[2]));
      EXPECT_TRUE(sameBits(betaSlide, reference[3]));
      EXPECT_EQ(std::memcmp(steps, referenceStep, sizeof(steps)), 0);
    }
    // projectMoved: what trial = x; project(x); (x - trial).normInf() > 0 decided, and the
    // same x; a projected x may move by round-off when projected again (c + ((c + y) - c)).
    for (const Vector* start : {&interior, &x}) {
      Vector y = copyOf(*start), yRef = copyOf(*start);
      EXPECT_EQ(set.projectMoved(y), movedByTpetraPasses(set, yRef));
      EXPECT_TRUE(sameBits(y, yRef));
    }
    Vector y = copyOf(interior);
    EXPECT_FALSE(set.projectMoved(y));
    for (int k : {0, kLength - 5}) {  // below the first bound, off the last ellipse
      Vector z = copyOf(interior);
      z.getLocalViewHost(Tpetra::Access::ReadWrite)(k - k % 7 + (k == 0 ? 0 : 1), 0) -= 10.0;
      Vector zRef = copyOf(z);
      EXPECT_TRUE(set.projectMoved(z));
      EXPECT_TRUE(movedByTpetraPasses(set, zRef));
      EXPECT_TRUE(sameBits(z, zRef));
    }
  });
}
