// share_threads: a coupled run's cores shared out by work (solver/parallel/thread_shares.h).
#include "solver/parallel/thread_shares.h"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

using crashlink::parallel::share_threads;

TEST(ShareThreads, EqualWorkGetsEqualThreads) {
  EXPECT_EQ(share_threads({1.0, 1.0}, 2), (std::vector<int>{1, 1}));
  EXPECT_EQ(share_threads({1.0, 1.0}, 4), (std::vector<int>{2, 2}));
}

// The head impact's domains: body 10 468 elements x 14 112 cycles, wiper 3 704 x 42 336 (about
// equal work): 2 + 2 on 4 cores, 3 + 3 on 6; a 3:1 split of work on 4 cores: 3 + 1.
TEST(ShareThreads, CoresGoWhereTheWorkPerThreadIsLargest) {
  const std::vector<double> head{10468.0 * 14112, 3704.0 * 42336};
  EXPECT_EQ(share_threads(head, 4), (std::vector<int>{2, 2}));
  EXPECT_EQ(share_threads(head, 6), (std::vector<int>{3, 3}));
  EXPECT_EQ(share_threads({3.0, 1.0}, 4), (std::vector<int>{3, 1}));
  EXPECT_EQ(share_threads({1.0, 5.0, 2.0}, 8), (std::vector<int>{1, 5, 2}));
}

TEST(ShareThreads, FewerCoresThanDomainsGiveOneEach) {
  EXPECT_EQ(share_threads({5.0, 1.0, 1.0}, 2), (std::vector<int>{1, 1, 1}));
  EXPECT_EQ(share_threads({}, 4), (std::vector<int>{}));
}

TEST(ShareThreads, DomainsWithoutWorkKeepOneThread) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(share_threads({0.0, 2.0}, 4), (std::vector<int>{1, 3}));
  EXPECT_EQ(share_threads({inf, 2.0}, 3), (std::vector<int>{1, 2}));
  EXPECT_EQ(share_threads({0.0, 0.0}, 4), (std::vector<int>{1, 1}));
}
