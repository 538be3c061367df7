#include "RunFiles.hpp"

#include <mpi.h>
#include <sys/resource.h>
#include <sys/statvfs.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include <functional>

#include "CommandLine.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/core/InputFiles.hpp"
#include "tribos/core/XmlParameters.hpp"

namespace tribos::driver {

namespace {
/// Runs `work` on rank 0 and makes every rank throw what it threw there: an InputError as
/// such, anything else as an internal error with its message.
void onRootForEveryRank(int rank, const std::function<void()>& work) {
  std::string error;
  int kind = 0;  // 0 ok, 1 bad input, 2 anything else
  if (rank == 0) {
    try {
      work();
    } catch (const core::InputError& e) {
      error = e.what();
      kind = 1;
    } catch (const std::exception& e) {
      error = e.what();
      kind = 2;
    }
  }
  MPI_Bcast(&kind, 1, MPI_INT, 0, MPI_COMM_WORLD);
  int length = static_cast<int>(error.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, MPI_COMM_WORLD);
  error.resize(static_cast<size_t>(length));
  MPI_Bcast(error.data(), length, MPI_CHAR, 0, MPI_COMM_WORLD);
  if (kind == 1) throw core::InputError(error);
  if (kind == 2) throw std::runtime_error(error);
}

/// An output that is an input would be destroyed by the result.
void requireNotAnInput(const std::string& output, const std::string& option, const std::vector<std::string>& inputs) {
  for (const auto& input : inputs)
    if (!input.empty() && core::sameFile(output, input))
      throw core::InputError(output + " (" + option + "): is an input of this run (" + input +
                             "); writing it would destroy it: give another file name");
}
}  // namespace

Teuchos::ParameterList readSceneXml(const std::string& path, int rank) {
  std::string text;
  onRootForEveryRank(rank, [&] { text = core::readRegularTextFile(path, "the scene file", kMaxSceneBytes); });
  long long length = static_cast<long long>(text.size());
  MPI_Bcast(&length, 1, MPI_LONG_LONG, 0, MPI_COMM_WORLD);
  text.resize(static_cast<size_t>(length));
  MPI_Bcast(text.data(), static_cast<int>(length), MPI_CHAR, 0, MPI_COMM_WORLD);
  // Strict: duplicate names, values that do not read as their type, non-finite numbers and
  // deep nesting are input errors naming the file and the parameter.
  const auto list = core::parameterListFromXml(text, path);
  list->setName("Tribos");  // Teuchos does not keep the top-level name; its contents are validated
  return *list;
}

ResultFiles prepareResultFiles(const CommandLine& cl, const std::vector<std::string>& inputs, int rank) {
  ResultFiles files;
  onRootForEveryRank(rank, [&] {
    if (!cl.output.empty() && !cl.summary.empty() && core::sameFile(cl.output, cl.summary))
      throw core::InputError(cl.output + ": given as both --output and --summary; the summary would replace the "
                             "results: give two file names");
    if (!cl.output.empty()) {
      requireNotAnInput(cl.output, "--output", inputs);
      files.exodus = std::make_unique<core::OutputFile>(cl.output, "--output", false);
    }
    if (!cl.summary.empty()) {
      requireNotAnInput(cl.summary, "--summary", inputs);
      files.summary = std::make_unique<core::OutputFile>(cl.summary, "--summary", true);
    }
  });
  return files;
}


namespace {
// Bytes the file system of `path` has left (statvfs of its directory, the space an unprivileged
// user may take) and the file size limit (ulimit -f); HUGE_VAL where there is no bound or the file
// system does not say (a pseudo file system reports no blocks).
std::pair<double, double> roomFor(const std::string& path) {
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  double space = HUGE_VAL, fileSize = HUGE_VAL;
  struct statvfs fs {};
  if (statvfs(dir.c_str(), &fs) == 0 && fs.f_blocks > 0)
    space = static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
  struct rlimit limit {};
  if (getrlimit(RLIMIT_FSIZE, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
    fileSize = static_cast<double>(limit.rlim_cur);
  return {space, fileSize};
}

std::string megabytes(double bytes) {
  if (!std::isfinite(bytes)) return "unbounded";
  char text[32];
  if (bytes >= 1e9)
    std::snprintf(text, sizeof text, "%.3g GB", bytes / 1e9);
  else
    std::snprintf(text, sizeof text, "%.3g MB", bytes / 1e6);
  return text;
}
}  // namespace

void requireRoomForTheResult(const ResultFiles& files, int loadSteps, LO numNodes, LO numElements, int rank) {
  onRootForEveryRank(rank, [&] {
    if (!files.exodus) return;
    const double result = 8.0 * std::max(loadSteps, 1) *
                          (kWrittenDoublesPerNodeAndStep * numNodes + kWrittenDoublesPerElementAndStep * numElements);
    // A history's last checkpoint stays on the disk beside its draft until the draft replaces
    // it (HistoryResults.hpp): twice the result's space, each file within the file size limit.
    const bool checkpoints = loadSteps > 1;
    const auto [space, fileSize] = roomFor(files.exodus->path());
    const double room = std::min(checkpoints ? space / 2.0 : space, fileSize);
    core::requireInput(result <= room,
                       files.exodus->path() + " (--output): the result of " + std::to_string(std::max(loadSteps, 1)) +
                           " step(s) of " + std::to_string(numNodes) + " nodes and " + std::to_string(numElements) +
                           " elements takes at least " + megabytes(result) +
                           (checkpoints ? " (twice that on the disk while the last checkpoint is replaced)" : "") +
                           "; the file system has " + megabytes(space) + " free, the file size limit (ulimit -f) is " +
                           megabytes(fileSize) + "; nothing was solved");
  });
}

}  // namespace tribos::driver
