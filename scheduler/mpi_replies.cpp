// The MPI executor's replies: what a worker gives back per evaluation (of each task's record only
// the doubles it fills, then the tasks' seconds), by message up a tree to rank 0 or through the
// node's shared-memory window; which rank holds which piece's record afterwards (output()).
#include <algorithm>
#include <atomic>
#include <stdexcept>

#include "scheduler/mpi_executor.hpp"

namespace raceway::scheduler {

// The replies' tree: the binomial tree rooted at rank 0 that MPI libraries use for small gathers
// (Open MPI's tuned MPI_Gather). Written out here because the executor needs variable sizes and a
// master that can bound its waits: MPI_Gatherv and the non-blocking MPI_Igather(v) of Open MPI
// (coll basic, libnbc) receive from every rank one by one, which is what the tree avoids: rank 0
// takes ceil(log2 P) messages per evaluation instead of P - 1. Rank r's parent is r with its lowest
// set bit cleared; its children r + 1, r + 2, r + 4, ... below that bit; it passes on the replies
// of ranks r .. subtree_end(r) - 1, in rank order.
std::vector<int> MpiExecutor::tree_children(int r) const {
  std::vector<int> children;
  const int below = r == 0 ? size_ : (r & -r);
  for (int m = 1; m < below && r + m < size_; m <<= 1) children.push_back(r + m);
  return children;
}

int MpiExecutor::subtree_end(int r) const { return r == 0 ? size_ : std::min(size_, r + (r & -r)); }

std::size_t MpiExecutor::subtree_reply_size(int phase, int r) const {
  std::size_t n = 0;
  for (int w = r; w < subtree_end(r); ++w) {
    const auto& list = tasks_of_[phase][static_cast<std::size_t>(w)];
    n += packed_size(phase, list) + list.size();
  }
  return n;
}

void MpiExecutor::place_record(int phase, int task, int w, const double* values, double task_seconds,
                               std::vector<double>& records, std::vector<double>& busy) {
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  const auto t = static_cast<std::size_t>(task);
  const auto used = static_cast<std::size_t>(catalogue_.used(phase, task));
  std::copy_n(values, used, records.data() + t * rs);
  std::fill_n(records.data() + t * rs + used, rs - used, 0.0);
  seconds_[phase][t] = task_seconds;
  busy[static_cast<std::size_t>(w)] += task_seconds;
}

void MpiExecutor::unpack_replies(int phase, int r, const double* packed, std::vector<double>& records,
                                 std::vector<double>& busy) {
  for (int w = r; w < subtree_end(r); ++w) {  // each rank's reply: its records' used doubles, then its seconds
    const auto& list = tasks_of_[phase][static_cast<std::size_t>(w)];
    const double* secs = packed + packed_size(phase, list);
    for (std::size_t i = 0; i < list.size(); ++i) {
      place_record(phase, list[i], w, packed, secs[i], records, busy);
      packed += catalogue_.used(phase, list[i]);
    }
    packed = secs + list.size();
  }
}

std::size_t MpiExecutor::packed_size(int phase, const std::vector<int>& tasks) const {
  std::size_t n = 0;
  for (const int t : tasks) n += static_cast<std::size_t>(catalogue_.used(phase, t));
  return n;
}

const std::vector<int>& MpiExecutor::output(std::span<const double> payload) {
  if (!is_master() || !attached_ || stopped_) throw std::logic_error("MpiExecutor::output is for rank 0, between attach() and stop()");
  if (payload.size() + header_size > message_size_) throw std::invalid_argument("MpiExecutor::output: payload too long");
  if (size_ > 1) {
    std::fill(message_.begin(), message_.end(), 0.0);
    message_[0] = command_output;
    std::copy(payload.begin(), payload.end(), message_.begin() + header_size);
    send_command("an output command");
  }
  // A tail task's record is on rank 0 whoever evaluated it (collect_tail).
  std::vector<int> owner = owner_[static_cast<int>(Phase::rhs)];
  for (const int t : tail_[static_cast<int>(Phase::rhs)]) owner[static_cast<std::size_t>(t)] = 0;
  holder_ = piece_holders(owner, catalogue_.parent);
  return holder_;
}

std::vector<MPI_Request> MpiExecutor::receive_subtree(int phase, std::vector<double>& reply) {
  const std::vector<int> children = tree_children(rank_);
  reply.resize(subtree_reply_size(phase, rank_));
  std::vector<MPI_Request> from(children.size());
  const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank_)];
  std::size_t at = packed_size(phase, mine) + mine.size();  // the children's replies after its own, in rank order
  for (std::size_t i = 0; i < children.size(); ++i) {
    const auto count = subtree_reply_size(phase, children[i]);
    MPI_Irecv(reply.data() + at, static_cast<int>(count), MPI_DOUBLE, children[i], phase, comm_, &from[i]);
    at += count;
  }
  return from;
}

