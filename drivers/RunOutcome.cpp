#include "RunOutcome.hpp"

#include <new>

#include "CommandLine.hpp"

namespace tribos::driver {

core::RankOutcome runCatchingErrors(const std::function<int()>& body) {
  try {
    return {body(), ""};
  } catch (const CommandLineError& e) {
    // What is wrong, then how to call tribos (the usage ends with its own newline).
    std::string text = std::string("error: ") + e.what() + "\n\n" + usage();
    while (!text.empty() && text.back() == '\n') text.pop_back();
    return {core::kExitBadInput, text};
  } catch (const core::InputError& e) {
    return {core::kExitBadInput, std::string("error: ") + e.what()};
  } catch (const core::IoError& e) {
    return {core::kExitIoFailure, std::string("error: ") + e.what()};
  } catch (const core::LimitReached& e) {
    return {core::kExitNotConverged, e.what()};
  } catch (const std::bad_alloc&) {
    return {core::kExitInternal, "internal error: out of memory (std::bad_alloc): the scene needs more memory "
                                 "than this process may use (physical memory, ulimit -v, or the cgroup's limit); "
                                 "use fewer ranks per machine, more machines, or a coarser mesh"};
  } catch (const std::exception& e) {
    return {core::kExitInternal, std::string("internal error: ") + e.what()};
  }
}

}  // namespace tribos::driver
