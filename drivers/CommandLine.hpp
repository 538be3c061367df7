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

/// The arguments Kokkos should see: argv[0] and the --kokkos-* options only. Kokkos 3 also
/// reads unprefixed --threads=N, --numa=N, ... and aborts on a bad value before Tribos can
/// refuse them; --help and --version are Tribos's (Kokkos would print its own help).
std::vector<char*> kokkosArguments(int argc, char** argv);

/// Throws CommandLineError naming the option when a Kokkos option that takes a count
/// (--kokkos-threads, --kokkos-num-threads, --kokkos-numa, --kokkos-device-id, ...,
/// --kokkos-num-devices=N[,M]) lacks "=N" or N is not a non-negative integer: Kokkos's own
/// parser throws std::invalid_argument from inside Kokkos::initialize (std::terminate,
/// signal 6). Call it before Kokkos is initialised.
void requireValidKokkosArguments(int argc, char** argv);

/// The text of `tribos --version`: git revision and the versions of the dependencies.
std::string versionText();

}  // namespace tribos::driver
