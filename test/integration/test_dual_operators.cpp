// Properties of the T-FETI dual operators (paper Section 4.2) on the bonded two bricks,
// distributed over however many ranks this runs on: F symmetric positive semidefinite,
// P^2 = P, G P = 0, G lambda_Im = e, implicit F = explicit F to 1e-12, and a bounded
// condition number of P F P on Ker G as the number of subdomains grows (Lanczos estimate);
// and, on one rank, G x and P x of TotalFeti's compact G against G = R^T B^T formed densely
// from the definition (the bricks, and the Hertz cylinder's curved mortar rows); and
// the lumped and Dirichlet preconditioners equal B K B^T and B S B^T formed from freshly
// assembled K_s (dense Schur complements) to round-off.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Vector.hpp>

#include <Teuchos_XMLParameterListHelpers.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tribos/core/Parameters.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/feti/DualOperators.hpp"
#include "tribos/feti/ProjectedCg.hpp"
#include "tribos/feti/TotalFeti.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/stack/LinearFetiSolve.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

namespace {
using namespace tribos;

struct Problem {
  stack::Scene scene;
  feti::ConstraintMatrix B;
  std::unique_ptr<feti::TotalFeti> feti;
};

std::unique_ptr<Problem> makeProblem(Teuchos::ParameterList params, const std::string& source, bool explicitF,
                                     feti::TotalFetiSettings settings = {}) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  core::validateAndSetDefaults(params, *stack::sceneValidParameters(), source);
  auto p = std::make_unique<Problem>();
  p->scene = stack::buildScene(params, source);
  std::vector<fem::SubdomainSystem> systems;
  stack::assembleOwnedSubdomains(p->scene, MPI_COMM_WORLD, systems);
  p->B = feti::buildConstraintMatrix(p->scene.mesh, p->scene.decomposition, stack::constraintSpec(p->scene), size);
  settings.explicitF = explicitF;
  p->feti = std::make_unique<feti::TotalFeti>(p->scene.mesh, p->scene.decomposition, std::move(systems), p->B,
                                              Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_WORLD)), settings);
  return p;
}

std::unique_ptr<Problem> makeProblem(const std::string& grid, int hOverH, bool explicitF,
                                     feti::TotalFetiSettings settings = {}) {
  Teuchos::ParameterList params("Tribos");
  const auto valid = stack::sceneValidParameters();
  core::applyOverride(params, *valid, "Mesh/Subdomains Per Brick=" + grid);
  core::applyOverride(params, *valid, "Mesh/H Over h=" + std::to_string(hOverH));
  core::applyOverride(params, *valid, "Contact/Friction Model=Bonded");
  core::applyOverride(params, *valid, "Contact/Slave Side Set=contact_aluminium");
  core::applyOverride(params, *valid, "Contact/Master Side Set=contact_steel");
  return makeProblem(params, "test", explicitF, settings);
}

// Deterministic in the global row id, so every rank count sees the same vector.
double sample(GO g, int seed) {
  return std::sin(1.0 + 0.37 * static_cast<double>(g) * (seed + 1)) + 0.1 * std::cos(3.1 * g + seed);
}

void randomize(feti::DualVector& v, int seed) {
  auto data = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
  const auto& map = *v.getMap();
  for (size_t i = 0; i < data.extent(0); ++i) data(i, 0) = sample(map.getGlobalElement(static_cast<LO>(i)), seed);
}
}  // namespace

TEST(TotalFeti, dualOperatorIsSymmetricPositiveSemidefinite) {
  auto p = makeProblem("4x2x2", 2, false);
  auto x = p->feti->createDualVector(), y = p->feti->createDualVector(), Fx = p->feti->createDualVector(),
       Fy = p->feti->createDualVector();
  for (int seed = 0; seed < 3; ++seed) {
    randomize(*x, seed);
    randomize(*y, seed + 10);
    p->feti->applyF(*x, *Fx);
    p->feti->applyF(*y, *Fy);
    const double xFy = x->dot(*Fy), yFx = y->dot(*Fx);
    EXPECT_NEAR(xFy, yFx, 1e-12 * (std::abs(xFy) + std::abs(yFx)));
    EXPECT_GE(x->dot(*Fx), -1e-14 * Fx->norm2() * x->norm2());
  }
}

