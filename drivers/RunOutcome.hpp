#pragma once
// The outcome of one rank's run of the driver, with the exceptions it may end with turned
// into exit statuses and messages (core::RankErrors then makes all ranks agree on them).
#include <functional>

#include "tribos/core/RankErrors.hpp"

namespace tribos::driver {

/// Runs `body` (which returns an exit status) and catches what it throws: a malformed
/// command line (status 2, the message and the usage), bad input (2), anything else (1,
/// "internal error").
core::RankOutcome runCatchingErrors(const std::function<int()>& body);

}  // namespace tribos::driver
