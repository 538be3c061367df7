#pragma once
/// \file Types.hpp
/// Fixed scalar and index types used across Tribos (Tpetra is instantiated for
/// double / int / long long in Debian's Trilinos 13.2).
#include <cstdint>

namespace tribos {
using Scalar = double;     ///< every floating-point quantity
using LO = int;            ///< local (per rank / per subdomain) index
using GO = long long;      ///< global index (Tpetra global ordinal)
}  // namespace tribos
