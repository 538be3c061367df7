#include "CommandLine.hpp"

#include "tribos/core/Errors.hpp"

namespace tribos::driver {

std::string usage() {
  return R"(tribos: 3D contact of elastic bodies with (orthotropic) Coulomb friction by
Total FETI + SMALSE-M + MPGP (Haslinger & Kucera).

Usage: [mpirun -np N] tribos --input SCENE.xml [options]

  --input FILE        Teuchos XML parameter list of the scene (top-level list "Tribos")
  --set "A/B=value"   override one parameter (repeatable), e.g. --set "Mesh/H Over h=4"
  --dry-run           build mesh, decomposition and subdomain matrices, print the
                      dimensions and stop
  --summary FILE      write the JSON summary (dimensions, counts, times)
  --output FILE       write the results (mesh, element variable "subdomain") to Exodus II
  --list-parameters   print every valid parameter: type, default, range, documentation
  --help              this text
  --version           git revision and dependency versions
  --kokkos-help       Kokkos's own options (--kokkos-threads=N, ...; accepted and passed on)

Threads per rank: Parallel/Threads or OMP_NUM_THREADS. Idle OpenMP threads sleep
(OMP_WAIT_POLICY=PASSIVE unless set otherwise). As root, mpirun needs
--allow-run-as-root (and --oversubscribe beyond the core count).

Progress (Solver/Verbose): one line per SMALSE-M outer iteration, and a line inside long
inner solves every Solver/Progress Interval seconds (default 2).

Exit status: 0 success, 1 internal error, 2 bad input (the message names the file or
parameter), 3 the solver did not converge or a limit ended it (Solver/Max Seconds, an
iteration cap; the message names it; results still written, flagged).

Examples:
  tribos --input input/two_bricks.xml --dry-run
  tribos --input input/two_bricks.xml --set "Mesh/Subdomains Per Brick=4x2x2" --set "Mesh/H Over h=3" --summary s.json
  mpirun -np 4 tribos --input input/two_bricks.xml --output two_bricks.exo
)";
}

CommandLine parseCommandLine(int argc, char** argv) {
  CommandLine cl;
  auto value = [&](int& i, const std::string& flag) -> std::string {
    if (i + 1 >= argc) throw CommandLineError("command line: " + flag + " needs a value");
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    // Accept both "--flag value" and "--flag=value".
    const auto eq = arg.find('=');
    const std::string flag = arg.rfind("--", 0) == 0 && eq != std::string::npos ? arg.substr(0, eq) : arg;
    auto get = [&]() { return eq != std::string::npos && flag != arg ? arg.substr(eq + 1) : value(i, flag); };
    if (flag == "--input") cl.input = get();
    else if (flag == "--set") cl.overrides.push_back(get());
    else if (flag == "--output") cl.output = get();
    else if (flag == "--summary") cl.summary = get();
    else if (arg == "--dry-run") cl.dryRun = true;
    else if (arg == "--help" || arg == "-h") cl.help = true;
    else if (arg == "--version") cl.version = true;
    else if (arg == "--kokkos-help") cl.kokkosHelp = true;
    else if (arg == "--list-parameters") cl.listParameters = true;
    else if (arg.rfind("--kokkos", 0) == 0) continue;  // consumed by Kokkos
    else throw CommandLineError("command line: unknown argument \"" + arg + "\"");
  }
  if (!cl.help && !cl.version && !cl.kokkosHelp && !cl.listParameters && cl.input.empty())
    throw CommandLineError("command line: --input SCENE.xml is required");
  return cl;
}

std::vector<char*> kokkosArguments(int argc, char** argv) {
  std::vector<char*> kept;
  for (int i = 0; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i == 0 || arg.rfind("--kokkos", 0) == 0) kept.push_back(argv[i]);
  }
  kept.push_back(nullptr);  // argv[argc] is a null pointer by convention
  return kept;
}

namespace {
// "123": digits only, within int.
bool isCount(const std::string& text) {
  if (text.empty() || text.size() > 9) return false;
  for (char c : text)
    if (c < '0' || c > '9') return false;
  return true;
}

// Kokkos's options that take an integer ("--kokkos-threads=4"); --kokkos-num-devices takes
// "N" or "N,M". Both Kokkos 3 and Kokkos 4 spellings.
constexpr const char* kKokkosCountOptions[] = {"--kokkos-threads", "--kokkos-num-threads", "--kokkos-numa",
                                               "--kokkos-device",  "--kokkos-device-id",   "--kokkos-skip-device"};
constexpr const char* kKokkosDeviceCountOptions[] = {"--kokkos-num-devices", "--kokkos-ndevices"};
}  // namespace

void requireValidKokkosArguments(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--kokkos-", 0) != 0) continue;
    const auto eq = arg.find('=');
    const std::string flag = arg.substr(0, eq), value = eq == std::string::npos ? "" : arg.substr(eq + 1);
    for (const char* option : kKokkosCountOptions)
      if (flag == option && !isCount(value))
        throw CommandLineError("command line: " + flag + " needs =N with N a non-negative integer, got \"" + arg +
                               "\"");
    for (const char* option : kKokkosDeviceCountOptions) {
      const auto comma = value.find(',');
      const bool ok = comma == std::string::npos ? isCount(value)
                                                 : isCount(value.substr(0, comma)) && isCount(value.substr(comma + 1));
      if (flag == option && !ok)
        throw CommandLineError("command line: " + flag + " needs =N or =N,M with non-negative integers, got \"" + arg +
                               "\"");
    }
  }
}

}  // namespace tribos::driver
