#include <algorithm>
#include <cmath>

#include "tribos/fem/SubdomainSystem.hpp"

namespace tribos::fem {

void CsrMatrix::apply(const double* x, double* y) const {
  for (LO i = 0; i < n; ++i) {
    double s = 0.0;
    for (LO k = rowPtr[i]; k < rowPtr[i + 1]; ++k) s += values[k] * x[colInd[k]];
    y[i] = s;
  }
}

double CsrMatrix::frobeniusNorm() const {
  double s = 0.0;
  for (double v : values) s += v * v;
  return std::sqrt(s);
}

double CsrMatrix::at(LO i, LO j) const {
  const auto first = colInd.begin() + rowPtr[i], last = colInd.begin() + rowPtr[i + 1];
  const auto it = std::lower_bound(first, last, j);
  return it != last && *it == j ? values[it - colInd.begin()] : 0.0;
}

}  // namespace tribos::fem
