// The plan's tail, handed out on demand within one evaluation (MpiExecutorOptions::tail_share).
//
// Why: the plans balance smoothed task costs, but each rank's task time scatters from one
// evaluation to the next by a few % of its load, and every evaluation waits for the slowest rank.
// The scatter is not predictable from the previous evaluation (perf/results/parallel_notes.md,
// section (j)), so no plan removes it; handing out the last part of the work to whichever rank is
// free first does.
//
// Protocol of an evaluation with a tail (the plan marks the tail tasks shared_task; the workers
// know them from the plan's owners, rank 0 hands them out in mark_tail's order):
//   worker w, claim_ahead tasks before the end of its fixed list: a claim (tag claim_tag: the flag
//     1, nothing else);
//   rank 0, between its own tasks (at most every poll_interval) and between the tail tasks it takes
//     itself once its list is done: for each claim that arrived, the records it carries into place,
//     then an answer (tag answer_tag: count, tasks): the next tail tasks, about chunk_seconds of
//     work, or none (count 0);
//   worker, on an answer with tasks: at once the next claim (its answer comes while it computes),
//     carrying the records of the chunk it computed before (each task's used doubles, then the
//     tasks' seconds); then it computes the chunk. On none: one last message (flag 0) with the
//     records of the chunk it computed last, if any; then its reply up the tree, as without a tail
//     (its fixed list only).
// So rank 0 knows every message's size: the message after w's k-th claim carries the chunk it
// answered w's (k-1)-th claim with. Each record lands at its task and the equations sum the
// records in task order: the bits depend on no rank count, plan or order of the claims.
//
// Rank 0's waits stay bounded (rank_timeout, naming the silent ranks); its answers are a few ints
// (MPI_Send of a message far below the eager limit: it returns without the receiver). A worker
// waits for rank 0 as long as it takes, as in serve().
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "scheduler/mpi_executor.hpp"

namespace raceway::scheduler {

namespace {

constexpr int claim_tag = 100, answer_tag = 101;  // the replies' tags are the phases (0-2)
// A worker's chunk: tail tasks until their smoothed cost reaches this (at least one task). Two
// messages per chunk cost a few us on both sides; the chunk is what two ranks may finish apart.
constexpr double chunk_seconds = 6e-6;
// Rank 0 looks for claims between its own tasks at most this often (a look costs MPI progress,
// about 0.1-0.3 us; a claim waits at most this plus one of rank 0's tasks).
constexpr double poll_interval = 3e-6;

using clock_type = std::chrono::steady_clock;

}  // namespace

/// Rank 0's side of one evaluation with a tail.
class MpiExecutor::TailServer {
 public:
  TailServer(MpiExecutor& ex, int phase, std::vector<double>& records, std::vector<double>& busy)
      : ex_(ex), phase_(phase), records_(records), busy_(busy), tail_(ex.tail_[phase]),
        workers_(static_cast<std::size_t>(ex.size_)), in_(static_cast<std::size_t>(ex.size_ - 1), MPI_REQUEST_NULL),
        index_(in_.size()) {
    const auto& cost = ex.cost_[phase];
    cost_ = cost.size() == static_cast<std::size_t>(ex.catalogue_.task_count) ? &cost : &ex.tail_cost_[phase];
    for (int w = 1; w < ex.size_; ++w) post(w);
  }
  /// Serves the claims that have arrived.
  void poll() {
    int count = 0;
    MPI_Testsome(static_cast<int>(in_.size()), in_.data(), &count, index_.data(), MPI_STATUSES_IGNORE);
    for (int i = 0; i < count && count != MPI_UNDEFINED; ++i) serve(index_[static_cast<std::size_t>(i)] + 1);
  }
  /// The next tail task for rank 0 itself; false when the tail is handed out.
  bool take(int& task) {
    if (next_ >= tail_.size()) return false;
    task = tail_[next_++];
    return true;
  }
  /// Every worker has had its last answer and sent its last records.
  bool done() const { return finished_ == ex_.size_ - 1; }
  /// The workers whose last message has not arrived (for the diagnosis).
  std::vector<int> waiting() const {
    std::vector<int> ranks;
    for (int w = 1; w < ex_.size_; ++w)
      if (!workers_[static_cast<std::size_t>(w)].finished) ranks.push_back(w);
    return ranks;
  }

 private:
  struct Worker {
    std::vector<double> message;
    std::vector<int> carry, last;  ///< the chunk its next message carries; the chunk it computes
    bool finished = false;
  };

  /// The receive of w's next message (its records: carry's).
  void post(int w) {
    auto& k = workers_[static_cast<std::size_t>(w)];
    k.message.resize(1 + ex_.packed_size(phase_, k.carry) + k.carry.size());
    MPI_Irecv(k.message.data(), static_cast<int>(k.message.size()), MPI_DOUBLE, w, claim_tag, ex_.comm_,
              &in_[static_cast<std::size_t>(w - 1)]);
  }

