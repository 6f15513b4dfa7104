// The plan's tail, claimed on demand within one evaluation (MpiExecutorOptions::tail_share).
//
// Why: the plans balance smoothed task costs, but each rank's task time scatters from one
// evaluation to the next by a few % of its load, and every evaluation waits for the slowest rank.
// The scatter does not carry over from one evaluation to the next (perf/studies/results/parallel_notes.md,
// section (j)), so no plan removes it; handing the last part of the work to whichever rank is free
// first does.
//
// How: the plan marks its tail (mark_tail: of each rank's tasks its cheapest, tail_share of its
// load); each rank's part of it stays its own, ordered largest first, and every rank knows all the
// parts from the plan's owners. In an evaluation each rank evaluates its fixed list, then claims
// its own tail tasks from the front, then, when its part is gone, steals from the back of the part
// with the most left (the smallest tasks, which fill the gaps best), until every part is gone. A
// part's claims are a word in rank 0's memory, a shared-memory window: front and back index,
// changed by compare-and-swap (no message, nothing rank 0 has to serve). When the ranks are
// balanced each evaluates its own part, the same tasks at every evaluation, and only what the
// scatter needs moves; at many ranks the claims spread over P cache lines instead of one. Rank 0
// writes its tail records in place; a worker writes each record, with its rank and seconds, to its
// task's slot in the window, then (after MPI_Win_sync) gives its usual reply for its fixed list (a
// message, or through the same window: mpi_replies.cpp). Once rank 0 has every reply, it copies the
// workers' slots into place. Every record lands at its task and the equations sum the records in
// task order: the bits depend on no rank count, plan or order of the claims.
//
// Why not messages: a claim protocol over point-to-point messages needs rank 0 to look for claims
// between its own tasks; with Open MPI's yield_when_idle (the default when oversubscribed, and
// perf/calibration/run_scaling_benchmarks.sh's setting) every look that finds nothing yields the core, 1-2 us
// each here, and about a hundred looks per evaluation cost more than the imbalance they remove
// (measured, parallel_notes.md (j)). A window needs every rank on one node (shared memory): on
// several nodes the tail is off (said at the start) and the fixed plan runs as before.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>

#include "scheduler/mpi_executor.hpp"

namespace raceway::scheduler {

namespace {

// The claim words are lock-free std::atomic_ref, written by hand instead of MPI_Compare_and_swap:
// Open MPI's shared-memory windows (osc sm) do their atomics under a spin lock, and a rank stopped
// (SIGSTOP) while holding it would hold rank 0 in its next claim for ever, beyond --rank-timeout;
// a single atomic instruction cannot be left half done.
static_assert(std::atomic_ref<std::int64_t>::is_always_lock_free, "the claim words must be lock-free");

// A part's claim word: the front index in the low 32 bits, the back (one past the last) above.
constexpr std::int64_t word(std::int64_t front, std::int64_t back) { return back << 32 | front; }
constexpr std::int64_t front_of(std::int64_t w) { return w & 0xffffffff; }
constexpr std::int64_t back_of(std::int64_t w) { return w >> 32; }

/// Takes one position of a part, from the front or the back; -1 when the part is empty.
std::int64_t take(std::int64_t& w_ref, bool from_front) {
  std::atomic_ref<std::int64_t> w(w_ref);
  std::int64_t now = w.load(std::memory_order_acquire);
  for (;;) {
    const std::int64_t f = front_of(now), b = back_of(now);
    if (f >= b) return -1;
    if (w.compare_exchange_weak(now, from_front ? word(f + 1, b) : word(f, b - 1), std::memory_order_acq_rel))
      return from_front ? f : b - 1;
  }
}

}  // namespace

void MpiExecutor::open_node_window(bool tail, bool shared_exchange, int record_size) {
  if (!tail && !shared_exchange) return;
  MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node_comm_);
  int node_size = 0;
  MPI_Comm_size(node_comm_, &node_size);
  if (node_size != size_) {  // the same answer on every rank: some rank is on another node
    MPI_Comm_free(&node_comm_);
    return;
  }
  // On rank 0: per rank its claim word and its reply line (the last evaluation it replied to, the
  // commands it has taken), a cache line each; with the shared exchange a command line (commands
  // written) and the command buffer; then per task a slot of rank, seconds and a record of the
  // largest phase's size.
  tail_slot_size_ = 2 + static_cast<std::size_t>(record_size);
  const auto whole_lines = [](std::size_t n) { return (n + window_word_stride - 1) / window_word_stride * window_word_stride; };
  std::size_t words = 2 * static_cast<std::size_t>(size_) * window_word_stride;
  const std::size_t command_at = words;
  if (shared_exchange) words += window_word_stride + whole_lines(message_size_);
  const auto doubles = is_master() ? words + static_cast<std::size_t>(catalogue_.task_count) * tail_slot_size_ : 0;
  void* mine = nullptr;
  MPI_Win_allocate_shared(static_cast<MPI_Aint>(doubles * sizeof(double)), sizeof(double), MPI_INFO_NULL, node_comm_,
                          &mine, &tail_window_);
  MPI_Aint bytes = 0;
  int unit = 0;
  void* base = nullptr;
  MPI_Win_shared_query(tail_window_, 0, &bytes, &unit, &base);
  tail_counter_ = static_cast<std::int64_t*>(base);  // the window's memory is untyped: int64s, then doubles
  // MPI does not promise zeroed memory: no word may start out naming an evaluation or a command.
  // Rank 0 clears them, and no rank reads one before the barrier.
  if (is_master()) std::fill_n(tail_counter_, words, std::int64_t{0});
  MPI_Barrier(node_comm_);
  if (shared_exchange) {
    reply_done_ = tail_counter_ + static_cast<std::size_t>(size_) * window_word_stride;
    command_word_ = tail_counter_ + command_at;
    command_buffer_ = reinterpret_cast<double*>(command_word_ + window_word_stride);
  }
  tail_on_ = tail;
  tail_slots_ = reinterpret_cast<double*>(static_cast<char*>(base) + words * sizeof(std::int64_t));
  MPI_Win_lock_all(MPI_MODE_NOCHECK, tail_window_);  // one passive epoch for the whole run
}

