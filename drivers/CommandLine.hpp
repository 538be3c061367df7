#pragma once
// Command line of the tribos driver (see `tribos --help`).
#include <string>
#include <vector>

#include "tribos/core/Errors.hpp"

namespace tribos::driver {

struct CommandLine {
  std::string input;                  ///< --input SCENE.xml
  std::vector<std::string> overrides; ///< --set "Sublist/Name=value", in order
  std::string output;                 ///< --output result.exo
  std::string summary;                ///< --summary summary.json
  bool dryRun = false;
  bool help = false;
  bool version = false;
  bool kokkosHelp = false;            ///< --kokkos-help: Kokkos printed its options at initialisation
  bool listParameters = false;
};

/// A malformed command line (bad input: exit 2, with the usage).
class CommandLineError : public core::InputError {
 public:
  using core::InputError::InputError;
};

/// Parses argv; throws CommandLineError naming the bad argument.
CommandLine parseCommandLine(int argc, char** argv);

/// The text of `tribos --help`.
std::string usage();

/// The arguments Kokkos should see: argv without --help and --version, which are Tribos's
/// (Kokkos would print its own 40 lines of help for --help); --kokkos-help stays.
std::vector<char*> kokkosArguments(int argc, char** argv);

/// The text of `tribos --version`: git revision and the versions of the dependencies.
std::string versionText();

}  // namespace tribos::driver