TEST(TotalFeti, projectorIsIdempotentAndAnnihilatedByG) {
  auto p = makeProblem("4x2x2", 2, false);
  auto x = p->feti->createDualVector(), Px = p->feti->createDualVector(), PPx = p->feti->createDualVector();
  randomize(*x, 1);
  p->feti->project(*x, *Px);
  p->feti->project(*Px, *PPx);
  PPx->update(-1.0, *Px, 1.0);
  EXPECT_LT(PPx->norm2(), 1e-12 * x->norm2());
  std::vector<double> GPx;
  p->feti->applyG(*Px, GPx);
  double norm = 0.0;
  for (double v : GPx) norm += v * v;
  EXPECT_LT(std::sqrt(norm), 1e-12 * x->norm2());

  // lambda_Im satisfies the equality constraint G lambda = e.
  std::vector<double> g;
  p->feti->applyG(p->feti->lambdaIm(), g);
  double diff = 0.0, eNorm = 0.0;
  for (size_t i = 0; i < g.size(); ++i) {
    diff += std::pow(g[i] - p->feti->e()[i], 2);
    eNorm += std::pow(p->feti->e()[i], 2);
  }
  EXPECT_LT(std::sqrt(diff), 1e-10 * std::sqrt(eNorm));
}

TEST(TotalFeti, aProjectionInPlaceHasTheBitsOfOneIntoAnotherVector) {
  // P x into another vector and P x in place (y aliases x): one G x, one coarse solve each,
  // the same bits.
  auto p = makeProblem("4x2x2", 2, false);
  auto x = p->feti->createDualVector(), Px = p->feti->createDualVector();
  randomize(*x, 1);
  const auto before = p->feti->profile();
  p->feti->project(*x, *Px);
  p->feti->project(*x, *x);
  const auto after = p->feti->profile();
  EXPECT_EQ(after.projections - before.projections, 2);
  EXPECT_EQ(after.coarseSolves - before.coarseSolves, 2);
  auto a = Px->getLocalViewHost(Tpetra::Access::ReadOnly), b = x->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < a.extent(0); ++i) EXPECT_EQ(a(i, 0), b(i, 0));
}

TEST(TotalFeti, aReleasedCoarseFactorIsRebuiltWithTheSameBits) {
  // releaseCoarseFactor() frees G G^T's factor before the factor of G_I G_I^T (the contact
  // solver's alpha), so that no rank holds two replicated factors. A coarse solve or
  // projection after it factorises G G^T again: the same bits as before.
  auto p = makeProblem("4x2x2", 2, false);
  std::vector<double> r(p->feti->numCoarse());
  for (size_t i = 0; i < r.size(); ++i) r[i] = std::sin(0.7 * static_cast<double>(i) + 0.1);
  std::vector<double> before = r, after = r;
  auto x = p->feti->createDualVector(), Px = p->feti->createDualVector(), Px2 = p->feti->createDualVector();
  randomize(*x, 31);
  p->feti->solveCoarse(before);
  p->feti->project(*x, *Px);
  p->feti->releaseCoarseFactor();
  p->feti->solveCoarse(after);
  p->feti->project(*x, *Px2);
  EXPECT_EQ(before, after);
  auto a = Px->getLocalViewHost(Tpetra::Access::ReadOnly), b = Px2->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < a.extent(0); ++i) EXPECT_EQ(a(i, 0), b(i, 0));
}

