#pragma once
/// \file Errors.hpp
/// Error types and the documented exit statuses of the drivers (DESIGN.md):
///   0 converged, 1 internal error, 2 bad input, 3 not converged (a limit such as
///   Solver/Max Seconds included), 4 the results could not be written (an I/O failure).
#include <stdexcept>
#include <string>

namespace tribos::core {

enum ExitStatus : int {
  kExitOk = 0,
  kExitInternal = 1,
  kExitBadInput = 2,
  kExitNotConverged = 3,
  kExitIoFailure = 4
};

/// Bad input from the user: a file that cannot be read, a parameter out of range, a mesh
/// entity that does not exist. The message must name the file / parameter / entity.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

/// A result file that could not be written (disk full, read-only, a file size limit): not the
/// user's input, and the solve itself may have been right. Exit status 4.
class IoError : public std::runtime_error {
 public:
  explicit IoError(const std::string& what) : std::runtime_error(what) {}
};

/// A limit of the run's own (Solver/Max Seconds) reached before the solve could start, e.g.
/// during the set-up or the factorisation: the run ends as not converged (exit status 3).
class LimitReached : public std::runtime_error {
 public:
  explicit LimitReached(const std::string& what) : std::runtime_error(what) {}
};

/// Throws InputError(message) when the condition holds.
inline void requireInput(bool ok, const std::string& message) {
  if (!ok) throw InputError(message);
}

}  // namespace tribos::core
