#pragma once
// Command line of the tribos driver (see `tribos --help`).
#include <string>
#include <vector>

namespace tribos::driver {

struct CommandLine {
  std::string input;                  ///< --input SCENE.xml
  std::vector<std::string> overrides; ///< --set "Sublist/Name=value", in order
  std::string output;                 ///< --output result.exo
  std::string summary;                ///< --summary summary.json
  bool dryRun = false;
  bool help = false;
  bool listParameters = false;
};

/// Parses argv; throws core::InputError naming the bad argument.
CommandLine parseCommandLine(int argc, char** argv);

/// The text of `tribos --help`.
std::string usage();

}  // namespace tribos::driver
