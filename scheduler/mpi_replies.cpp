// The MPI executor's replies: what a worker sends back per evaluation (of each task's record only
// the doubles it fills, then the tasks' seconds) and the tree they travel to rank 0; which rank
// holds which piece's record afterwards (output()).
#include <algorithm>
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

void MpiExecutor::unpack_replies(int phase, int r, const double* packed, std::vector<double>& records,
                                 std::vector<double>& busy) {
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  auto& seconds = seconds_[phase];
  for (int w = r; w < subtree_end(r); ++w) {  // each rank's reply: its records' used doubles, then its seconds
    const auto& list = tasks_of_[phase][static_cast<std::size_t>(w)];
    const double* secs = packed + packed_size(phase, list);
    for (std::size_t i = 0; i < list.size(); ++i) {
      const auto t = static_cast<std::size_t>(list[i]);
      const auto used = static_cast<std::size_t>(catalogue_.used(phase, list[i]));
      std::copy_n(packed, used, records.data() + t * rs);
      std::fill_n(records.data() + t * rs + used, rs - used, 0.0);
      packed += used;
      seconds[t] = secs[i];
      busy[static_cast<std::size_t>(w)] += secs[i];
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
    broadcast(message_.data(), static_cast<int>(message_size_), "an output command");
  }
  // A tail task's record is on rank 0 whoever evaluated it (collect_tail).
  std::vector<int> owner = owner_[static_cast<int>(Phase::rhs)];
  for (const int t : tail_[static_cast<int>(Phase::rhs)]) owner[static_cast<std::size_t>(t)] = 0;
  holder_ = piece_holders(owner, catalogue_.parent);
  return holder_;
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