TEST(TotalFeti, aNewRightHandSideOnTheSameOperators) {
  // A load step (ALGORITHMS.md 11): setRightHandSide(2 f, 2 c) doubles e, d~ and lambda_Im to
  // the bit (a power of two commutes with every rounding), and projected CG's lambda with them;
  // setting (f, c) back gives the first bits again. Nothing is factorised again.
  auto p = makeProblem("4x2x2", 2, false);
  std::vector<fem::SubdomainSystem> systems;  // the same loads, assembled again
  stack::assembleOwnedSubdomains(p->scene, MPI_COMM_WORLD, systems);
  std::vector<std::vector<double>> f, twiceF;
  for (const auto& s : systems) {
    f.push_back(s.f);
    twiceF.push_back(s.f);
    for (double& v : twiceF.back()) v *= 2.0;
  }
  const std::vector<double> c = p->feti->ownedC();
  std::vector<double> twiceC = c;
  for (double& v : twiceC) v *= 2.0;
  auto copy = [](const feti::DualVector& v) {
    const auto a = v.getLocalViewHost(Tpetra::Access::ReadOnly);
    std::vector<double> out(a.extent(0));
    for (size_t i = 0; i < out.size(); ++i) out[i] = a(i, 0);
    return out;
  };
  auto solve = [&] {
    auto lambda = p->feti->createDualVector();
    feti::ProjectedCgSettings cg;
    cg.tolerance = 1e-10;
    EXPECT_TRUE(feti::solveProjectedCg(*p->feti, *lambda, cg).converged);
    return copy(*lambda);
  };
  const auto e = p->feti->e();
  const auto d = copy(p->feti->dTilde()), im = copy(p->feti->lambdaIm()), lambda = solve();
  p->feti->setRightHandSide(twiceF, twiceC);
  EXPECT_EQ(p->feti->ownedC(), twiceC);
  for (size_t i = 0; i < e.size(); ++i) EXPECT_EQ(p->feti->e()[i], 2.0 * e[i]);
  const auto d2 = copy(p->feti->dTilde()), im2 = copy(p->feti->lambdaIm()), lambda2 = solve();
  for (size_t i = 0; i < d.size(); ++i) {
    EXPECT_EQ(d2[i], 2.0 * d[i]);
    EXPECT_EQ(im2[i], 2.0 * im[i]);
    EXPECT_EQ(lambda2[i], 2.0 * lambda[i]);
  }
  p->feti->setRightHandSide(f, c);
  EXPECT_EQ(copy(p->feti->dTilde()), d);
  EXPECT_EQ(solve(), lambda);
  EXPECT_THROW(p->feti->setRightHandSide(f, std::vector<double>(c.size() + 1)), std::invalid_argument);
}

TEST(TotalFeti, aSingularRigidMotionSystemThrowsOnEveryRankAndKeepsThemInStep) {
  // G_I G_I^T (and G G^T) are factorised and solved on rank 0 alone and the result broadcast:
  // a failure there must reach every rank as the same exception, and the ranks must meet in
  // the next collective. With no row counted, G_I G_I^T = 0: singular.
  auto p = makeProblem("4x2x2", 2, false);
  auto lambda = p->feti->createDualVector(), x = p->feti->createDualVector(), Px = p->feti->createDualVector();
  lambda->putScalar(0.0);
  const std::vector<char> noRow(lambda->getLocalLength(), 0);
  EXPECT_THROW(p->feti->rigidBodyCoefficients(*lambda, noRow), feti::RigidMotionsUndetermined);
  randomize(*x, 5);
  p->feti->project(*x, *Px);  // collective: hangs if a rank were left behind
  std::vector<double> gx;
  p->feti->applyG(*Px, gx);
  double worst = 0.0;
  for (double v : gx) worst = std::max(worst, std::abs(v));
  EXPECT_LE(worst, 1e-10 * Px->norm2());
}

TEST(TotalFeti, theProjectionHandsOverTheCoarseCoordinatesOfItsInput) {
  // project(x, y, &c) gives c = (G x, (G G^T)^{-1} G x) with the bits of coarseCoordinates(x),
  // at no extra coarse solve; gx^T a = ||Q x||^2 = ||x - P x||^2 to round-off.
  auto p = makeProblem("4x2x2", 2, false);
  auto x = p->feti->createDualVector(), Px = p->feti->createDualVector();
  randomize(*x, 5);
  feti::CoarseCoordinates given;
  const auto before = p->feti->profile();
  p->feti->project(*x, *Px, &given);
  EXPECT_EQ(p->feti->profile().coarseSolves - before.coarseSolves, 1);
  std::vector<double> gx, a;
  p->feti->coarseCoordinates(*x, gx, a);
  EXPECT_EQ(p->feti->profile().coarseCoordinates - before.coarseCoordinates, 1);
  EXPECT_EQ(given.gx, gx);
  EXPECT_EQ(given.a, a);
  double q = 0.0;
  for (size_t i = 0; i < gx.size(); ++i) q += gx[i] * a[i];
  auto Qx = p->feti->createDualVector();
  Qx->update(1.0, *x, -1.0, *Px, 0.0);
  const double normQ = Qx->norm2();
  EXPECT_NEAR(std::sqrt(q), normQ, 1e-10 * normQ);
}

