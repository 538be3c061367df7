#include "tribos/feti/ProjectedCg.hpp"

#include <Tpetra_Vector.hpp>

#include <cmath>

#include "tribos/core/Errors.hpp"
#include "tribos/core/ReproducibleSum.hpp"

extern "C" void dstev_(const char* jobz, const int* n, double* d, double* e, double* z, const int* ldz,
                       double* work, int* info);

namespace tribos::feti {

namespace {
// a^T b, the same bits on any rank layout (core/ReproducibleSum.hpp).
double dot(const DualVector& a, const DualVector& b) {
  return core::reproducibleDot(a.getMap()->getComm().get(), a.getLocalViewHost(Tpetra::Access::ReadOnly).data(),
                               b.getLocalViewHost(Tpetra::Access::ReadOnly).data(), a.getLocalLength(),
                               static_cast<long long>(a.getGlobalLength()));
}
double norm2(const DualVector& x) { return std::sqrt(dot(x, x)); }
}  // namespace

std::pair<double, double> lanczosExtremes(const std::vector<double>& alpha, const std::vector<double>& beta) {
  // CG's Lanczos matrix: T_kk = 1/alpha_k + beta_{k-1}/alpha_{k-1}, T_k,k+1 = sqrt(beta_k)/alpha_k.
  const int k = static_cast<int>(alpha.size());
  if (k == 0) return {0.0, 0.0};
  std::vector<double> d(k), e(std::max(k - 1, 1));
  for (int i = 0; i < k; ++i) {
    d[i] = 1.0 / alpha[i] + (i > 0 ? beta[i - 1] / alpha[i - 1] : 0.0);
    if (i + 1 < k) e[i] = std::sqrt(beta[i]) / alpha[i];
  }
  int info = 0, ldz = 1;
  dstev_("N", &k, d.data(), e.data(), nullptr, &ldz, nullptr, &info);
  if (info != 0) return {0.0, 0.0};
  return {d.front(), d.back()};  // dstev returns ascending eigenvalues
}

ProjectedCgResult solveProjectedCg(const TotalFeti& feti, DualVector& lambda, const ProjectedCgSettings& settings) {
  const DualPreconditioner pc = settings.preconditioner;
  ProjectedCgResult result;
  const long long fStart = feti.fApplications();
  auto w = feti.createDualVector(), z = feti.createDualVector(), p = feti.createDualVector(),
       q = feti.createDualVector();
  // z = P M P w: the preconditioner acts on projected residuals and returns a vector of Ker G.
  auto precondition = [&](const DualVector& in, DualVector& out) {
    if (pc == DualPreconditioner::None) {
      out.assign(in);
      return;
    }
    DualVector tmp(in.getMap());
    if (pc == DualPreconditioner::Lumped) feti.applyLumped(in, tmp);
    else feti.applyDirichlet(in, tmp);
    feti.project(tmp, out);
  };

  // lambda_0 = lambda_Im satisfies G lambda = e; r_0 = d~ - F lambda_0, w_0 = P r_0 = P h.
  lambda.assign(feti.lambdaIm());
  feti.applyF(lambda, *q);
  w->assign(feti.dTilde());
  w->update(-1.0, *q, 1.0);
  feti.project(*w, *w);
  const double normPh = norm2(*w);
  if (normPh == 0.0) {
    result.converged = true;
    result.fApplications = feti.fApplications() - fStart;
    return result;
  }
  precondition(*w, *z);
  p->assign(*z);
  double wz = dot(*w, *z);
  std::vector<double> alphas, betas;
  double relative = 1.0;
  int it = 0;
  auto stopRequested = [&] { return settings.stopRequested && settings.stopRequested(); };
  for (; it < settings.maxIterations && relative > settings.tolerance && !stopRequested(); ++it) {
    feti.applyPF(*p, *q);  // p = P M P w lies in Ker G
    const double pq = dot(*p, *q);
    if (!(pq > 0.0)) break;  // breakdown: F not positive on Ker G (bad constraints)
    const double alpha = wz / pq;
    lambda.update(alpha, *p, 1.0);
    w->update(-alpha, *q, 1.0);
    relative = norm2(*w) / normPh;
    precondition(*w, *z);
    const double wzNew = dot(*w, *z);
    const double beta = wzNew / wz;
    wz = wzNew;
    alphas.push_back(alpha);
    betas.push_back(beta);
    p->update(1.0, *z, beta);
  }
  result.iterations = it;
  result.relativeResidual = relative;
  result.converged = relative <= settings.tolerance;
  if (!betas.empty()) betas.pop_back();  // the last beta belongs to a step not taken
  const auto [lo, hi] = lanczosExtremes(alphas, betas);
  result.lambdaMin = lo;
  result.lambdaMax = hi;
  result.conditionEstimate = lo > 0.0 ? hi / lo : 0.0;
  result.fApplications = feti.fApplications() - fStart;
  return result;
}

}  // namespace tribos::feti
