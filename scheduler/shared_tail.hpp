// The plan's tail in a run: the claim words (scheduler/tail_claims.hpp) and the task slots of the
// node window (scheduler/node_window.hpp). Every rank done with its fixed list claims tail tasks
// until none is left; rank 0 writes its tail records in place, a worker streams each record, with
// its rank and seconds, into its task's slot, then (after a memory barrier) gives its usual reply.
// Between its claims rank 0 places the fixed lists the workers have announced (the `between`
// hook), so the copy out of the window is shared out by the tail like a task; once rank 0 has every
// reply, it copies the workers' tail slots (and any fixed list not yet placed) into place.
#pragma once

#include <span>
#include <vector>

#include "scheduler/executor.hpp"
#include "scheduler/node_window.hpp"
#include "scheduler/task_clock.hpp"
#include "scheduler/tail_claims.hpp"

namespace raceway::scheduler {

class SharedTail {
 public:
  /// Both, after the node window is open (a tail needs it): the plans get a tail of `share`.
  void open(const NodeWindow& window, int rank, int ranks, double share);
  bool is_on() const { return window_ != nullptr; }
  double share() const { return window_ ? share_ : 0.0; }

  /// Master: marks the tail of plan `owner` under `cost` (encode_tail).
  void mark(std::vector<int>& owner, std::span<const double> cost) const;
  /// Both: the phase's tail from a plan's owners (decode_tail; none when no owner is negative).
  void adopt(int phase, std::span<const int> owner) { parts_[phase] = decode_tail(owner, ranks_); }
  const TailParts& parts(int phase) const { return parts_[phase]; }
  bool has_tail(int phase) const { return !parts_[phase].empty(); }
  /// Master, before the command that starts an evaluation: every part whole.
  void reset(int phase) { claims_.reset(parts_[phase]); }

  /// Claims and evaluates tail tasks until none is left, with run(task, record): rank 0's into
  /// `records` (at their task, record_size each) and `seconds`, a worker's (records nullptr) into the
  /// slots. Before each claim, between(): true when it did work of its own (rank 0 placing a
  /// worker's records), which then counts in no task's seconds. Returns the seconds this rank spent
  /// on the tasks (each task's include its claim).
  template <class Run, class Between>
  double evaluate(int phase, std::size_t record_size, Run run, double* records, double* seconds, Between between);
  /// Master, after every reply: the workers' tail records from the slots into place.
  void collect(int phase, std::size_t record_size, std::vector<double>& records, std::vector<double>& seconds,
               std::vector<double>& busy) const;

 private:
  const NodeWindow* window_ = nullptr;
  TailClaims claims_;
  int rank_ = 0, ranks_ = 1;
  double share_ = 0;
  TailParts parts_[phase_count];
};

template <class Run, class Between>
double SharedTail::evaluate(int phase, std::size_t record_size, Run run, double* records, double* seconds,
                            Between between) {
  const auto& tail = parts_[phase].tasks;
  const std::size_t stride = NodeWindow::slot_stride(record_size);
  std::vector<double> scratch(records ? 0 : stride, 0.0);  // a worker's slot, streamed into the window
  double spent = 0;
  TaskClock clock;
  for (;;) {
    if (between()) clock.lap();  // its time is no task's
    const std::int64_t position = claims_.claim(rank_);
    if (position < 0) break;
    const int task = tail[static_cast<std::size_t>(position)];
    const auto t = static_cast<std::size_t>(task);
    double* slot = window_->slot(task, stride);
    run(task, std::span<double>(records ? records + t * record_size : scratch.data() + 2, record_size));
    const double s = clock.lap();
    spent += s;
    if (records) {
      slot[0] = rank_;
      seconds[t] = s;
    } else {
      scratch[0] = rank_;
      scratch[1] = s;
      NodeWindow::stream_slot(slot, scratch.data(), stride);
    }
  }
  if (!records) window_->sync();  // the slots are written before this rank's reply leaves
  return spent;
}

}  // namespace raceway::scheduler
