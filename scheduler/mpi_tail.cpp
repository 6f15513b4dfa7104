// The plan's tail, claimed on demand within one evaluation (MpiExecutorOptions::tail_share).
//
// Why: the plans balance smoothed task costs, but each rank's task time scatters from one
// evaluation to the next by a few % of its load, and every evaluation waits for the slowest rank.
// The scatter does not carry over from one evaluation to the next (perf/results/parallel_notes.md,
// section (j)), so no plan removes it; handing the last part of the work to whichever rank is free
// first does.
//
// How: the plan marks its tail (mark_tail: of each rank's tasks its cheapest, tail_share of its
// load) and orders it, largest first; every rank knows the order from the plan's owners. In an
// evaluation each rank evaluates its fixed list, then claims tail positions one by one from a
// counter in rank 0's memory (an atomic add on a shared-memory window: no message, and nothing
// rank 0 has to serve) until the counter passes the tail's end. Rank 0
// writes its tail records in place; a worker writes each record, with its rank and seconds, to the
// position's slot in the window, then (after MPI_Win_sync) sends its usual reply with its fixed
// list. Once rank 0 has every reply, it copies the workers' slots into place. Every record lands at
// its task and the equations sum the records in task order: the bits depend on no rank count,
// plan or order of the claims.
//
// Why not messages: a claim protocol over point-to-point messages needs rank 0 to look for claims
// between its own tasks; with Open MPI's yield_when_idle (the default when oversubscribed, and
// perf/run_scaling_benchmarks.sh's setting) every look that finds nothing yields the core, 1-2 us
// each here, and about a hundred looks per evaluation cost more than the imbalance they remove
// (measured, parallel_notes.md (j)). A window needs every rank on one node (shared memory): on
// several nodes the tail is off (said at the start) and the fixed plan runs as before.
#include <atomic>
#include <chrono>
#include <cstdint>

#include "scheduler/mpi_executor.hpp"

namespace raceway::scheduler {

namespace {

// The claim counter is a lock-free std::atomic_ref, written by hand instead of MPI_Fetch_and_op:
// Open MPI's shared-memory windows (osc sm) do a fetch-and-op under a spin lock, and a rank stopped
// (SIGSTOP) while holding it would hold rank 0 in its next claim for ever, beyond --rank-timeout;
// a single atomic instruction cannot be left half done.
static_assert(std::atomic_ref<std::int64_t>::is_always_lock_free, "the claim counter must be lock-free");

}  // namespace

void MpiExecutor::open_tail_window(bool wanted, int record_size) {
  if (!wanted) return;
  MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node_comm_);
  int node_size = 0;
  MPI_Comm_size(node_comm_, &node_size);
  if (node_size != size_) {  // the same answer on every rank: some rank is on another node
    MPI_Comm_free(&node_comm_);
    return;
  }
  // On rank 0: the claim counter (one int64), then per tail position (at most every task) a slot of
  // rank, seconds and a record of the largest phase's size.
  tail_slot_size_ = 2 + static_cast<std::size_t>(record_size);
  const auto doubles = is_master() ? 1 + static_cast<std::size_t>(catalogue_.task_count) * tail_slot_size_ : 0;
  void* mine = nullptr;
  MPI_Win_allocate_shared(static_cast<MPI_Aint>(doubles * sizeof(double)), sizeof(double), MPI_INFO_NULL, node_comm_,
                          &mine, &tail_window_);
  MPI_Aint bytes = 0;
  int unit = 0;
  void* base = nullptr;
  MPI_Win_shared_query(tail_window_, 0, &bytes, &unit, &base);
  tail_counter_ = static_cast<std::int64_t*>(base);  // the window's memory is untyped: an int64, then doubles
  tail_slots_ = reinterpret_cast<double*>(static_cast<char*>(base) + sizeof(std::int64_t));
  MPI_Win_lock_all(MPI_MODE_NOCHECK, tail_window_);  // one passive epoch for the whole run
  if (is_master()) reset_tail_claims();
}

void MpiExecutor::close_tail_window() {
  if (tail_window_ != MPI_WIN_NULL) {
    MPI_Win_unlock_all(tail_window_);
    MPI_Win_free(&tail_window_);
  }
  if (node_comm_ != MPI_COMM_NULL) MPI_Comm_free(&node_comm_);
}

void MpiExecutor::reset_tail_claims() { std::atomic_ref<std::int64_t>(*tail_counter_).store(0, std::memory_order_release); }

double MpiExecutor::evaluate_tail(int phase, std::span<const double> context, const TaskFunction& function,
                                  double* records, double* seconds) {
  const auto& tail = tail_[phase];
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  std::atomic_ref<std::int64_t> counter(*tail_counter_);
  double spent = 0;
  auto last = std::chrono::steady_clock::now();  // a task's seconds include its claim
  for (;;) {
    const std::int64_t position = counter.fetch_add(1, std::memory_order_acq_rel);
    if (position >= static_cast<std::int64_t>(tail.size())) break;
    const auto t = static_cast<std::size_t>(tail[static_cast<std::size_t>(position)]);
    double* slot = tail_slots_ + static_cast<std::size_t>(position) * tail_slot_size_;
    // Rank 0 writes in place; a worker to the slot, with its rank and the seconds.
    run_task(phase, context, function, static_cast<int>(t), std::span<double>(records ? records + t * rs : slot + 2, rs));
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last).count();
    last = now;
    spent += s;
    slot[0] = rank_;
    (records ? seconds[t] : slot[1]) = s;
  }
  if (!records) MPI_Win_sync(tail_window_);  // the slots are written before this rank's reply leaves
  return spent;
}

void MpiExecutor::collect_tail(int phase, std::vector<double>& records, std::vector<double>& busy) {
  MPI_Win_sync(tail_window_);  // every reply is in: the workers' slots are written
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  const auto& tail = tail_[phase];
  for (std::size_t i = 0; i < tail.size(); ++i) {
    const double* slot = tail_slots_ + i * tail_slot_size_;
    const auto r = static_cast<std::size_t>(slot[0]);
    if (r == 0) continue;  // rank 0's own, already in place
    const auto t = static_cast<std::size_t>(tail[i]);
    std::copy_n(slot + 2, rs, records.data() + t * rs);
    seconds_[phase][t] = slot[1];
    busy[r] += slot[1];
  }
}

}  // namespace raceway::scheduler
