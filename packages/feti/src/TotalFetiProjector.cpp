// TotalFeti's projector P = I - G^T (G G^T)^-1 G, and the coarse coordinates of SMALSE-M's ||Q x||.
#include "TotalFetiParts.hpp"

namespace tribos::feti {

void TotalFeti::project(const DualVector& x, DualVector& y) const {
  // y = x - G^T (G G^T)^{-1} G x on the owned rows: x on the overlap rows (several ranks),
  // one all-reduce of length l, no allocation.
  const double* xd = readOnly(x);
  auto yView = [&]() { return &x == &y ? readWrite(y) : y.getLocalViewHost(Tpetra::Access::OverwriteAll).data(); };
  ++profile_.projections;
  core::Stopwatch watch;
  const int hit = findProjection(xd);
  if (hit >= 0) {
    // x has the bits of the memo's input: G^T a again with its a = (G G^T)^{-1} G x, the same
    // operations on the same numbers as the projection that stored it (the same bits), and
    // no copy of P x kept for the few projections that repeat (17 of 1140 on Table 1's
    // 10x5x5/5; the coarse coordinates, which repeat, need only gx and a).
    double* yd = yView();
    if (&x == &y) xd = yd;
    subtractGt(*G_, projectionMemo_[hit].coarse.data(), xd, yd, nullptr);
    ++profile_.projectionsReused;
    profile_.gSeconds += watch.seconds();
    return;
  }
  ProjectionMemo& memo = projectionMemo_[projectionMemoNext_];
  projectionMemoNext_ = (projectionMemoNext_ + 1) % kProjectionMemo;
  memo.valid = false;  // until its answer is stored below
  memo.rhs.resize(static_cast<size_t>(G_->numRows));  // filled by the G^T pass, before y (maybe x) is written
  applyGOwnedSubdomains(overlapValues(x), coarseLocal_.data());
  profile_.gSeconds += watch.seconds();
  watch.restart();
  reduceCoarse(coarseLocal_, coarseVector_.data());
  profile_.coarseReduceSeconds += watch.seconds();
  memo.gx.assign(coarseVector_.begin(), coarseVector_.end());
  solveCoarse(coarseVector_);
  memo.coarse.assign(coarseVector_.begin(), coarseVector_.end());
  watch.restart();
  double* yd = yView();
  if (&x == &y) xd = yd;
  subtractGt(*G_, coarseVector_.data(), xd, yd, memo.rhs.data());
  memo.valid = true;
  profile_.gSeconds += watch.seconds();
}

void TotalFeti::projectExactly(const DualVector& x, DualVector& y) const {
  if (!coarseFactored_) factorizeCoarse();
  if (!coarseSingle_) {
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

int TotalFeti::findProjection(const double* x) const {
  // Bitwise (memcmp): the copy is then exactly what the projection would compute. The
  // comparison stops at the first differing entry, so a miss costs next to nothing; all
  // ranks must agree (a hit skips the all-reduce of G x): one all-reduce of an int.
  const size_t bytes = sizeof(double) * static_cast<size_t>(G_->numRows);
  int local = -1;
  // Newest first: the entry a caller most likely means.
  for (int age = 1; age <= kProjectionMemo && local < 0; ++age) {
    const int k = (projectionMemoNext_ - age + kProjectionMemo) % kProjectionMemo;
    if (projectionMemo_[k].valid && (bytes == 0 || std::memcmp(x, projectionMemo_[k].rhs.data(), bytes) == 0)) local = k;
  }
  if (comm_->getSize() == 1) return local;
  // Agreement: the same entry on every rank (MIN of (k or none) and MAX agree).
  const int none = kProjectionMemo;
  int mine[2] = {local < 0 ? none : local, -(local < 0 ? none : local)}, all[2] = {0, 0};
  Teuchos::reduceAll(*comm_, Teuchos::REDUCE_MIN, 2, mine, all);
  return (all[0] == -all[1] && all[0] < none) ? all[0] : -1;
}

void TotalFeti::coarseCoordinates(const DualVector& x, std::vector<double>& gx, std::vector<double>& a) const {
  ++profile_.coarseCoordinates;
  const int hit = findProjection(readOnly(x));
  if (hit >= 0) {
    gx = projectionMemo_[hit].gx;
    a = projectionMemo_[hit].coarse;
    ++profile_.coarseCoordinatesReused;
    return;
  }
  applyG(x, gx);
  a = gx;
  solveCoarse(a);
}


}  // namespace tribos::feti
