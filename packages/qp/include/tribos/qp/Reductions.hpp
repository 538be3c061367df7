#pragma once
/// \file Reductions.hpp
/// Dot products and norms of dual vectors whose bits do not depend on the rank layout
/// (core/ReproducibleSum.hpp): every sum that steers MPGP and SMALSE-M goes through these
/// instead of Tpetra's dot / norm2, whose rounding follows the split of the rows over ranks.
#include <array>

#include "tribos/qp/DualTypes.hpp"

namespace tribos::qp {

/// a^T b over all ranks.
double dot(const Vector& a, const Vector& b);
/// ||x||_2 over all ranks.
double norm2(const Vector& x);
/// {a^T b, c^T d} with the all-reduces of both shared (one MAX, one SUM); each result has
/// the bits of dot() alone, so batching changes no iterate.
std::array<double, 2> dots(const Vector& a, const Vector& b, const Vector& c, const Vector& d);
/// {a^T b, c^T d, e^T f}, the same way.
std::array<double, 3> dots(const Vector& a, const Vector& b, const Vector& c, const Vector& d, const Vector& e,
                           const Vector& f);
/// sum of every rank's terms[0..n) over x's communicator; `count` bounds the number of
/// terms over all ranks and must be the same on every rank (e.g. x's global length).
double sumOver(const Vector& x, const double* terms, std::size_t n, long long count);

}  // namespace tribos::qp
