#pragma once
// Runs a shell command for driver tests: exit status and combined output.
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace tribos::test {

struct CommandResult {
  int status = -1;     ///< exit status, or -1 if the command did not exit normally
  std::string output;  ///< stdout and stderr
};

inline CommandResult runCommand(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  if (WIFEXITED(raw)) result.status = WEXITSTATUS(raw);
  return result;
}

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

}  // namespace tribos::test
