#pragma once
// Internal to stack/: the right-hand side of each load step of a quasi-static history
// (ALGORITHMS.md 11). Step k scales every load and every prescribed value by its factor; the
// normal rows keep their gaps on the reference configuration; the tangential rows measure the
// slip increment since step k - 1: their c is shifted by the relative tangential displacement
// reached there, so Coulomb's and Tresca's laws act on the increment (friction with memory).
#include <vector>

#include "tribos/feti/ConstraintMatrix.hpp"

namespace tribos::feti {
class TotalFeti;
}

namespace tribos::stack {

class LoadHistory {
 public:
  /// `f0`: the full loads of the owned subdomains; B's c on this rank's rows is the full step.
  LoadHistory(const feti::ConstraintMatrix& B, int rank, std::vector<std::vector<double>> f0);

  /// f_s of the step at load factor `factor`.
  std::vector<std::vector<double>> loads(double factor) const;
  /// c on this rank's rows at `factor`: prescribed values scaled, gaps kept, the tangential rows
  /// shifted by the slip so far.
  std::vector<double> constraintValues(double factor) const;
  /// After a step at `factor` with displacements `u` (owned subdomains): the relative
  /// tangential displacement so far, T u - factor c0_T on the tangential rows. Collective.
  void advance(const feti::TotalFeti& feti, const std::vector<std::vector<double>>& u, double factor);

 private:
  std::vector<std::vector<double>> f0_;
  std::vector<double> c0_;       ///< B's c on the owned rows
  std::vector<double> fixed_;    ///< the part of c0 that no factor scales (the normal rows' gaps)
  std::vector<char> tangential_;  ///< owned row is a contact tangential row
  std::vector<double> slip_;     ///< relative tangential displacement so far (tangential rows)
};

}  // namespace tribos::stack
