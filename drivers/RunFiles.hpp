#pragma once
// The files of one run of the driver: the scene it reads (once, on rank 0) and the result
// files it writes (checked before any work; core/OutputFile.hpp says how they are written).
#include <Teuchos_ParameterList.hpp>

#include <memory>
#include <string>
#include <vector>

#include "tribos/core/OutputFile.hpp"
#include "tribos/core/Types.hpp"

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

/// Doubles a result file holds at least per mesh node and per element for each step: measured,
/// a linear scene writes 13 per node and 8 per element, a contact scene 29 and 8
/// (block_on_plate.xml: 208 kB per step for 515 nodes and 1386 elements).
constexpr double kWrittenDoublesPerNodeAndStep = 13.0;
constexpr double kWrittenDoublesPerElementAndStep = 8.0;

/// Before the assembly: refuses (core::InputError on every rank, naming --output, the sizes and
/// the room) a result that cannot fit where --output writes it: the free space of its file
/// system or the file size limit (issue 44: 10 000 steps wrote 2.08 GB before the disk said no);
/// a history's twice (its last checkpoint stays until the final file replaces it). Nothing
/// without --output. Collective.
void requireRoomForTheResult(const ResultFiles& files, int loadSteps, LO numNodes, LO numElements, int rank);

}  // namespace tribos::driver