TEST(TotalFeti, projectedDualOperatorSkipsTheKernelProjectionsOnKerG) {
  // P F x = P B K^+ B^T x for x in Ker G (applyPF): the kernel projections of K^dagger act
  // on nothing there, up to rounding.
  auto p = makeProblem("4x2x2", 3, false);
  auto x = p->feti->createDualVector(), Px = p->feti->createDualVector(), reference = p->feti->createDualVector(),
       fast = p->feti->createDualVector();
  for (int seed = 0; seed < 2; ++seed) {
    randomize(*x, seed);
    p->feti->project(*x, *Px);
    p->feti->applyF(*Px, *reference);
    p->feti->project(*reference, *reference);
    const long long before = p->feti->fApplications();
    p->feti->applyPF(*Px, *fast);
    EXPECT_EQ(p->feti->fApplications(), before + 1);
    fast->update(-1.0, *reference, 1.0);
    EXPECT_LT(fast->norm2(), 1e-12 * reference->norm2());
  }
}

TEST(TotalFeti, implicitAndExplicitDualOperatorsAgree) {
  auto implicitF = makeProblem("4x2x2", 3, false);
  auto explicitF = makeProblem("4x2x2", 3, true);
  auto x = implicitF->feti->createDualVector(), a = implicitF->feti->createDualVector(),
       b = implicitF->feti->createDualVector();
  randomize(*x, 2);
  implicitF->feti->applyF(*x, *a);
  explicitF->feti->applyF(*x, *b);
  b->update(-1.0, *a, 1.0);
  EXPECT_LT(b->norm2(), 1e-12 * a->norm2());
}

TEST(TotalFeti, conditionNumberStaysBoundedAsSubdomainsGrow) {
  // Numerical scalability (paper Section 4): at fixed H/h, kappa(P F P | Ker G) does not
  // grow with the number of subdomains. Estimated from projected CG's Lanczos coefficients.
  std::vector<double> kappa;
  for (const char* grid : {"2x1x1", "4x2x2", "6x3x3"}) {
    auto p = makeProblem(grid, 2, false);
    auto lambda = p->feti->createDualVector();
    feti::ProjectedCgSettings cg;
    cg.tolerance = 1e-10;
    const auto r = feti::solveProjectedCg(*p->feti, *lambda, cg);
    EXPECT_TRUE(r.converged);
    kappa.push_back(r.conditionEstimate);
    RecordProperty(std::string("kappa_") + grid, std::to_string(r.conditionEstimate));
  }
  for (double k : kappa) EXPECT_GT(k, 1.0);
  EXPECT_LT(kappa[2], 1.5 * kappa[1]) << "kappa(108 subdomains) vs kappa(32): " << kappa[2] << " vs " << kappa[1];
}

