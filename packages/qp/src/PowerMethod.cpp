#include <Tpetra_Vector.hpp>

#include <cmath>

#include "tribos/qp/Mpgp.hpp"

namespace tribos::qp {

double powerMethod(const SymmetricOperator& A, const Map& map, int iterations, double tolerance,
                   long long* applications) {
  // A deterministic start in the global index, so every rank count gives the same estimate.
  Vector x(Teuchos::rcpFromRef(map)), y(Teuchos::rcpFromRef(map));
  {
    auto v = x.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < v.extent(0); ++i) {
      const auto g = static_cast<double>(map.getGlobalElement(static_cast<int>(i)));
      v(i, 0) = 1.0 + 0.5 * std::sin(0.7 * g + 0.3) + 0.25 * std::cos(1.9 * g);
    }
  }
  double norm = x.norm2(), estimate = 0.0;
  if (norm == 0.0) return 0.0;
  x.scale(1.0 / norm);
  for (int it = 0; it < iterations; ++it) {
    A.apply(x, y);
    if (applications) ++*applications;
    const double next = y.norm2();  // ||A x|| with ||x|| = 1
    if (next == 0.0) return 0.0;
    if (!std::isfinite(next)) return next;  // a NaN / Inf in A: the caller stops (no more products)
    x.update(1.0 / next, y, 0.0);
    const bool done = std::abs(next - estimate) <= tolerance * next;
    estimate = next;
    if (done) break;
  }
  return estimate;
}

}  // namespace tribos::qp
