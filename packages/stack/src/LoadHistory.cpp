#include "LoadHistory.hpp"

#include <Tpetra_Vector.hpp>

#include "tribos/feti/TotalFeti.hpp"

namespace tribos::stack {

LoadHistory::LoadHistory(const feti::ConstraintMatrix& B, int rank,
                         std::vector<std::vector<std::vector<double>>> loadVectors,
                         std::vector<std::vector<double>> factors, int steps, std::vector<size_t> dofs)
    : loadVectors_(std::move(loadVectors)), factors_(std::move(factors)), dofs_(std::move(dofs)), steps_(steps) {
  for (const auto& f : factors_)
    for (int k = 1; k <= steps_; ++k) proportional_ = proportional_ && f[k - 1] == ramp(k);
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  c0_.assign(B.c.begin() + first, B.c.begin() + end);
  fixed_.assign(c0_.size(), 0.0);
  tangential_.assign(c0_.size(), 0);
  slip_.assign(c0_.size(), 0.0);
  for (const auto& node : B.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;
    // The normal row's c = scale (d - known): the gap d stays (reference configuration), the
    // known (prescribed) part scales. A tied row has no gap in c and no slip to remember.
    if (B.interfaces.at(static_cast<size_t>(node.interface)).tied) continue;
    fixed_[static_cast<size_t>(node.normalRow - first)] = node.rowScale * node.gap;
    for (int j = 0; j < 2; ++j)
      if (const GO t = node.tangentialRow(j); t >= 0) tangential_[static_cast<size_t>(t - first)] = 1;
  }
}

std::vector<std::vector<double>> LoadHistory::loads(int k) const {
  std::vector<std::vector<double>> f;
  for (size_t n : dofs_) f.emplace_back(n, 0.0);
  for (size_t l = 0; l < loadVectors_.size(); ++l)
    for (size_t i = 0; i < f.size(); ++i)
      for (size_t d = 0; d < f[i].size(); ++d) f[i][d] += factors_[l][k - 1] * loadVectors_[l][i][d];
  return f;
}

std::vector<double> LoadHistory::constraintValues(int k) const {
  std::vector<double> c(c0_.size());
  for (size_t r = 0; r < c.size(); ++r) c[r] = fixed_[r] + ramp(k) * (c0_[r] - fixed_[r]) + slip_[r];
  return c;
}

void LoadHistory::advance(const feti::TotalFeti& feti, const std::vector<std::vector<double>>& u, int k) {
  auto Bu = feti.createDualVector();
  feti.applyB(u, *Bu);
  const auto bu = Bu->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t r = 0; r < slip_.size(); ++r)
    if (tangential_[r]) slip_[r] = bu(r, 0) - ramp(k) * c0_[r];
}

}  // namespace tribos::stack