namespace {
// G = R^T B^T (l x n_d, dense, row-major) straight from the definition: R_s =
// fem::rigidBodyModes of each subdomain's nodes, B's blocks as built (one rank: row = dual index).
std::vector<double> denseG(const Problem& p) {
  const auto& subdomains = p.scene.decomposition.subdomains;
  const size_t l = 6 * subdomains.size(), nd = static_cast<size_t>(p.B.numRows);
  std::vector<double> G(l * nd, 0.0);
  for (size_t s = 0; s < subdomains.size(); ++s) {
    std::vector<std::array<double, 3>> coords;
    for (LO node : subdomains[s].nodes) coords.push_back(p.scene.mesh.coords[node]);
    const std::vector<double> R = fem::rigidBodyModes(coords);
    const size_t n = 3 * coords.size();
    const auto& b = p.B.blocks[s];
    for (size_t i = 0; i < b.rows.size(); ++i)
      for (LO k = b.rowPtr[i]; k < b.rowPtr[i + 1]; ++k)
        for (size_t j = 0; j < 6; ++j) G[(6 * s + j) * nd + b.rows[i]] += b.value[k] * R[j * n + b.dof[k]];
  }
  return G;
}

// The compact G of TotalFeti (geometric modes and a 6 x 6 change of basis per subdomain) is the
// G of the definition to round-off: G x and P x = x - G^T (G G^T)^{-1} G x agree with the dense
// ones. A wrong sign or index in a rotation row, a wrong kind of row or a wrong change of
// basis moves G x by O(|G| |x|), far beyond the tolerance.
void expectCompactGMatchesDefinition(const Problem& p) {
  const auto G = denseG(p);
  const size_t nd = static_cast<size_t>(p.B.numRows), l = G.size() / nd;
  auto x = p.feti->createDualVector(), Px = p.feti->createDualVector();
  randomize(*x, 7);
  std::vector<double> xs(nd);
  {
    auto v = x->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < nd; ++i) xs[i] = v(i, 0);
  }
  std::vector<double> Gx(l, 0.0);
  for (size_t i = 0; i < l; ++i)
    for (size_t r = 0; r < nd; ++r) Gx[i] += G[i * nd + r] * xs[r];
  std::vector<double> compact;
  p.feti->applyG(*x, compact);
  ASSERT_EQ(compact.size(), l);
  double diff = 0.0, norm = 0.0;
  for (size_t i = 0; i < l; ++i) {
    diff = std::max(diff, std::abs(compact[i] - Gx[i]));
    norm = std::max(norm, std::abs(Gx[i]));
  }
  EXPECT_LT(diff, 1e-12 * norm) << "G x: compact vs definition";

  // (G G^T) a = G x by a dense Cholesky, then P x.
  std::vector<double> A(l * l, 0.0);
  for (size_t i = 0; i < l; ++i)
    for (size_t j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (size_t r = 0; r < nd; ++r) sum += G[i * nd + r] * G[j * nd + r];
      A[i * l + j] = sum;
    }
  for (size_t j = 0; j < l; ++j) {
    for (size_t k = 0; k < j; ++k) A[j * l + j] -= A[j * l + k] * A[j * l + k];
    ASSERT_GT(A[j * l + j], 0.0);
    A[j * l + j] = std::sqrt(A[j * l + j]);
    for (size_t i = j + 1; i < l; ++i) {
      for (size_t k = 0; k < j; ++k) A[i * l + j] -= A[i * l + k] * A[j * l + k];
      A[i * l + j] /= A[j * l + j];
    }
  }
  std::vector<double> a = Gx;
  for (size_t i = 0; i < l; ++i) {
    for (size_t k = 0; k < i; ++k) a[i] -= A[i * l + k] * a[k];
    a[i] /= A[i * l + i];
  }
  for (size_t i = l; i-- > 0;) {
    for (size_t k = i + 1; k < l; ++k) a[i] -= A[k * l + i] * a[k];
    a[i] /= A[i * l + i];
  }
  std::vector<double> reference = xs;
  for (size_t i = 0; i < l; ++i)
    for (size_t r = 0; r < nd; ++r) reference[r] -= G[i * nd + r] * a[i];
  p.feti->project(*x, *Px);
  auto v = Px->getLocalViewHost(Tpetra::Access::ReadOnly);
  double pDiff = 0.0, xNorm = 0.0;
  for (size_t r = 0; r < nd; ++r) {
    pDiff = std::max(pDiff, std::abs(v(r, 0) - reference[r]));
    xNorm = std::max(xNorm, std::abs(xs[r]));
  }
  EXPECT_LT(pDiff, 1e-12 * xNorm) << "P x: compact vs definition";
  char text[64];
  std::snprintf(text, sizeof text, "%.3e", diff / norm);
  ::testing::Test::RecordProperty("gx_max_relative_difference", text);
  std::snprintf(text, sizeof text, "%.3e", pDiff / xNorm);
  ::testing::Test::RecordProperty("px_max_relative_difference", text);
}
}  // namespace

