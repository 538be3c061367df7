#include "tribos/qp/VectorOps.hpp"

#include <Tpetra_Vector.hpp>

#include <algorithm>

#include "tribos/core/Parallel.hpp"

namespace tribos::qp {

namespace {
const double* readOnly(const Vector& v) { return v.getLocalViewHost(Tpetra::Access::ReadOnly).data(); }
double* readWrite(Vector& v) { return v.getLocalViewHost(Tpetra::Access::ReadWrite).data(); }
long lengthOf(const Vector& v) { return static_cast<long>(v.getLocalLength()); }

// y[i] = a x[i] + b y[i] for i in [begin, end), with KokkosBlas axpby's cases: a zero
// coefficient's term is left out (0 * inf would be NaN, and -0 + 0 would lose a sign).
void axpbyRange(double a, const double* x, double b, double* y, long begin, long end) {
  if (a == 0.0 && b == 0.0) {
    std::fill(y + begin, y + end, 0.0);
  } else if (a == 0.0) {
    if (b != 1.0)
      for (long i = begin; i < end; ++i) y[i] = b * y[i];
  } else if (b == 0.0) {
    for (long i = begin; i < end; ++i) y[i] = a * x[i];
  } else {
    for (long i = begin; i < end; ++i) y[i] = a * x[i] + b * y[i];
  }
}
}  // namespace

void assign(Vector& y, const Vector& x) {
  if (&x == &y) return;
  const double* xv = readOnly(x);
  double* yv = y.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
  core::forEachChunk(lengthOf(y), [&](long, long begin, long end) { std::copy(xv + begin, xv + end, yv + begin); });
}

void axpby(double a, const Vector& x, double b, Vector& y) {
  const double* xv = readOnly(x);
  double* yv = readWrite(y);
  core::forEachChunk(lengthOf(y), [&](long, long begin, long end) { axpbyRange(a, xv, b, yv, begin, end); });
}

void update(double a, const Vector& x, double b, const Vector& y, double c, Vector& z) {
  if (a == 0.0 || b == 0.0) {
    // One term of the two is left out: z = b y + c z or a x + c z, the axpby's arithmetic.
    if (a == 0.0) axpby(b, y, c, z);
    else axpby(a, x, c, z);
    return;
  }
  const double *xv = readOnly(x), *yv = readOnly(y);
  double* zv = readWrite(z);
  core::forEachChunk(lengthOf(z), [&](long, long begin, long end) {
    if (c == 0.0)
      for (long i = begin; i < end; ++i) zv[i] = a * xv[i] + b * yv[i];
    else
      for (long i = begin; i < end; ++i) zv[i] = a * xv[i] + b * yv[i] + c * zv[i];
  });
}

void stepAlong(double alpha, const Vector& p, const Vector& q, Vector& x, Vector& g) {
  const double a = -alpha;
  const double *pv = readOnly(p), *qv = readOnly(q);
  double *xv = readWrite(x), *gv = readWrite(g);
  core::forEachChunk(lengthOf(x), [&](long, long begin, long end) {
    axpbyRange(a, pv, 1.0, xv, begin, end);
    axpbyRange(a, qv, 1.0, gv, begin, end);
  });
}

void saveAndStep(double alpha, const Vector& p, Vector& x, const Vector& g, Vector& savedX, Vector& savedG) {
  const double a = -alpha;
  const double *pv = readOnly(p), *gv = readOnly(g);
  double* xv = readWrite(x);
  double *sx = savedX.getLocalViewHost(Tpetra::Access::OverwriteAll).data(),
         *sg = savedG.getLocalViewHost(Tpetra::Access::OverwriteAll).data();
  core::forEachChunk(lengthOf(x), [&](long, long begin, long end) {
    std::copy(xv + begin, xv + end, sx + begin);
    std::copy(gv + begin, gv + end, sg + begin);
    axpbyRange(a, pv, 1.0, xv, begin, end);
  });
}

}  // namespace tribos::qp
