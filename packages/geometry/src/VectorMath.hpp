#pragma once
/// \file VectorMath.hpp
/// The few 3-vector operations the contact geometry uses (private to the package).
#include <array>
#include <cmath>

namespace tribos::geometry {

inline double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
inline std::array<double, 3> minus(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline double norm(const std::array<double, 3>& v) { return std::sqrt(dot(v, v)); }

}  // namespace tribos::geometry
