#pragma once
/// \file Format.hpp
/// Numbers and points in messages: 10 significant digits (std::to_string prints 1e-7 as
/// "0.000000", which hides the very values an error message is about).
#include <array>
#include <sstream>
#include <string>

namespace tribos::core {

inline std::string formatNumber(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

/// "(x, y, z)".
inline std::string formatPoint(const std::array<double, 3>& x) {
  return "(" + formatNumber(x[0]) + ", " + formatNumber(x[1]) + ", " + formatNumber(x[2]) + ")";
}

}  // namespace tribos::core
