// The workers' replies to an evaluation: of each task's record only the doubles it fills
// (TaskCatalogue::used_size, a size both sides know, so nothing about sizes is exchanged per
// evaluation), then the tasks' seconds; by message up a binomial tree to rank 0, or through the
// node's shared-memory window (scheduler/node_window.hpp). Rank 0 places every record at its task.
#pragma once

#include <mpi.h>

#include <vector>

#include "scheduler/command_channel.hpp"
#include "scheduler/executor.hpp"
#include "scheduler/node_window.hpp"
#include "scheduler/rank_watch.hpp"

namespace raceway::scheduler {

/// Per rank its fixed task list in one phase's plan (ascending).
using RankTaskLists = std::vector<std::vector<int>>;

/// The replies' tree: the binomial tree rooted at rank 0 that MPI libraries use for small gathers
/// (Open MPI's tuned MPI_Gather), for `size` ranks. Rank r's parent is r with its lowest set bit
/// cleared; its children r + 1, r + 2, r + 4, ... below that bit; it passes on the replies of ranks
/// r .. subtree_end(r) - 1, in rank order.
std::vector<int> tree_children(int r, int size);
int subtree_end(int r, int size);

/// Per piece (`parent`; per task when it is empty), the rank that holds the piece's final record
/// after an evaluation with `owner` per task: the owner of its task when it is one task, rank 0
/// (which combines the parts in a fixed order) when it is cut into several.
std::vector<int> piece_holders(std::span<const int> owner, std::span<const int> parent);
/// Per piece (`parent`): its task count.
std::vector<int> piece_task_counts(std::span<const int> parent);
/// Worker, after an rhs evaluation (what an output command samples): of its tasks `mine` (records
/// `full`, record_size each, in the order of mine) the pieces it evaluated whole into `pieces`,
/// their records into `records` (a cut piece's tasks hold parts, which rank 0 combines and writes).
/// `piece_tasks`: piece_task_counts(parent).
void keep_whole_pieces(std::span<const int> parent, std::span<const int> piece_tasks, std::span<const int> mine,
                       std::span<const double> full, std::size_t record_size, std::vector<int>& pieces,
                       std::vector<double>& records);

class ReplyExchange {
 public:
  /// `catalogue`: the executor's (record sizes and used sizes, read at each call).
  ReplyExchange(MPI_Comm comm, const RankWatch& watch, CommandChannel& channel, const TaskCatalogue& catalogue)
      : comm_(comm), watch_(watch), channel_(channel), catalogue_(catalogue) {}
  /// Both, after the start: with the shared exchange the replies go through `window`.
  void open(const NodeWindow* window, bool shared_exchange);

  /// Master, before its own tasks: posts the receives of its children's replies (tree) into
  /// `requests`, with the sending rank in `ranks`.
  void post_receives(int phase, const RankTaskLists& lists, std::vector<MPI_Request>& requests, std::vector<int>& ranks);
  /// Master, after its own tasks: waits (bounded) for `requests` and every reply, then places each
  /// worker's records (used doubles, zeros after them) and seconds at their tasks, its seconds
  /// counted in busy[worker].
  void collect(int phase, const RankTaskLists& lists, std::vector<MPI_Request>& requests, const std::vector<int>& ranks,
               long evaluation, std::vector<double>& records, std::vector<double>& seconds, std::vector<double>& busy);

  /// Master, through the window, between its own tail tasks: places the fixed lists of the workers
  /// that have announced theirs (fixed_done) for this evaluation and were not placed yet, so that
  /// the copy out of the window is part of what the tail balances. True when it placed one.
  bool place_announced(int phase, const RankTaskLists& lists, long evaluation, std::vector<double>& records,
                       std::vector<double>& seconds, std::vector<double>& busy);
  /// Worker, through the window, after its fixed list: its slots are written (fixed_word).
  void fixed_done(long evaluation) const;

  /// Worker, before it computes: posts the receives of its subtree's replies (tree).
  void expect_subtree(int phase, const RankTaskLists& lists);
  /// Both: the replies go through the node window. A worker's tasks then write their records and
  /// seconds straight into their slots (slot_of) as they run, each record while it is fresh in the
  /// worker's cache, and its reply is one word; by message a worker packs them after its last task.
  bool through_window() const { return window_ != nullptr; }
  /// Worker, through the window: task `task`'s slot in `phase` (NodeWindow::slot).
  double* slot_of(int phase, int task) const;
  /// Worker, after: its tasks' `full` records and `seconds` (in the order of its list) to rank 0
  /// (through the window: they are in the slots already, and `full` and `seconds` are not read).
  void send(int phase, const RankTaskLists& lists, const double* full, const double* seconds, long evaluation);

 private:
  /// Doubles of the records of `tasks` that cross ranks in `phase`.
  std::size_t packed_size(int phase, const std::vector<int>& tasks) const;
  std::size_t subtree_reply_size(int phase, const RankTaskLists& lists, int r) const;
  void place_record(int phase, int task, int w, const double* values, double task_seconds, std::vector<double>& records,
                    std::vector<double>& seconds, std::vector<double>& busy) const;
  /// Master, through the window: worker w's fixed list from its slots into place.
  void place_slots(int phase, const std::vector<int>& list, int w, std::vector<double>& records,
                   std::vector<double>& seconds, std::vector<double>& busy) const;

  MPI_Comm comm_;
  const RankWatch& watch_;
  CommandChannel& channel_;
  const TaskCatalogue& catalogue_;
  const NodeWindow* window_ = nullptr;  ///< the shared exchange's, else nullptr (messages)
  std::vector<std::vector<double>> receive_;  ///< master: per child its subtree's reply
  std::vector<char> placed_;                   ///< master, through the window: per worker, its fixed list placed
  std::vector<double> reply_;                  ///< worker: its subtree's reply
  std::vector<MPI_Request> from_;              ///< worker: its children's replies
};

}  // namespace raceway::scheduler
