#include "tribos/stack/LoadHistory.hpp"

#include <algorithm>
#include <cmath>

#include <Tpetra_Vector.hpp>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Format.hpp"
#include "tribos/feti/TotalFeti.hpp"

namespace tribos::stack {

LoadHistory::LoadHistory(const feti::ConstraintMatrix& B, int rank, const Scene& scene,
                         std::vector<std::vector<std::vector<double>>> loadVectors, std::vector<size_t> dofs)
    : loadVectors_(std::move(loadVectors)),
      factors_(scene.loadFactors),
      displacementFactors_(scene.displacementFactors),
      dofs_(std::move(dofs)),
      steps_(scene.loadSteps) {
  for (const auto& load : scene.namedLoads) loadNames_.push_back(load.first);
  for (const auto& condition : scene.displacementConditions) {
    conditionNames_.push_back(condition.name);
    // A condition of zero values (a clamp, a symmetry plane) has no factor worth naming.
    nonZero_.push_back(std::any_of(condition.value.begin(), condition.value.end(), [](double v) { return v != 0.0; }));
  }
  for (const auto& active : scene.conditionActive)
    switched_.push_back(std::count(active.begin(), active.end(), 0) > 0 ? active : std::vector<char>());
  for (const auto& [i, j] : B.overlappingConditions)
    core::requireInput(displacementFactors_[i] == displacementFactors_[j],
                       "Load Steps: Boundary/" + conditionNames_[i] + " and Boundary/" + conditionNames_[j] +
                           " prescribe the same component of a node and have different factors (give them one "
                           "table, or let one condition prescribe that component)");
  for (const auto* table : {&factors_, &displacementFactors_})
    for (const auto& f : *table)
      for (int k = 1; k <= steps_; ++k) proportional_ = proportional_ && f[k - 1] == ramp(k);
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  fixed_.assign(B.c.begin() + first, B.c.begin() + end);
  for (const auto& part : B.prescribedParts) {
    if (part.row < first || part.row >= end) continue;
    fixed_[static_cast<size_t>(part.row - first)] -= part.value;
    parts_.push_back({part.row - first, part.condition, part.value});
  }
  addSections(B, first, end, scene);
  tangential_.assign(fixed_.size(), 0);
  slip_.assign(fixed_.size(), 0.0);
  for (const auto& node : B.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;
    // The Interference part of the gap (c = rowScale (gap - interference)) follows the ramp.
    if (node.interference != 0.0) {
      const double part = -node.rowScale * node.interference;
      fixed_[static_cast<size_t>(node.normalRow - first)] -= part;
      interference_.push_back({node.normalRow - first, part});
    }
    // A tied row has no slip to remember (its rows are equalities in every step).
    if (B.interfaces.at(static_cast<size_t>(node.interface)).tied) continue;
    for (int j = 0; j < 2; ++j)
      if (const GO t = node.tangentialRow(j); t >= 0) tangential_[static_cast<size_t>(t - first)] = 1;
  }
}

void LoadHistory::addSections(const feti::ConstraintMatrix& B, GO first, GO end, const Scene& scene) {
  sections_ = scene.pretensions;
  proportional_ = proportional_ && sections_.empty();  // a pretension is no ramped load
  for (const auto& section : sections_) {
    std::vector<std::pair<size_t, double>> rows;
    long long count = 0;
    std::array<double, 3> low{HUGE_VAL, HUGE_VAL, HUGE_VAL}, high{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (const auto& node : B.contact) {
      if (node.interface != static_cast<int>(section.interface)) continue;
      ++count;
      for (int c = 0; c < 3; ++c) {
        low[c] = std::min(low[c], scene.mesh.coords[static_cast<size_t>(node.slaveNode)][c]);
        high[c] = std::max(high[c], scene.mesh.coords[static_cast<size_t>(node.slaveNode)][c]);
      }
      if (node.normalRow >= first && node.normalRow < end)
        rows.push_back({static_cast<size_t>(node.normalRow - first), node.rowScale});
    }
    core::requireInput(count > 0, "Pretension/" + section.name + "/Interface: Contact/" +
                                      scene.contacts[section.interface].rows.name +
                                      " pairs no slave node, so the section has no rows to pull (check its side sets "
                                      "and Search Distance)");
    sectionRows_.push_back(std::move(rows));
    sectionRowCount_.push_back(count);
    sectionSize_.push_back(count > 0 ? std::hypot(high[0] - low[0], high[1] - low[1], high[2] - low[2]) : 0.0);
  }
  shortening_.assign(sections_.size(), 0.0);
  slope_.assign(sections_.size(), 0.0);
}

void LoadHistory::setSectionsAt(double position) {
  for (size_t p = 0; p < sections_.size(); ++p)
    if (!sections_[p].byForce)
      shortening_[p] = sections_[p].target * std::min(position / sections_[p].steps, 1.0);
}

std::vector<std::pair<std::string, double>> LoadHistory::factors(int k) const {
  std::vector<std::pair<std::string, double>> out;
  for (size_t l = 0; l < loadNames_.size(); ++l) out.push_back({loadNames_[l], factors_[l][k - 1]});
  for (size_t j = 0; j < conditionNames_.size(); ++j)
    if (nonZero_[j]) out.push_back({conditionNames_[j], displacementFactors_[j][k - 1]});
  return out;
}

std::string LoadHistory::label(int k) const {
  std::string text;
  if (proportional_) text = "ramp " + core::formatNumber(ramp(k));
  else
    for (const auto& [name, factor] : factors(k))
      text += (text.empty() ? "" : ", ") + name + " " + core::formatNumber(factor);
  // A condition switched between steps (Load Steps/<name>/Active): whether it holds.
  for (size_t j = 0; j < switched_.size(); ++j)
    if (!switched_[j].empty())
      text += (text.empty() ? "" : ", ") + conditionNames_[j] + (switched_[j][static_cast<size_t>(k - 1)] ? " on" : " off");
  return text;
}

namespace {
/// A factor table's value at `position`: its entry k - 1 at step k, linear in between, 0 before
/// step 1 (the unloaded start).
double factorAt(const std::vector<double>& table, double position) {
  const int k = static_cast<int>(std::ceil(position));
  const double after = table[static_cast<size_t>(k - 1)];
  const double s = position - (k - 1);
  if (s == 1.0) return after;  // a whole step: the table's value itself
  const double before = k >= 2 ? table[static_cast<size_t>(k - 2)] : 0.0;
  return before + s * (after - before);
}
}  // namespace

std::vector<std::vector<double>> LoadHistory::loads(double position) const {
  std::vector<std::vector<double>> f;
  for (size_t n : dofs_) f.emplace_back(n, 0.0);
  for (size_t l = 0; l < loadVectors_.size(); ++l) {
    const double factor = factorAt(factors_[l], position);
    for (size_t i = 0; i < f.size(); ++i)
      for (size_t d = 0; d < f[i].size(); ++d) f[i][d] += factor * loadVectors_[l][i][d];
  }
  return f;
}

std::vector<double> LoadHistory::prescribedValues(double position) const {
  std::vector<double> c(fixed_);
  for (const auto& part : parts_)
    c[static_cast<size_t>(part.row)] +=
        factorAt(displacementFactors_[static_cast<size_t>(part.condition)], position) * part.value;
  for (const auto& [row, part] : interference_) c[static_cast<size_t>(row)] += ramp(position) * part;
  // A section's normal rows read (u_s - chi u_m) . nu = shortening (tied rows otherwise 0).
  for (size_t p = 0; p < sections_.size(); ++p)
    for (const auto& [row, scale] : sectionRows_[p]) c[row] += scale * shortening_[p];
  return c;
}

std::vector<double> LoadHistory::constraintValues(double position) const {
  std::vector<double> c = prescribedValues(position);
  for (size_t r = 0; r < c.size(); ++r) c[r] += slip_[r];
  return c;
}

void LoadHistory::advance(const feti::TotalFeti& feti, const std::vector<std::vector<double>>& u, double position) {
  auto Bu = feti.createDualVector();
  feti.applyB(u, *Bu);
  const auto bu = Bu->getLocalViewHost(Tpetra::Access::ReadOnly);
  const std::vector<double> c = prescribedValues(position);
  for (size_t r = 0; r < slip_.size(); ++r)
    if (tangential_[r]) slip_[r] = bu(r, 0) - c[r];
}

void LoadHistory::restore(const feti::ConstraintMatrix& B, int rank, const std::vector<double>& t1,
                          const std::vector<double>& t2) {
  const GO first = B.firstRowOfRank[rank], end = B.firstRowOfRank[rank + 1];
  for (const auto& node : B.contact) {
    if (node.normalRow < first || node.normalRow >= end) continue;
    for (int j = 0; j < 2; ++j) {
      const GO t = node.tangentialRow(j);
      if (t < 0 || !tangential_[static_cast<size_t>(t - first)]) continue;
      // The row measures tangentialScale (u_slave - chi u_master) . t_j (ConstraintMatrix.hpp).
      slip_[static_cast<size_t>(t - first)] =
          node.tangentialScale[j] * (j == 0 ? t1 : t2)[static_cast<size_t>(node.slaveNode)];
    }
  }
}

}  // namespace tribos::stack