  /// w's message arrived: its records into place, then (a claim) an answer and the next receive.
  void serve(int w) {
    auto& k = workers_[static_cast<std::size_t>(w)];
    const auto rs = static_cast<std::size_t>(ex_.catalogue_.record_size[static_cast<std::size_t>(phase_)]);
    const double* packed = k.message.data() + 1;
    const double* seconds = packed + ex_.packed_size(phase_, k.carry);
    for (std::size_t i = 0; i < k.carry.size(); ++i) {
      const auto t = static_cast<std::size_t>(k.carry[i]);
      const auto used = static_cast<std::size_t>(ex_.catalogue_.used(phase_, k.carry[i]));
      std::copy_n(packed, used, records_.data() + t * rs);
      std::fill_n(records_.data() + t * rs + used, rs - used, 0.0);
      packed += used;
      ex_.seconds_[phase_][t] = seconds[i];
      busy_[static_cast<std::size_t>(w)] += seconds[i];
    }
    if (k.message[0] == 0) {  // its last message
      k.finished = true, ++finished_;
      return;
    }
    std::vector<int> chunk;  // the next tail tasks, about chunk_seconds of work
    for (double c = 0; next_ < tail_.size() && (chunk.empty() || c < chunk_seconds); ++next_) {
      chunk.push_back(tail_[next_]);
      c += (*cost_)[static_cast<std::size_t>(tail_[next_])];
    }
    std::vector<int> answer{static_cast<int>(chunk.size())};
    answer.insert(answer.end(), chunk.begin(), chunk.end());
    MPI_Send(answer.data(), static_cast<int>(answer.size()), MPI_INT, w, answer_tag, ex_.comm_);
    k.carry = std::move(k.last);
    k.last = std::move(chunk);
    if (k.last.empty() && k.carry.empty())  // none, and nothing computed to send: w is done
      k.finished = true, ++finished_;
    else
      post(w);  // the next claim, or (after none) the last records
  }

  MpiExecutor& ex_;
  int phase_;
  std::vector<double>& records_;
  std::vector<double>& busy_;
  const std::vector<int>& tail_;
  const std::vector<double>* cost_;
  std::size_t next_ = 0;
  int finished_ = 0;
  std::vector<Worker> workers_;  ///< by rank (0 unused)
  std::vector<MPI_Request> in_;  ///< rank w's next message at w - 1
  std::vector<int> index_;
};

void MpiExecutor::evaluate_with_tail(int phase, std::span<const double> context, const TaskFunction& task,
                                     std::vector<double>& records, std::vector<double>& busy,
                                     std::vector<MPI_Request>& requests, const std::vector<int>& request_rank) {
  TailServer server(*this, phase, records, busy);
  auto& seconds = seconds_[phase];
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  auto polled = clock_type::now();
  evaluate_own(phase, context, static_cast<int>(rs), task, records.data(), seconds.data(), true, [&](std::size_t) {
    if (const auto now = clock_type::now(); std::chrono::duration<double>(now - polled).count() >= poll_interval) {
      server.poll();
      polled = now;
    }
  });
  for (const int t : tasks_of_[phase][0]) busy[0] += seconds[static_cast<std::size_t>(t)];
  if (capacity_[0] > 0)  // rank 0 takes tail tasks too (not with --master-share 0)
    for (int t = 0; server.take(t);) {
      const auto at = static_cast<std::size_t>(t);
      seconds[at] = run_task(phase, context, task, t, std::span<double>(records.data() + at * rs, rs));
      busy[0] += seconds[at];
      server.poll();
    }
  // Bounded: the command, the tree replies, and every worker's claims until its last message.
  const auto deadline = clock_type::now() + std::chrono::duration<double>(options_.rank_timeout);
  for (;;) {
    server.poll();
    int complete = 0;
    MPI_Testall(static_cast<int>(requests.size()), requests.data(), &complete, MPI_STATUSES_IGNORE);
    if (complete && server.done()) return;
    if (clock_type::now() < deadline) continue;
    std::vector<int> silent = server.waiting();
    for (std::size_t i = 0; i < requests.size(); ++i) {
      int done = 0;
      MPI_Test(&requests[i], &done, MPI_STATUS_IGNORE);
      if (!done && request_rank[i] >= 0) silent.push_back(request_rank[i]);
    }
    std::sort(silent.begin(), silent.end());
    silent.erase(std::unique(silent.begin(), silent.end()), silent.end());
    std::string names;
    for (const int r : silent) names += (names.empty() ? "" : ", ") + silent_rank(r);
    char timeout[32];
    std::snprintf(timeout, sizeof timeout, "%g", options_.rank_timeout);
    fail((names.empty() ? std::string("the workers") : names) + " did not answer the " +
         (phase == 0 ? "rhs" : "jacobian") + " evaluation " + std::to_string(evaluation_) + " within " + timeout +
         " s (--rank-timeout): stopped, hung or lost; ending the job");
  }
}

void MpiExecutor::send_claim(double flag, const std::vector<double>& packed) {
  std::vector<double> message{flag};
  message.insert(message.end(), packed.begin(), packed.end());
  MPI_Send(message.data(), static_cast<int>(message.size()), MPI_DOUBLE, 0, claim_tag, comm_);
}

void MpiExecutor::claim_tail(int phase, std::span<const double> context, const TaskFunction& function) {
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  std::vector<int> answer(tail_[phase].size() + 1), computed;
  std::vector<double> record(rs), packed, seconds;
  for (;;) {  // the first claim went out from the fixed list
    MPI_Recv(answer.data(), static_cast<int>(answer.size()), MPI_INT, 0, answer_tag, comm_, MPI_STATUS_IGNORE);
    const auto count = static_cast<std::size_t>(answer[0]);
    if (count == 0) break;
    send_claim(1, packed);  // the next claim, with the records of the chunk before
    packed.clear();
    seconds.clear();
    computed.assign(answer.begin() + 1, answer.begin() + 1 + static_cast<std::ptrdiff_t>(count));
    for (const int t : computed) {
      seconds.push_back(run_task(phase, context, function, t, record));
      packed.insert(packed.end(), record.begin(), record.begin() + catalogue_.used(phase, t));
    }
    packed.insert(packed.end(), seconds.begin(), seconds.end());
  }
  if (!computed.empty()) send_claim(0, packed);
}

}  // namespace raceway::scheduler
