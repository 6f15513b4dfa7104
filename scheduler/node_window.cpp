#include "scheduler/node_window.hpp"

#include <algorithm>

namespace raceway::scheduler {

void NodeWindow::open(MPI_Comm comm, int task_count, std::size_t command_size, int record_size, bool shared_exchange) {
  int rank = 0, size = 1, node_size = 0;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  MPI_Comm_split_type(comm, MPI_COMM_TYPE_SHARED, rank, MPI_INFO_NULL, &node_comm_);
  MPI_Comm_size(node_comm_, &node_size);
  if (node_size != size) {  // the same answer on every rank: some rank is on another node
    MPI_Comm_free(&node_comm_);
    return;
  }
  slot_size_ = 2 + static_cast<std::size_t>(record_size);
  const auto whole_lines = [](std::size_t n) { return (n + word_stride - 1) / word_stride * word_stride; };
  std::size_t words = 2 * static_cast<std::size_t>(size) * word_stride;
  const std::size_t command_at = words;
  if (shared_exchange) words += word_stride + whole_lines(command_size);
  const auto doubles = rank == 0 ? words + static_cast<std::size_t>(task_count) * slot_size_ : 0;
  void* mine = nullptr;
  MPI_Win_allocate_shared(static_cast<MPI_Aint>(doubles * sizeof(double)), sizeof(double), MPI_INFO_NULL, node_comm_,
                          &mine, &window_);
  MPI_Aint bytes = 0;
  int unit = 0;
  void* base = nullptr;
  MPI_Win_shared_query(window_, 0, &bytes, &unit, &base);
  words_ = static_cast<std::int64_t*>(base);  // the window's memory is untyped: int64s, then doubles
  // MPI does not promise zeroed memory: no word may start out naming an evaluation or a command.
  // Rank 0 clears them, and no rank reads one before the barrier.
  if (rank == 0) std::fill_n(words_, words, std::int64_t{0});
  MPI_Barrier(node_comm_);
  reply_lines_ = words_ + static_cast<std::size_t>(size) * word_stride;
  if (shared_exchange) {
    command_word_ = words_ + command_at;
    command_buffer_ = reinterpret_cast<double*>(command_word_ + word_stride);
  }
  slots_ = reinterpret_cast<double*>(static_cast<char*>(base) + words * sizeof(std::int64_t));
  MPI_Win_lock_all(MPI_MODE_NOCHECK, window_);  // one passive epoch for the whole run
}

void NodeWindow::sync() const { MPI_Win_sync(window_); }

void NodeWindow::close() {
  if (window_ != MPI_WIN_NULL) {
    MPI_Win_unlock_all(window_);
    MPI_Win_free(&window_);
  }
  if (node_comm_ != MPI_COMM_NULL) MPI_Comm_free(&node_comm_);
  words_ = reply_lines_ = command_word_ = nullptr;
  command_buffer_ = slots_ = nullptr;
}

}  // namespace raceway::scheduler
