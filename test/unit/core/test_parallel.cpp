#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <vector>

#include "tribos/core/Parallel.hpp"

using tribos::core::forEachSubdomain;

TEST(forEachSubdomain, runsEveryIndexExactlyOnce) {
  tribos::core::setNumThreads(2);
  std::vector<std::atomic<int>> hits(257);
  forEachSubdomain(257, [&](int i) { hits[i]++; });
  for (auto& h : hits) EXPECT_EQ(h.load(), 1);
  tribos::core::setNumThreads(0);
}

TEST(forEachSubdomain, rethrowsTheFirstErrorAfterAllFinish) {
  tribos::core::setNumThreads(2);
  std::atomic<int> ran{0};
  EXPECT_THROW(forEachSubdomain(16,
                                [&](int i) {
                                  ran++;
                                  if (i == 3) throw std::runtime_error("subdomain 3 failed");
                                }),
               std::runtime_error);
  EXPECT_EQ(ran.load(), 16);
  tribos::core::setNumThreads(0);
}

TEST(forEachSubdomain, zeroCountRunsNothing) {
  int ran = 0;
  forEachSubdomain(0, [&](int) { ran++; });
  EXPECT_EQ(ran, 0);
}

TEST(forEachChunk, fixedChunksCoverEveryEntryOnceOnAnyThreadCount) {
  for (int threads : {1, 2}) {
    tribos::core::setNumThreads(threads);
    for (long n : {0L, 1L, 8191L, 8192L, 8193L, 3 * 8192L + 5}) {
      std::vector<std::atomic<int>> hits(static_cast<size_t>(n));
      std::vector<long> begins(static_cast<size_t>(tribos::core::numChunks(n)), -1);
      tribos::core::forEachChunk(n, [&](long c, long begin, long end) {
        begins[c] = begin;
        EXPECT_EQ(end, std::min(n, begin + tribos::core::kVectorChunk));
        for (long i = begin; i < end; ++i) hits[i]++;
      });
      for (auto& h : hits) EXPECT_EQ(h.load(), 1);
      for (size_t c = 0; c < begins.size(); ++c) EXPECT_EQ(begins[c], static_cast<long>(c) * tribos::core::kVectorChunk);
    }
  }
  tribos::core::setNumThreads(0);
}
