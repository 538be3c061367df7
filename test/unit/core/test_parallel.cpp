#include <gtest/gtest.h>

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
