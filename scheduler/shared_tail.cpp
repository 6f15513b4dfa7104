#include "scheduler/shared_tail.hpp"

#include <algorithm>

namespace raceway::scheduler {

void SharedTail::open(const NodeWindow& window, int rank, int ranks, double share) {
  if (!window.is_open()) return;
  window_ = &window;
  claims_ = TailClaims(window.claim_words(), NodeWindow::word_stride, ranks);
  rank_ = rank;
  ranks_ = ranks;
  share_ = share;
}

void SharedTail::mark(std::vector<int>& owner, std::span<const double> cost) const {
  encode_tail(owner, cost, share_, ranks_);
}

void SharedTail::collect(int phase, std::size_t record_size, std::vector<double>& records, std::vector<double>& seconds,
                         std::vector<double>& busy) const {
  window_->sync();  // every reply is in: the workers' slots are written
  const std::size_t stride = NodeWindow::slot_stride(record_size);
  for (const int task : parts_[phase].tasks) {
    const auto t = static_cast<std::size_t>(task);
    const double* slot = window_->slot(task, stride);
    const auto r = static_cast<std::size_t>(slot[0]);
    if (r == 0) continue;  // rank 0's own, already in place
    std::copy_n(slot + 2, record_size, records.data() + t * record_size);
    seconds[t] = slot[1];
    busy[r] += slot[1];
  }
}

}  // namespace raceway::scheduler