void MpiExecutor::send_reply(int phase, const double* full, const double* seconds, std::vector<double>& reply,
                             std::vector<MPI_Request>& from) {
  const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank_)];
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  double* out = reply.data();
  for (std::size_t i = 0; i < mine.size(); ++i) out = std::copy_n(full + i * rs, catalogue_.used(phase, mine[i]), out);
  std::copy_n(seconds, mine.size(), out);
  await_master(from);  // as long as it takes while rank 0 lives, like serve()
  std::vector<MPI_Request> to(1);
  MPI_Isend(reply.data(), static_cast<int>(reply.size()), MPI_DOUBLE, rank_ & (rank_ - 1), phase, comm_, to.data());
  await_master(to);
}

// Shared replies. Why not messages on one node: rank 0's wait for a worker's reply of a few kB
// that finished at the same moment was measured at a median of 4.5-6.6 us by message (a rendezvous
// past Open MPI's 4 KiB eager limit: three legs, each waiting on the other side's progress loop)
// against 1.2-2.1 us through the window, on the heavy scene at np=2 (perf/studies/results/parallel_notes.md
// (n)). Through the window a reply is the records in their slots and one word stored after them.
void MpiExecutor::post_shared_reply(int phase, const double* full, const double* seconds) {
  const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank_)];
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  for (std::size_t i = 0; i < mine.size(); ++i) {
    double* slot = tail_slots_ + static_cast<std::size_t>(mine[i]) * tail_slot_size_;
    slot[0] = rank_;
    slot[1] = seconds[i];
    std::copy_n(full + i * rs, catalogue_.used(phase, mine[i]), slot + 2);
  }
  MPI_Win_sync(tail_window_);  // the slots before the word
  std::atomic_ref<std::int64_t>(reply_done_[static_cast<std::size_t>(rank_) * window_word_stride + reply_word])
      .store(evaluation_, std::memory_order_release);
}

void MpiExecutor::collect_shared_replies(int phase, std::vector<double>& records, std::vector<double>& busy) {
  await_worker_words(reply_word, evaluation_, "answer", phase);
  commands_taken_by_all_ = commands_;  // a worker takes a command before it replies to it
  MPI_Win_sync(tail_window_);  // the words before the slots
  for (int w = 1; w < size_; ++w)
    for (const int task : tasks_of_[phase][static_cast<std::size_t>(w)]) {
      const double* slot = tail_slots_ + static_cast<std::size_t>(task) * tail_slot_size_;
      place_record(phase, task, w, slot + 2, slot[1], records, busy);
    }
}

std::vector<int> piece_holders(std::span<const int> owner, std::span<const int> parent) {
  if (parent.empty()) return {owner.begin(), owner.end()};
  const int pieces = *std::max_element(parent.begin(), parent.end()) + 1;
  std::vector<int> tasks(static_cast<std::size_t>(pieces), 0), holder(static_cast<std::size_t>(pieces), 0);
  for (std::size_t t = 0; t < parent.size(); ++t) {
    const auto p = static_cast<std::size_t>(parent[t]);
    ++tasks[p];
    holder[p] = owner[t];
  }
  for (std::size_t p = 0; p < holder.size(); ++p)
    if (tasks[p] > 1) holder[p] = 0;  // a piece cut into tasks: the master combines its records
  return holder;
}

}  // namespace raceway::scheduler
