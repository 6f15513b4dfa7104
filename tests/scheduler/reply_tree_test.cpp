// The replies' pure parts (scheduler/replies.hpp): the binomial tree reaches every rank once and
// each subtree is a contiguous range; which rank holds a piece; what a worker keeps for the output.
#include <gtest/gtest.h>

#include <vector>

#include "scheduler/replies.hpp"

using namespace raceway::scheduler;

TEST(ReplyTree, EveryRankReachesRankZeroOnceThroughContiguousSubtrees) {
  for (int size = 1; size <= 40; ++size) {
    std::vector<int> parent_count(static_cast<std::size_t>(size), 0);
    for (int r = 0; r < size; ++r) {
      int next = r + 1;  // a subtree is r, then its children's subtrees in rank order
      for (const int c : tree_children(r, size)) {
        ASSERT_EQ(c, next) << "size " << size << ", rank " << r;
        ASSERT_EQ(c & (c - 1), r) << "the parent is the child with its lowest bit cleared";
        ++parent_count[static_cast<std::size_t>(c)];
        next = subtree_end(c, size);
      }
      ASSERT_EQ(next, subtree_end(r, size)) << "size " << size << ", rank " << r;
    }
    EXPECT_EQ(subtree_end(0, size), size);
    for (int r = 1; r < size; ++r) EXPECT_EQ(parent_count[static_cast<std::size_t>(r)], 1) << "size " << size;
  }
  EXPECT_EQ(tree_children(0, 16), (std::vector<int>{1, 2, 4, 8}));  // rank 0 hears from log2 P ranks
  EXPECT_EQ(tree_children(4, 16), (std::vector<int>{5, 6}));
  EXPECT_EQ(subtree_end(12, 14), 14);
}

TEST(PieceHolders, OwnerOfAWholePieceRankZeroForACutOne) {
  EXPECT_EQ(piece_holders(std::vector<int>{2, 1, 3}, {}), (std::vector<int>{2, 1, 3}));
  // Pieces: 0 = tasks 0, 1 (cut over ranks 1 and 2); 1 = task 2 on rank 3; 2 = task 3 on rank 1.
  EXPECT_EQ(piece_holders(std::vector<int>{1, 2, 3, 1}, std::vector<int>{0, 0, 1, 2}), (std::vector<int>{0, 3, 1}));
}

TEST(KeepWholePieces, OnlyPiecesOfOneTaskWithTheirRecords) {
  const std::vector<int> parent{0, 0, 1, 2};  // piece 0 is cut into tasks 0 and 1
  const auto counts = piece_task_counts(parent);
  EXPECT_EQ(counts, (std::vector<int>{2, 1, 1}));
  const std::vector<int> mine{1, 3};              // this rank's tasks
  const std::vector<double> full{1, 2, 3, 4};     // their records, 2 doubles each
  std::vector<int> pieces;
  std::vector<double> records;
  keep_whole_pieces(parent, counts, mine, full, 2, pieces, records);
  EXPECT_EQ(pieces, (std::vector<int>{2}));
  EXPECT_EQ(records, (std::vector<double>{3, 4}));
  keep_whole_pieces({}, {}, mine, full, 2, pieces, records);  // no pieces: every task is one
  EXPECT_EQ(pieces, (std::vector<int>{1, 3}));
  EXPECT_EQ(records, full);
}
