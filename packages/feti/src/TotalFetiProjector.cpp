// TotalFeti's projector P = I - G^T (G G^T)^-1 G, the coarse coordinates of SMALSE-M's ||Q x||,
// and the coarse solves it makes with its CoarseProblem.
#include "CoarseProblem.hpp"
#include "TotalFetiParts.hpp"

namespace tribos::feti {

void TotalFeti::solveCoarse(std::vector<double>& a) const { coarse_->solve(a); }

void TotalFeti::solveCoarseExactly(std::vector<double>& a) const {
  // Products G G^T x as G (G^T x) for the refinement of a single-precision factor's solves.
  coarse_->solveExactly(a, [this](const std::vector<double>& x, std::vector<double>& y) {
    DualVector v(dualMap_);
    applyGt(x, v);
    applyG(v, y);
  });
}

void TotalFeti::releaseCoarseFactor() const {
  if (!keepCoarseFactor_) coarse_->release();
}

void TotalFeti::project(const DualVector& x, DualVector& y, CoarseCoordinates* ofX) const {
  // y = x - G^T (G G^T)^{-1} G x on the owned rows: x on the overlap rows (several ranks),
  // one all-reduce of length l, no allocation.
  ++profile_.projections;
  core::Stopwatch watch;
  applyGOwnedSubdomains(overlapValues(x), coarseLocal_.data());
  profile_.gSeconds += watch.seconds();
  watch.restart();
  reduceCoarse(coarseLocal_, coarseVector_.data());
  profile_.coarseReduceSeconds += watch.seconds();
  if (ofX) ofX->gx.assign(coarseVector_.begin(), coarseVector_.end());
  solveCoarse(coarseVector_);
  if (ofX) ofX->a.assign(coarseVector_.begin(), coarseVector_.end());
  watch.restart();
  const double* xd = readOnly(x);
  double* yd = &x == &y ? readWrite(y) : y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
  if (&x == &y) xd = yd;
  subtractGt(*G_, coarseVector_.data(), xd, yd);
  profile_.gSeconds += watch.seconds();
}

void TotalFeti::projectExactly(const DualVector& x, DualVector& y) const {
  if (!coarse_->single()) {
    project(x, y);  // exact already
    return;
  }
  std::vector<double> a;
  applyG(x, a);
  solveCoarseExactly(a);
  DualVector gta(dualMap_);
  applyGt(a, gta);
  y.update(1.0, x, -1.0, gta, 0.0);
}

void TotalFeti::coarseCoordinates(const DualVector& x, std::vector<double>& gx, std::vector<double>& a) const {
  ++profile_.coarseCoordinates;
  applyG(x, gx);
  a = gx;
  solveCoarse(a);
}


}  // namespace tribos::feti
