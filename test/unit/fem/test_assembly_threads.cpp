// assembleSubdomain on OpenMP threads (core::forEachSubdomain) with Debian's Serial-only,
// non-thread-safe Kokkos (TOOLCHAIN.md "Threads inside a rank"): the result must be
// bitwise the one of a single thread, run after run. A stress test: a managed View, a
// scan or a shared scratch buffer inside the assembly would show up here as a crash or a
// differing bit. Registered with THREADS 2.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tribos/core/Errors.hpp"
#include "tribos/core/Parallel.hpp"
#include "tribos/fem/SubdomainSystem.hpp"
#include "tribos/mesh/Decomposition.hpp"
#include "tribos/mesh/TwoBricks.hpp"

using namespace tribos;

namespace {
const std::vector<fem::Material> kMaterials{{2.792e4, 2.593e4}, {6.360e4, 8.301e4}};

fem::Loads paperLoads() {
  fem::Loads loads;
  loads.tractions = {{"load_end", {1.0, 0.0, 20.0}}, {"load_top", {0.0, 0.0, -30.0}}};
  loads.volumeForce = {{0.0, 0.0, -1e-3}, {0.0, 0.0, -2e-3}};
  return loads;
}

std::vector<fem::SubdomainSystem> assembleAll(const mesh::Mesh& mesh, const mesh::Decomposition& d, int threads) {
  core::setNumThreads(threads);
  // One slot per subdomain, allocated before the parallel region: threads only fill them.
  std::vector<fem::SubdomainSystem> systems(d.numSubdomains());
  const auto loads = paperLoads();
  core::forEachSubdomain(d.numSubdomains(), [&](int s) {
    systems[s] = fem::assembleSubdomain(mesh, d.subdomains[s], kMaterials, loads);
  });
  core::setNumThreads(0);
  return systems;
}

void expectBitwiseEqual(const fem::SubdomainSystem& a, const fem::SubdomainSystem& b, const std::string& where) {
  EXPECT_EQ(a.K.n, b.K.n) << where;
  EXPECT_TRUE(a.K.rowPtr == b.K.rowPtr) << where << ": rowPtr";
  EXPECT_TRUE(a.K.colInd == b.K.colInd) << where << ": colInd";
  EXPECT_TRUE(a.K.values == b.K.values) << where << ": K values";
  EXPECT_TRUE(a.f == b.f) << where << ": f";
  EXPECT_TRUE(a.R == b.R) << where << ": R";
}
}  // namespace

TEST(SubdomainSystem, twoThreadsGiveBitwiseTheSameSystemsAsOne) {
  const mesh::TwoBricksSpec spec{{4, 2, 2}, 2};
  const auto mesh = mesh::generateTwoBricks(spec);
  // 32 structured cubes and 40 irregular METIS parts (different sizes: uneven thread loads).
  for (const auto& part : {mesh::structuredPartition(mesh, spec), mesh::metisPartition(mesh, 40)}) {
    const auto d = mesh::buildDecomposition(mesh, part);
    const auto reference = assembleAll(mesh, d, 1);
    for (int repeat = 0; repeat < 6; ++repeat) {
      const auto threaded = assembleAll(mesh, d, 2);
      for (int s = 0; s < d.numSubdomains(); ++s)
        expectBitwiseEqual(threaded[s], reference[s], "repeat " + std::to_string(repeat) + ", subdomain " +
                                                          std::to_string(s));
    }
  }
}

TEST(SubdomainSystem, anInputErrorOnAThreadReachesTheCaller) {
  const mesh::TwoBricksSpec spec{{4, 2, 2}, 2};
  const auto mesh = mesh::generateTwoBricks(spec);
  auto d = mesh::buildDecomposition(mesh, mesh::structuredPartition(mesh, spec));
  std::swap(d.subdomains[21].localElements.mutableNodes(0)[0], d.subdomains[21].localElements.mutableNodes(0)[1]);
  core::setNumThreads(2);
  std::vector<fem::SubdomainSystem> systems(d.numSubdomains());
  EXPECT_THROW(core::forEachSubdomain(d.numSubdomains(),
                                      [&](int s) {
                                        systems[s] = fem::assembleSubdomain(mesh, d.subdomains[s], kMaterials, {});
                                      }),
               core::InputError);
  core::setNumThreads(0);
}
