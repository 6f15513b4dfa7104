// The tail's claims (scheduler/tail_claims.hpp): the owner codes round trip, a rank takes its own
// part front first and then steals from the back of the fullest part, and every position is handed
// out exactly once when many threads claim at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "scheduler/plan.hpp"
#include "scheduler/tail_claims.hpp"

using namespace raceway::scheduler;

TEST(TailCodes, EncodeThenDecodeGivesEachRanksCheapestTasksLargestFirst) {
  // Rank 0: tasks 0-3, rank 1: tasks 4-7; costs such that each rank's tail is its two cheapest.
  std::vector<int> owner{0, 0, 0, 0, 1, 1, 1, 1};
  const std::vector<double> cost{10, 1, 2, 10, 10, 10, 1.5, 1};
  encode_tail(owner, cost, 0.25, 2);
  EXPECT_EQ(owner[0], 0);
  EXPECT_EQ(owner[5], 1);
  EXPECT_LT(owner[1], 0);
  const TailParts parts = decode_tail(owner, 2);
  EXPECT_EQ(parts.tasks, (std::vector<int>{2, 1, 6, 7}));
  EXPECT_EQ(parts.start, (std::vector<int>{0, 2, 4}));
  EXPECT_TRUE(decode_tail(std::vector<int>{0, 1, 1}, 2).empty());
}

TEST(TailClaims, OwnPartFromTheFrontThenTheBackOfTheFullestPart) {
  TailParts parts;
  parts.tasks = {10, 11, 12, 20, 21, 22, 23, 30};
  parts.start = {0, 3, 7, 8};  // rank 0: 3 positions, rank 1: 4, rank 2: 1
  std::vector<std::int64_t> words(3 * 8, 0);
  TailClaims claims(words.data(), 8, 3);
  claims.reset(parts);
  EXPECT_EQ(claims.claim(2), 7);  // its own
  EXPECT_EQ(claims.claim(2), 6);  // then the back of rank 1's part (4 left, the most)
  EXPECT_EQ(claims.claim(0), 0);  // rank 0's own front
  EXPECT_EQ(claims.claim(2), 5);  // rank 1's (3 left) beats rank 0's (2 left)
  EXPECT_EQ(claims.claim(1), 3);
  EXPECT_EQ(claims.claim(1), 4);
  EXPECT_EQ(claims.claim(1), 2);  // rank 1's gone: the back of rank 0's
  EXPECT_EQ(claims.claim(0), 1);
  EXPECT_EQ(claims.claim(0), -1);
  EXPECT_EQ(claims.claim(1), -1);
  claims.reset(parts);  // whole again for the next evaluation
  EXPECT_EQ(claims.claim(1), 3);
}

TEST(TailClaims, EveryPositionExactlyOnceUnderConcurrentClaims) {
  constexpr int ranks = 4, per_rank = 2000;
  TailParts parts;
  for (int r = 0; r < ranks; ++r) {
    parts.start.push_back(static_cast<int>(parts.tasks.size()));
    for (int i = 0; i < per_rank / (r + 1); ++i) parts.tasks.push_back(static_cast<int>(parts.tasks.size()));  // uneven parts
  }
  parts.start.push_back(static_cast<int>(parts.tasks.size()));
  std::vector<std::int64_t> words(ranks * 8, 0);
  for (int round = 0; round < 20; ++round) {
    TailClaims claims(words.data(), 8, ranks);
    claims.reset(parts);
    std::vector<std::atomic<int>> taken(parts.tasks.size());
    std::vector<std::jthread> threads;
    for (int r = 0; r < ranks; ++r)
      threads.emplace_back([&, r] {
        for (std::int64_t p; (p = claims.claim(r)) >= 0;) taken[static_cast<std::size_t>(p)].fetch_add(1);
      });
    threads.clear();  // join
    for (std::size_t p = 0; p < taken.size(); ++p) ASSERT_EQ(taken[p].load(), 1) << "position " << p << ", round " << round;
  }
}
