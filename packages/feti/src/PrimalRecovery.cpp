// The primal recovery (PrimalRecovery.hpp): alpha from lambda (paper (14)), u, B u and the
// residuals of the discrete problem.
#include "PrimalRecovery.hpp"

#include "CoarseProblem.hpp"

namespace tribos::feti {

namespace {
/// Below this reciprocal condition estimate G_I G_I^T counts as singular (rigidBodyCoefficients).
constexpr double kSingularReciprocalCondition = 1e-10;
}  // namespace

PrimalRecovery::PrimalRecovery(const SubdomainSet& subdomains, const CoarseSpace& coarse,
                               const TotalFetiSettings& settings)
    : subdomains_(subdomains), coarse_(coarse), settings_(settings) {}

std::vector<double> PrimalRecovery::rigidBodyCoefficients(DualVector& residual, const std::vector<char>& ownedRowMask,
                                                          const std::vector<TotalFeti::RowCombination>& combinations) const {
  TEUCHOS_TEST_FOR_EXCEPTION(ownedRowMask.size() != static_cast<size_t>(coarse_.rows().numRows), std::invalid_argument,
                             "tribos::feti::TotalFeti::rigidBodyCoefficients: the mask has "
                                 << ownedRowMask.size() << " entries, this rank owns " << coarse_.rows().numRows
                                 << " rows");
  {
    // G_I^T alpha = (F lambda - d~)_I; a combination w contributes w (w . (F lambda - d~)_{a,b}).
    auto data = residual.getLocalViewHost(Tpetra::Access::ReadWrite);
    std::vector<double> combined(combinations.size());
    for (size_t k = 0; k < combinations.size(); ++k) {
      const auto& c = combinations[k];
      combined[k] = coarse_.problem().sameSubdomains(c.a, c.b) ? c.wa * data(c.a, 0) + c.wb * data(c.b, 0) : 0.0;
    }
    for (size_t i = 0; i < data.extent(0); ++i)
      if (!ownedRowMask[i]) data(i, 0) = 0.0;
    for (size_t k = 0; k < combinations.size(); ++k) {
      data(combinations[k].a, 0) += combinations[k].wa * combined[k];
      data(combinations[k].b, 0) += combinations[k].wb * combined[k];
    }
  }
  std::vector<double> alpha;
  coarse_.applyG(residual, alpha);
  // Assembled, factorised and solved on rank 0 (as G G^T: onRootThenBroadcast).
  fem::CsrMatrix GiGit = coarse_.problem().assemble(&ownedRowMask, combinations.empty() ? nullptr : &combinations);
  onRootThenBroadcast(
      *subdomains_.comm(), alpha,
      [&] {
        auto factor = makeSparseCholesky(settings_.factorization, settings_.factorOptions);
        try {
          factor->factorizeConsuming(std::move(GiGit));
        } catch (const std::exception& e) {
          throw RigidMotionsUndetermined(
              std::string("tribos::feti::TotalFeti::rigidBodyCoefficients: G_I G_I^T is singular "
                          "(the inactive rows do not fix every rigid body mode): ") +
              e.what());
        }
        // Singular in exact arithmetic, the pivots can stay positive in round-off: the block
        // under the three bodies' punch, sliding everywhere, gave 1.7e-16 (a proper G_I G_I^T
        // there and on the bricks and Hertz scenes: 5e-3 to 3e-2); alpha would then take any
        // value along the free motions.
        const double rcond = factor->reciprocalCondition();
        if (!(rcond >= kSingularReciprocalCondition))
          throw RigidMotionsUndetermined(
              "tribos::feti::TotalFeti::rigidBodyCoefficients: G_I G_I^T is numerically singular (reciprocal "
              "condition estimate " + std::to_string(rcond) + "): the inactive rows do not fix every rigid body mode");
        std::vector<double> rhs = alpha;
        factor->solve(rhs.data(), alpha.data());
      },
      [](const std::string& message) { throw RigidMotionsUndetermined(message); });
  return alpha;
}

void PrimalRecovery::applyB(const std::vector<std::vector<double>>& u, DualVector& y) const {
  const int first = subdomains_.firstOwned();
  subdomains_.applyBlockwise(y, y, [&u, first](OwnedSubdomain& L, bool) {
    applyBlock(*L.block, u[L.subdomain - first].data(), L.out.data());
  });
}

double PrimalRecovery::equilibriumResidual(const DualVector& lambda, const std::vector<std::vector<double>>& u,
                                      double* forceScale) const {
  const double* lo = subdomains_.overlapValues(lambda);
  double worst[2] = {0.0, 0.0}, global[2] = {0.0, 0.0};  // the residual, the largest force
  for (int i = 0; i < subdomains_.numOwned(); ++i) {
    OwnedSubdomain& L = subdomains_.owned(i);
    for (LO r = 0; r < L.m(); ++r) L.in[r] = lo[L.overlapIndex[r]];
    applyBlockTranspose(*L.block, L.rowOrder, L.in.data(), L.x.data(), L.n());
    L.system.K.apply(u[i].data(), L.y.data());
    // A NaN anywhere stays a NaN (std::max would drop it): never a residual of 0 for it.
    auto keepLarger = [](double& largest, double v) {
      if (!(v <= largest)) largest = v;
    };
    const fem::CsrMatrix& K = L.system.K;
    for (LO k = 0; k < L.n(); ++k) {
      keepLarger(worst[0], std::abs(L.y[k] - L.system.f[k] + L.x[k]));
      // The size of the internal force's terms sum_j |K_kj u_j| too: a body moved rigidly by a
      // prescribed displacement with nothing touching has K u = 0 to round-off of them, and
      // neither loads nor multipliers to measure that round-off against.
      double terms = 0.0;
      for (LO e = K.rowPtr[k]; e < K.rowPtr[k + 1]; ++e) terms += std::abs(K.values[e] * u[i][K.colInd[e]]);
      keepLarger(worst[1], std::max({std::abs(L.system.f[k]), std::abs(L.x[k]), terms}));
    }
  }
  Teuchos::reduceAll(*subdomains_.comm(), Teuchos::REDUCE_MAX, 2, worst, global);
  if (forceScale) *forceScale = global[1];
  return global[0];
}

double PrimalRecovery::energy(const std::vector<std::vector<double>>& u) const {
  // One term per dof, summed independently of the layout (core::ReproducibleSum.hpp).
  std::vector<double> terms;
  for (int i = 0; i < subdomains_.numOwned(); ++i) {
    OwnedSubdomain& L = subdomains_.owned(i);
    L.system.K.apply(u[i].data(), L.y.data());
    for (LO k = 0; k < L.n(); ++k) terms.push_back(0.5 * u[i][k] * L.y[k] - L.system.f[k] * u[i][k]);
  }
  return core::reproducibleSum(subdomains_.comm().get(), terms.data(), terms.size(), subdomains_.primalDofs());
}

double PrimalRecovery::loadNormInf() const {
  double local = 0.0;
  for (const auto& L : subdomains_.all())
    for (double v : L->system.f) local = std::max(local, std::abs(v));
  double global = 0.0;
  Teuchos::reduceAll(*subdomains_.comm(), Teuchos::REDUCE_MAX, 1, &local, &global);
  return global;
}

std::vector<std::vector<double>> PrimalRecovery::recoverDisplacements(const DualVector& lambda,
                                                                      const std::vector<double>& alpha) const {
  const double* lo = subdomains_.overlapValues(lambda);
  std::vector<std::vector<double>> u(subdomains_.numOwned());
  core::forEachSubdomain(subdomains_.numOwned(), [&](int i) {
    OwnedSubdomain& L = subdomains_.owned(i);
    const LO n = L.n();
    for (LO r = 0; r < L.m(); ++r) L.in[r] = lo[L.overlapIndex[r]];
    applyBlockTranspose(*L.block, L.rowOrder, L.in.data(), L.x.data(), n);
    for (LO k = 0; k < n; ++k) L.x[k] = L.system.f[k] - L.x[k];
    u[i].assign(n, 0.0);
    L.solver.applyPseudoInverse(L.x.data(), u[i].data());
    for (LO k = 0; k < n; ++k)
      for (int j = 0; j < 6; ++j) u[i][k] += L.system.R[static_cast<size_t>(j) * n + k] * alpha[6 * L.subdomain + j];
  });
  return u;
}


std::vector<EliminatedReaction> PrimalRecovery::eliminatedReactions(const std::vector<std::vector<double>>& u) const {
  std::vector<EliminatedReaction> out;
  for (int i = 0; i < subdomains_.numOwned(); ++i) {
    const OwnedSubdomain& L = subdomains_.owned(i);
    const std::vector<double> force = feti::eliminatedReactions(L.eliminated, u[i]);
    for (size_t k = 0; k < force.size(); ++k) out.push_back({L.subdomain, L.eliminated.dof[k], force[k]});
  }
  return out;
}

}  // namespace tribos::feti
