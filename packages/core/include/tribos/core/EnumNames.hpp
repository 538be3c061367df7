#pragma once
/// \file EnumNames.hpp
/// An option's names and values in one table: the parameter list declares the names
/// (ParameterTable, Teuchos's string-to-integral validator), a validated list is turned into
/// the value once, and messages and the printed solver chain name the value from the same
/// table. After validation no option is compared as a string.
///
///   enum class FixedPoint { Inexact, Exact };
///   inline constexpr core::EnumNames<FixedPoint, 2> kFixedPointNames{{{"Inexact", FixedPoint::Inexact},
///                                                                     {"Exact", FixedPoint::Exact}}};
#include <array>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace tribos::core {

template <class E, std::size_t N>
using EnumNames = std::array<std::pair<const char*, E>, N>;

/// The name of `value` in `names`.
template <class E, std::size_t N>
const char* nameOf(const EnumNames<E, N>& names, E value) {
  for (const auto& [name, v] : names)
    if (v == value) return name;
  throw std::logic_error("tribos::core::nameOf: a value without a name");
}

/// The value named `name`; std::invalid_argument listing the names otherwise (a validated
/// list never gets there).
template <class E, std::size_t N>
E valueOf(const EnumNames<E, N>& names, const std::string& name) {
  std::string valid;
  for (const auto& [n, v] : names) {
    if (name == n) return v;
    valid += std::string(valid.empty() ? "" : ", ") + "\"" + n + "\"";
  }
  throw std::invalid_argument("\"" + name + "\" is not one of " + valid);
}

/// Every name, in the table's order.
template <class E, std::size_t N>
std::vector<std::string> namesOf(const EnumNames<E, N>& names) {
  std::vector<std::string> out;
  for (const auto& entry : names) out.push_back(entry.first);
  return out;
}

}  // namespace tribos::core
