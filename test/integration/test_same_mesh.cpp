// Ranks that read different meshes (the file replaced while a job starts) stop together with
// an input error naming the file, instead of computing nonsense or waiting forever. The test
// double: rank 1 is given another mesh than rank 0 (on one rank it compares against itself).
#include <gtest/gtest.h>

#include "BoxMesh.hpp"
#include "WorldRank.hpp"
#include "tribos/core/Errors.hpp"
#include "tribos/stack/SameMeshOnEveryRank.hpp"

using tribos::stack::meshChecksum;
using tribos::stack::requireSameMeshOnEveryRank;

namespace {
tribos::mesh::Mesh box(double height) { return tribos::test::boxMesh({0, 0, 0}, {1, 1, height}, {2, 2, 2}, "body"); }
}  // namespace

TEST(SameMeshOnEveryRank, theChecksumSeesEveryValue) {
  const auto mesh = box(1.0);
  EXPECT_EQ(meshChecksum(mesh), meshChecksum(box(1.0)));
  auto moved = mesh;
  moved.coords[5][2] += 1e-12;
  EXPECT_NE(meshChecksum(mesh), meshChecksum(moved));
  auto renamed = mesh;
  renamed.nodeSets[0].name = "other";
  EXPECT_NE(meshChecksum(mesh), meshChecksum(renamed));
  auto rewired = mesh;
  std::swap(rewired.elements.mutableNodes(0)[1], rewired.elements.mutableNodes(0)[2]);
  EXPECT_NE(meshChecksum(mesh), meshChecksum(rewired));
}

TEST(SameMeshOnEveryRank, theSameMeshPasses) {
  EXPECT_NO_THROW(requireSameMeshOnEveryRank(box(1.0), "mesh.exo", MPI_COMM_WORLD));
}

TEST(SameMeshOnEveryRank, anotherMeshOnOneRankIsAnInputErrorOnEveryRank) {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size < 2) GTEST_SKIP() << "needs 2 ranks";
  // Same counts, one coordinate different: only the checksum can tell.
  const auto mesh = box(tribos::test::worldRank() == 1 ? 1.5 : 1.0);
  try {
    requireSameMeshOnEveryRank(mesh, "/data/mesh.exo", MPI_COMM_WORLD);
    FAIL() << "nothing thrown";
  } catch (const tribos::core::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("/data/mesh.exo: the ranks read different meshes (rank 0: 27 nodes, 48 elements; rank 1: "
                        "27 nodes, 48 elements"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("was the file replaced while the job started?"), std::string::npos) << what;
  }
}
