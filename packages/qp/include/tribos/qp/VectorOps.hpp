#pragma once
/// \file VectorOps.hpp
/// Element-wise operations on the local entries of dual vectors, on the threads of
/// core::forEachChunk over its fixed chunks (issue 9: MPGP's vector work was single-threaded
/// Tpetra calls, a pass over the vector each). Every entry is computed by the same floating
/// point operations as Tpetra's update / assign (KokkosBlas axpby and update:
/// a x + b y, then + c z, a term with a zero coefficient left out), so the results have
/// Tpetra's bits on any number of threads. The file is compiled without fused multiply-add.
#include "tribos/qp/DualTypes.hpp"

namespace tribos::qp {

/// y = x.
void assign(Vector& y, const Vector& x);
/// y = a x + b y (Tpetra's y.update(a, x, b)).
void axpby(double a, const Vector& x, double b, Vector& y);
/// z = a x + b y + c z (Tpetra's z.update(a, x, b, y, c)).
void update(double a, const Vector& x, double b, const Vector& y, double c, Vector& z);
/// x = -alpha p + x and g = -alpha q + g in one pass (MPGP's steps along p, with q = A p):
/// the bits of x.update(-alpha, p, 1) and g.update(-alpha, q, 1).
void stepAlong(double alpha, const Vector& p, const Vector& q, Vector& x, Vector& g);
/// savedX = x, savedG = g, then x = -alpha p + x, in one pass (a step that may be undone).
void saveAndStep(double alpha, const Vector& p, Vector& x, const Vector& g, Vector& savedX, Vector& savedG);

}  // namespace tribos::qp
