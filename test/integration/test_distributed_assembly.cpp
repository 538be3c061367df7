// The subdomain matrices do not depend on how the subdomains are distributed: every rank
// assembles the subdomains it owns with OMP_NUM_THREADS threads (the driver's code path,
// stack::assembleOwnedSubdomains), hashes K_s, f_s, R_s bitwise, and rank 0 compares each
// hash with a serial, single-threaded assembly of the same subdomain. Run under 1, 2 and
// 4 ranks and 1 and 2 threads.
#include <gtest/gtest.h>
#include <mpi.h>

#include <Teuchos_ParameterList.hpp>

#include <cstdint>
#include <cstring>

#include "tribos/core/Parallel.hpp"
#include "tribos/core/Parameters.hpp"
#include "tribos/stack/Scene.hpp"
#include "tribos/stack/SceneParameters.hpp"
#include "tribos/stack/SubdomainSetup.hpp"

namespace {
using namespace tribos;

// FNV-1a over the bytes of a vector: any difference in any bit changes the hash.
template <class T>
void hashInto(std::uint64_t& h, const std::vector<T>& v) {
  const auto* bytes = reinterpret_cast<const unsigned char*>(v.data());
  for (size_t i = 0; i < v.size() * sizeof(T); ++i) h = (h ^ bytes[i]) * 1099511628211ULL;
}

std::uint64_t hashOf(const fem::SubdomainSystem& s) {
  std::uint64_t h = 1469598103934665603ULL;
  hashInto(h, s.K.rowPtr);
  hashInto(h, s.K.colInd);
  hashInto(h, s.K.values);
  hashInto(h, s.f);
  hashInto(h, s.R);
  return h;
}

stack::Scene sceneFor(const std::vector<std::string>& overrides) {
  Teuchos::ParameterList params("Tribos");
  const auto valid = stack::sceneValidParameters();
  for (const auto& o : overrides) core::applyOverride(params, *valid, o);
  core::validateAndSetDefaults(params, *valid, "test");
  return stack::buildScene(params, "test");
}

void expectSameAsSerial(const stack::Scene& scene) {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<fem::SubdomainSystem> systems;
  const auto report = stack::assembleOwnedSubdomains(scene, MPI_COMM_WORLD, systems);
  const int nSub = scene.decomposition.numSubdomains();
  EXPECT_EQ(report.nSubdomains, nSub);
  EXPECT_EQ(report.nRanks, size);
  EXPECT_EQ(report.nPrimal, scene.decomposition.numPrimalDofs());

  std::vector<unsigned long long> mine;
  for (const auto& s : systems) mine.push_back(hashOf(s));
  std::vector<int> counts(size), offsets(size);
  for (int r = 0; r < size; ++r) {
    offsets[r] = mesh::firstSubdomain(r, nSub, size);
    counts[r] = mesh::firstSubdomain(r + 1, nSub, size) - offsets[r];
  }
  ASSERT_EQ(static_cast<int>(mine.size()), counts[rank]);
  std::vector<unsigned long long> all(nSub);
  MPI_Gatherv(mine.data(), counts[rank], MPI_UNSIGNED_LONG_LONG, all.data(), counts.data(), offsets.data(),
              MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD);
  if (rank != 0) return;
  for (int s = 0; s < nSub; ++s) {
    const auto reference = fem::assembleSubdomain(scene.mesh, scene.decomposition.subdomains[s],
                                                  scene.materials, scene.loads);
    EXPECT_EQ(all[s], hashOf(reference)) << "subdomain " << s << " differs from its serial assembly";
  }
}
}  // namespace

TEST(assembleOwnedSubdomains, structuredSplitIsIndependentOfRanksAndThreads) {
  expectSameAsSerial(sceneFor({"Mesh/Subdomains Per Brick=4x2x2", "Mesh/H Over h=3"}));
}

TEST(assembleOwnedSubdomains, metisSplitIsIndependentOfRanksAndThreads) {
  expectSameAsSerial(sceneFor({"Mesh/Decomposition=METIS", "Mesh/Subdomains=11", "Mesh/H Over h=4"}));
}
