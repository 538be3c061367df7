#include "RunOutcome.hpp"

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
  } catch (const std::exception& e) {
    return {core::kExitInternal, std::string("internal error: ") + e.what()};
  }
}

}  // namespace tribos::driver