void MpiExecutor::encode_tail(std::vector<int>& owner, const std::vector<double>& cost) const {
  const std::vector<int> plan = owner;
  const std::vector<int> tail = mark_tail(owner, cost, options_.tail_share);  // largest first
  std::vector<int> count(static_cast<std::size_t>(size_), 0);
  for (const int t : tail) {  // rank r's i-th: shared_task - (i * P + r)
    const int r = plan[static_cast<std::size_t>(t)];
    owner[static_cast<std::size_t>(t)] = shared_task - (count[static_cast<std::size_t>(r)]++ * size_ + r);
  }
}

void MpiExecutor::decode_tail(int phase, const std::vector<int>& owner) {
  std::vector<std::vector<int>> part(static_cast<std::size_t>(size_));
  for (std::size_t t = 0; t < owner.size(); ++t) {
    if (owner[t] >= 0) continue;
    const int code = shared_task - owner[t];
    auto& p = part[static_cast<std::size_t>(code % size_)];
    const auto at = static_cast<std::size_t>(code / size_);
    if (p.size() <= at) p.resize(at + 1, -1);
    p[at] = static_cast<int>(t);
  }
  auto& tail = tail_[phase];
  auto& start = tail_start_[phase];
  tail.clear();
  start.assign(1, 0);
  for (const auto& p : part) {
    tail.insert(tail.end(), p.begin(), p.end());
    start.push_back(static_cast<int>(tail.size()));
  }
}

void MpiExecutor::close_tail_window() {
  if (tail_window_ != MPI_WIN_NULL) {
    MPI_Win_unlock_all(tail_window_);
    MPI_Win_free(&tail_window_);
  }
  if (node_comm_ != MPI_COMM_NULL) MPI_Comm_free(&node_comm_);
}

void MpiExecutor::reset_tail_claims(int phase) {
  const auto& start = tail_start_[phase];
  for (std::size_t r = 0; r + 1 < start.size(); ++r)
    std::atomic_ref<std::int64_t>(tail_counter_[r * window_word_stride])
        .store(word(start[r], start[r + 1]), std::memory_order_release);
}

std::int64_t MpiExecutor::claim_tail_position(int phase) {
  // Its own part from the front; then the back of the part with the most left.
  const auto mine = static_cast<std::size_t>(rank_) * window_word_stride;
  if (const std::int64_t own = take(tail_counter_[mine], true); own >= 0) return own;
  for (;;) {
    std::size_t victim = 0;
    std::int64_t most = 0;
    for (std::size_t r = 0; r + 1 < tail_start_[phase].size(); ++r) {
      const std::int64_t w =
          std::atomic_ref<std::int64_t>(tail_counter_[r * window_word_stride]).load(std::memory_order_acquire);
      if (back_of(w) - front_of(w) > most) most = back_of(w) - front_of(w), victim = r;
    }
    if (most == 0) return -1;
    if (const std::int64_t stolen = take(tail_counter_[victim * window_word_stride], false); stolen >= 0) return stolen;
  }
}

double MpiExecutor::evaluate_tail(int phase, std::span<const double> context, const TaskFunction& function,
                                  double* records, double* seconds) {
  const auto& tail = tail_[phase];
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  double spent = 0;
  auto last = std::chrono::steady_clock::now();  // a task's seconds include its claim
  for (std::int64_t position; (position = claim_tail_position(phase)) >= 0;) {
    const auto t = static_cast<std::size_t>(tail[static_cast<std::size_t>(position)]);
    double* slot = tail_slots_ + t * tail_slot_size_;
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
  for (const int task : tail) {
    const auto t = static_cast<std::size_t>(task);
    const double* slot = tail_slots_ + t * tail_slot_size_;
    const auto r = static_cast<std::size_t>(slot[0]);
    if (r == 0) continue;  // rank 0's own, already in place
    std::copy_n(slot + 2, rs, records.data() + t * rs);
    seconds_[phase][t] = slot[1];
    busy[r] += slot[1];
  }
}

}  // namespace raceway::scheduler
