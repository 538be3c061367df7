#pragma once
/// \file Errors.hpp
/// Error types and the documented exit statuses of the drivers (DESIGN.md):
///   0 converged, 1 internal error, 2 bad input, 3 not converged.
#include <stdexcept>
#include <string>

namespace tribos::core {

enum ExitStatus : int { kExitOk = 0, kExitInternal = 1, kExitBadInput = 2, kExitNotConverged = 3 };

/// Bad input from the user: a file that cannot be read, a parameter out of range, a mesh
/// entity that does not exist. The message must name the file / parameter / entity.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// Throws InputError(message) when the condition holds.
inline void requireInput(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

}  // namespace tribos::core
