#include "tribos/qp/Reductions.hpp"

#include <Tpetra_Vector.hpp>

#include <cmath>

#include "tribos/core/ReproducibleSum.hpp"

namespace tribos::qp {

namespace {
const double* values(const Vector& v) { return v.getLocalViewHost(Tpetra::Access::ReadOnly).data(); }
const Teuchos::Comm<int>* commOf(const Vector& v) { return v.getMap()->getComm().get(); }
// Global number of entries: the same on every layout.
long long countOf(const Vector& v) { return static_cast<long long>(v.getGlobalLength()); }
}  // namespace

double dot(const Vector& a, const Vector& b) {
  return core::reproducibleDot(commOf(a), values(a), values(b), a.getLocalLength(), countOf(a));
}

double norm2(const Vector& x) {
  const double* v = values(x);
  return std::sqrt(core::reproducibleDot(commOf(x), v, v, x.getLocalLength(), countOf(x)));
}

std::array<double, 2> dots(const Vector& a, const Vector& b, const Vector& c, const Vector& d) {
  std::array<double, 2> out{};
  core::reproducibleDots(commOf(a), values(a), values(b), values(c), values(d), a.getLocalLength(), countOf(a),
                         out.data());
  return out;
}

std::array<double, 3> dots(const Vector& a, const Vector& b, const Vector& c, const Vector& d, const Vector& e,
                           const Vector& f) {
  const double* left[3] = {values(a), values(c), values(e)};
  const double* right[3] = {values(b), values(d), values(f)};
  std::array<double, 3> out{};
  core::reproducibleDots(commOf(a), left, right, 3, a.getLocalLength(), countOf(a), out.data());
  return out;
}

double sumOver(const Vector& x, const double* terms, std::size_t n, long long count) {
  return core::reproducibleSum(commOf(x), terms, n, count);
}

}  // namespace tribos::qp