TEST(TotalFeti, compactCoarseRowsMatchTheDefinitionOnTheBricks) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) GTEST_SKIP() << "the dense reference is built on one rank";
  expectCompactGMatchesDefinition(*makeProblem("4x2x2", 2, false));
}

TEST(TotalFeti, compactCoarseRowsMatchTheDefinitionOnCurvedContact) {
  // The Hertz cylinder's mortar rows have several terms per subdomain (the full entries).
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size > 1) GTEST_SKIP() << "the dense reference is built on one rank";
  // With multiplier rows for its zero displacements (the scene eliminates them): the definition
  // here takes all six rigid modes of every subdomain (integration.eliminatedConditions.* check
  // the eliminated path by its solution).
  const std::string input = std::string(TRIBOS_SOURCE_DIR) + "/input/hertz_cylinder.xml";
  auto params = *Teuchos::getParametersFromXmlFile(input);
  params.sublist("FETI").set("Displacement Conditions", std::string("Multipliers"));
  expectCompactGMatchesDefinition(*makeProblem(params, input, false));
}

namespace {
// y_b = S x_b with S = K_bb - K_bi K_ii^{-1} K_ib from dense blocks of K (b = `touched`): K_ii
// by a dense Cholesky factorisation, independent of TotalFeti's sparse blocks and factors.
std::vector<double> denseSchurProduct(const fem::CsrMatrix& K, const std::vector<char>& touched,
                                      const std::vector<double>& x) {
  const LO n = K.n;
  std::vector<LO> interior;
  for (LO d = 0; d < n; ++d)
    if (!touched[d]) interior.push_back(d);
  const size_t m = interior.size();
  std::vector<double> y(n, 0.0), L(m * m, 0.0), t(m, 0.0);
  K.apply(x.data(), y.data());  // K x (x zero on i): K_bb x_b on b, K_ib x_b on i
  for (size_t a = 0; a < m; ++a) {
    t[a] = y[interior[a]];
    for (size_t c = 0; c < m; ++c) L[a * m + c] = K.at(interior[a], interior[c]);
  }
  for (size_t j = 0; j < m; ++j) {  // K_ii = L L^T, lower triangle in place
    for (size_t k = 0; k < j; ++k) L[j * m + j] -= L[j * m + k] * L[j * m + k];
    L[j * m + j] = std::sqrt(L[j * m + j]);
    for (size_t a = j + 1; a < m; ++a) {
      for (size_t k = 0; k < j; ++k) L[a * m + j] -= L[a * m + k] * L[j * m + k];
      L[a * m + j] /= L[j * m + j];
    }
  }
  for (size_t a = 0; a < m; ++a) {  // t := K_ii^{-1} t
    for (size_t k = 0; k < a; ++k) t[a] -= L[a * m + k] * t[k];
    t[a] /= L[a * m + a];
  }
  for (size_t a = m; a-- > 0;) {
    for (size_t k = a + 1; k < m; ++k) t[a] -= L[k * m + a] * t[k];
    t[a] /= L[a * m + a];
  }
  std::vector<double> z(n, 0.0), Kz(n, 0.0);
  for (size_t a = 0; a < m; ++a) z[interior[a]] = t[a];
  K.apply(z.data(), Kz.data());
  for (LO d = 0; d < n; ++d) y[d] = touched[d] ? y[d] - Kz[d] : 0.0;
  return y;
}

// sum_s B_s A_s B_s^T x for x = sample(., seed), A_s = K_s (lumped) or its Schur complement on
// the dofs B_s touches (Dirichlet), in plain loops over freshly assembled K_s, by global row
// id, summed over the ranks.
std::vector<double> referencePreconditioner(const Problem& p, int seed, bool dirichlet) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<fem::SubdomainSystem> systems;
  stack::assembleOwnedSubdomains(p.scene, MPI_COMM_WORLD, systems);
  const int numSubdomains = p.scene.decomposition.numSubdomains();
  const int first = mesh::firstSubdomain(rank, numSubdomains, size);
  auto id = [&](GO r) { return p.B.rowId.empty() ? r : p.B.rowId[r]; };
  std::vector<double> mine(p.B.numRows, 0.0), all(p.B.numRows, 0.0);
  for (size_t i = 0; i < systems.size(); ++i) {
    const fem::CsrMatrix& K = systems[i].K;
    const feti::SubdomainBlock& b = p.B.blocks[first + i];
    std::vector<double> x(K.n, 0.0), y(K.n, 0.0);
    std::vector<char> touched(K.n, 0);
    for (size_t r = 0; r < b.rows.size(); ++r)
      for (LO k = b.rowPtr[r]; k < b.rowPtr[r + 1]; ++k) {
        x[b.dof[k]] += b.value[k] * sample(id(b.rows[r]), seed);
        touched[b.dof[k]] = 1;
      }
    if (dirichlet)
      y = denseSchurProduct(K, touched, x);
    else
      K.apply(x.data(), y.data());
    for (size_t r = 0; r < b.rows.size(); ++r)
      for (LO k = b.rowPtr[r]; k < b.rowPtr[r + 1]; ++k) mine[id(b.rows[r])] += b.value[k] * y[b.dof[k]];
  }
  MPI_Allreduce(mine.data(), all.data(), static_cast<int>(all.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  return all;
}

// max |y - reference| / max |reference| over the dual vector (all ranks).
double relativeDifference(const feti::DualVector& y, const std::vector<double>& reference) {
  auto data = y.getLocalViewHost(Tpetra::Access::ReadOnly);
  const auto& map = *y.getMap();
  double local[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};
  for (size_t i = 0; i < data.extent(0); ++i) {
    const double r = reference[map.getGlobalElement(static_cast<LO>(i))];
    local[0] = std::max(local[0], std::abs(data(i, 0) - r));
    local[1] = std::max(local[1], std::abs(r));
  }
  MPI_Allreduce(local, global, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return global[0] / global[1];
}
}  // namespace

TEST(TotalFeti, lumpedFromKbbEqualsBKBtWithTheWholeK) {
  // applyLumped multiplies by K_bb alone (b = the dofs that B touches): B^T x vanishes off b
  // and B reads b only, so it is B K B^T with the whole K, up to rounding. H/h = 3 gives the
  // subdomains interior dofs (the ones K_bb leaves out).
  feti::TotalFetiSettings settings;
  settings.lumpedPreconditioner = true;
  auto p = makeProblem("4x2x2", 3, false, settings);
  auto x = p->feti->createDualVector(), y = p->feti->createDualVector();
  for (int seed = 0; seed < 2; ++seed) {
    randomize(*x, seed);
    p->feti->applyLumped(*x, *y);
    EXPECT_LT(relativeDifference(*y, referencePreconditioner(*p, seed, false)), 1e-13);
  }
  auto plain = makeProblem("4x2x2", 2, false);
  EXPECT_THROW(plain->feti->applyLumped(*plain->feti->createDualVector(), *plain->feti->createDualVector()),
               std::logic_error);
}

TEST(TotalFeti, dirichletEqualsBSBtFromDenseSchurComplements) {
  // applyDirichlet (K_bb, K_ib, K_bi as sparse blocks, K_ii's sparse factor) against dense
  // S_s = K_bb - K_bi K_ii^{-1} K_ib per subdomain; lumped from the same object shares K_bb.
  feti::TotalFetiSettings settings;
  settings.dirichletPreconditioner = true;
  auto p = makeProblem("4x2x2", 3, false, settings);
  auto x = p->feti->createDualVector(), y = p->feti->createDualVector();
  for (int seed = 0; seed < 2; ++seed) {
    randomize(*x, seed);
    p->feti->applyDirichlet(*x, *y);
    EXPECT_LT(relativeDifference(*y, referencePreconditioner(*p, seed, true)), 1e-12);
    p->feti->applyLumped(*x, *y);
    EXPECT_LT(relativeDifference(*y, referencePreconditioner(*p, seed, false)), 1e-13);
  }
}

TEST(TotalFeti, dualOperatorsAsTpetraOperatorsGiveTheDirectProductsAndCheckTheirMaps) {
  // makeDualOperator: Y = alpha op(X) + beta Y column by column with the bits of the direct
  // calls (F, P F P = applyPF(P x), P, P D P), on the dual map; X of another map is refused.
  feti::TotalFetiSettings settings;
  settings.dirichletPreconditioner = true;
  auto p = makeProblem("4x2x2", 2, false, settings);
  const auto& f = *p->feti;
  using MV = Tpetra::MultiVector<Scalar, LO, GO>;
  MV X(f.dualMap(), 2), Y(f.dualMap(), 2);
  for (int j = 0; j < 2; ++j) {
    randomize(*X.getVectorNonConst(j), 40 + j);
    randomize(*Y.getVectorNonConst(j), 50 + j);
  }
  const double alpha = 0.75, beta = -0.5;
  auto direct = [&](feti::DualOperatorKind kind, const feti::DualVector& x, feti::DualVector& y) {
    auto t = f.createDualVector();
    switch (kind) {
      case feti::DualOperatorKind::F: f.applyF(x, y); break;
      case feti::DualOperatorKind::PFP: f.project(x, *t); f.applyPF(*t, y); break;
      case feti::DualOperatorKind::Projector: f.project(x, y); break;
      case feti::DualOperatorKind::PDP: f.project(x, *t); f.applyDirichlet(*t, y); f.project(y, y); break;
    }
  };
  for (auto kind : {feti::DualOperatorKind::F, feti::DualOperatorKind::PFP, feti::DualOperatorKind::Projector,
                    feti::DualOperatorKind::PDP}) {
    auto op = feti::makeDualOperator(f, kind);
    EXPECT_TRUE(op->getDomainMap()->isSameAs(*f.dualMap()));
    EXPECT_TRUE(op->hasTransposeApply());
    MV Z(Y, Teuchos::Copy);
    op->apply(X, Z, Teuchos::NO_TRANS, alpha, beta);
    for (int j = 0; j < 2; ++j) {
      auto expected = f.createDualVector();
      direct(kind, *X.getVector(j), *expected);
      expected->update(beta, *Y.getVector(j), alpha);  // alpha op(x) + beta y, in the operator's order
      auto z = Z.getVector(j)->getLocalViewHost(Tpetra::Access::ReadOnly);
      auto e = expected->getLocalViewHost(Tpetra::Access::ReadOnly);
      double worst = 0.0, scale = 0.0;
      for (size_t i = 0; i < z.extent(0); ++i) {
        worst = std::max(worst, std::abs(z(i, 0) - e(i, 0)));
        scale = std::max(scale, std::abs(e(i, 0)));
      }
      EXPECT_LE(worst, 1e-14 * scale) << "kind " << static_cast<int>(kind) << ", column " << j;
    }
  }
  // beta = 0 ignores Y's old values, NaN included.
  auto F = feti::makeDualOperator(f, feti::DualOperatorKind::F);
  MV W(f.dualMap(), 1);
  W.putScalar(std::nan(""));
  MV X1(f.dualMap(), 1);
  randomize(*X1.getVectorNonConst(0), 7);
  F->apply(X1, W, Teuchos::NO_TRANS, 1.0, 0.0);
  EXPECT_TRUE(std::isfinite(W.getVector(0)->norm2()));
  // Another map: refused on every rank.
  auto other = Teuchos::rcp(new Tpetra::Map<LO, GO>(f.dualMap()->getGlobalNumElements() + 3, 0, f.comm()));
  MV Xother(other, 1), Yother(other, 1);
  EXPECT_THROW(F->apply(Xother, Yother), std::invalid_argument);
  // A lumped or Dirichlet preconditioner is needed for P D P.
  auto plain = makeProblem("4x2x2", 2, false);
  EXPECT_THROW(feti::makeDualOperator(*plain->feti, feti::DualOperatorKind::PDP), std::invalid_argument);
}
