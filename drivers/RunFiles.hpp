#pragma once
// The files of one run of the driver: the scene it reads (once, on rank 0) and the result
// files it writes (checked before any work; core/OutputFile.hpp says how they are written).
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <string>
#include <vector>

#include "tribos/core/OutputFile.hpp"

namespace tribos::driver {

struct CommandLine;

/// Scene files are a few kilobytes; anything beyond this is the wrong file (`--input
/// /dev/urandom` is refused as a device before, a huge regular file here).
constexpr std::uintmax_t kMaxSceneBytes = 16u << 20;

/// Rank 0 reads the scene file (a regular file of at most kMaxSceneBytes); every rank parses
/// the same text, so every rank sees the same parameters and the same errors. Collective.
Teuchos::ParameterList readSceneXml(const std::string& path, int rank);

/// The run's result files; rank 0 holds them, other ranks hold none.
struct ResultFiles {
  std::unique_ptr<core::OutputFile> exodus;   ///< --output
  std::unique_ptr<core::OutputFile> summary;  ///< --summary
};

/// Before any work: refuses (core::InputError on every rank) an output that is one of
/// `inputs` or the other output, or that cannot be written. Collective.
ResultFiles prepareResultFiles(const CommandLine& cl, const std::vector<std::string>& inputs, int rank);

}  // namespace tribos::driver
