#pragma once
// Internal to stack/: the right-hand side of each load step of a quasi-static history
// (ALGORITHMS.md 11). Step k scales each named load by its factor (Scene::loadFactors) and each
// displacement condition's part of c (feti::PrescribedPart) by its factor
// (Scene::displacementFactors); the normal rows keep their gaps on the reference
// configuration, less an interface's Interference times the ramp k / N; the tangential rows measure the slip increment since step k - 1: their c is
// shifted by the relative tangential displacement reached there, so Coulomb's and Tresca's laws
// act on the increment (friction with memory).
#include <string>
#include <utility>
#include <vector>

#include "tribos/feti/ConstraintMatrix.hpp"
#include "tribos/stack/Scene.hpp"

namespace tribos::feti {
class TotalFeti;
}

namespace tribos::stack {

class LoadHistory {
 public:
  /// `loadVectors[l][i]`: the scene's named load l (Scene::namedLoads) assembled on owned
  /// subdomain i; the factors of the loads and displacement conditions are the scene's
  /// (Scene::loadFactors, Scene::displacementFactors). B's c on this rank's rows holds the full
  /// prescribed values. `dofs[i]`: the size of owned subdomain i's f_s (a history may have no
  /// load at all: prescribed displacements alone). Throws core::InputError where two conditions
  /// prescribing one component have different factors (B.overlappingConditions).
  LoadHistory(const feti::ConstraintMatrix& B, int rank, const Scene& scene,
              std::vector<std::vector<std::vector<double>>> loadVectors, std::vector<size_t> dofs);

  int steps() const { return steps_; }
  /// The ramp k / N: the prescribed values' factor in step k (and a load's without a table); at
  /// a position between steps (a cut-back sub-step), position / N.
  double ramp(double position) const { return position / steps_; }
  /// Every load and prescribed displacement follows the ramp (a proportional history).
  bool proportional() const { return proportional_; }
  /// Each load's and displacement condition's factor in step k, by name (Loads/<name>,
  /// Boundary/<name>); conditions of zero values (clamps, symmetry planes) are left out.
  std::vector<std::pair<std::string, double>> factors(int k) const;
  /// Step k in words: "ramp r" for a proportional history, else each factor ("press 1, shear -1"),
  /// and whether each condition switched between steps holds ("grip on", "grip off").
  std::string label(int k) const;
  /// f_s at `position` in steps: step k at k (1-based); between steps k - 1 and k (a cut-back
  /// sub-step) every factor interpolated linearly, from 0 before step 1.
  std::vector<std::vector<double>> loads(double position) const;
  /// c on this rank's rows at `position`: prescribed values at their factors, gaps kept, the
  /// tangential rows shifted by the slip so far.
  std::vector<double> constraintValues(double position) const;
  /// After the state at `position` with displacements `u` (owned subdomains): the relative
  /// tangential displacement so far, T u - (c without the slip) on the tangential rows. Collective.
  void advance(const feti::TotalFeti& feti, const std::vector<std::vector<double>>& u, double position);
  /// A restart (Load Steps/Restart From): the relative tangential displacement reached so far,
  /// per global node along each contact node's t1 and t2 (the result's contact_tangential_t1/t2).
  void restore(const feti::ConstraintMatrix& B, int rank, const std::vector<double>& t1, const std::vector<double>& t2);

  /// Pretension sections (Scene::pretensions, Pretension.hpp): their shortening, in c of their
  /// normal rows (shortening x rowScale). A Shortening section is at its target x min(position /
  /// steps, 1) by itself (setSectionsAt); a Force section at what the iterations set, kept after
  /// its steps (locked).
  size_t sections() const { return sections_.size(); }
  const PretensionSection& section(size_t p) const { return sections_[p]; }
  double shortening(size_t p) const { return shortening_[p]; }
  void setShortening(size_t p, double s) { shortening_[p] = s; }
  /// dF/ds of section p as the last iterations measured it (0: not yet).
  double slope(size_t p) const { return slope_[p]; }
  void setSlope(size_t p, double k) { slope_[p] = k; }
  /// Sets the Shortening sections' values at `position`.
  void setSectionsAt(double position);
  /// The section's normal rows on this rank: (owned row, rowScale).
  const std::vector<std::pair<size_t, double>>& sectionRows(size_t p) const { return sectionRows_[p]; }
  /// The number of normal rows of section p over all ranks (a reproducible sum's bound).
  long long sectionRowCount(size_t p) const { return sectionRowCount_[p]; }
  /// The diagonal of the bounding box of section p's slave nodes (a length scale for its first
  /// shortening, Pretension.cpp).
  double sectionSize(size_t p) const { return sectionSize_[p]; }

 private:
  std::vector<std::vector<std::vector<double>>> loadVectors_;
  std::vector<std::string> loadNames_, conditionNames_;
  std::vector<char> nonZero_;  ///< per condition: some Displacement component is not zero
  std::vector<std::vector<char>> switched_;  ///< per condition: its Active flags, empty when it holds throughout
  std::vector<std::vector<double>> factors_;
  std::vector<std::vector<double>> displacementFactors_;
  std::vector<size_t> dofs_;
  int steps_ = 1;
  bool proportional_ = true;
  void addSections(const feti::ConstraintMatrix& B, GO first, GO end, const Scene& scene);
  std::vector<PretensionSection> sections_;
  std::vector<std::vector<std::pair<size_t, double>>> sectionRows_;
  std::vector<long long> sectionRowCount_;
  std::vector<double> sectionSize_;
  std::vector<double> shortening_;  ///< per section, the value c holds now
  std::vector<double> slope_;       ///< per section, dF/ds
  std::vector<double> fixed_;     ///< the part of B's c that no factor scales (the normal rows' gaps)
  std::vector<feti::PrescribedPart> parts_;  ///< the owned rows' parts, rows counted from the first owned
  /// (owned row, its c's Interference part at the full value): normal rows, ramped (k / N).
  std::vector<std::pair<GO, double>> interference_;
  /// c on the owned rows at `position` without the slip: the fixed part and the factored parts.
  std::vector<double> prescribedValues(double position) const;
  std::vector<char> tangential_;  ///< owned row is a contact tangential row (not tied)
  std::vector<double> slip_;      ///< relative tangential displacement so far (tangential rows)
};

}  // namespace tribos::stack
