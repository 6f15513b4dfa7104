#include "scheduler/node_window.hpp"

#include <algorithm>
#include <cstdint>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace raceway::scheduler {

namespace {
constexpr std::uintptr_t line_bytes = NodeWindow::word_stride * sizeof(std::int64_t);
}  // namespace

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
  std::size_t words = 2 * static_cast<std::size_t>(size) * word_stride;
  const std::size_t command_at = words;
  if (shared_exchange) words += word_stride + whole_lines(command_size);
  // One line more than the layout: it starts at the first line boundary.
  const auto doubles =
      rank == 0 ? word_stride + words + static_cast<std::size_t>(task_count) * slot_stride(static_cast<std::size_t>(record_size)) : 0;
  void* mine = nullptr;
  MPI_Win_allocate_shared(static_cast<MPI_Aint>(doubles * sizeof(double)), sizeof(double), MPI_INFO_NULL, node_comm_,
                          &mine, &window_);
  MPI_Aint bytes = 0;
  int unit = 0;
  void* base = nullptr;
  MPI_Win_shared_query(window_, 0, &bytes, &unit, &base);
  // Every rank maps the window at a page boundary, so the padding to the first line is the same on
  // every rank; rank 0's is broadcast all the same (the layout must be one).
  auto padding = static_cast<long>((line_bytes - reinterpret_cast<std::uintptr_t>(base) % line_bytes) % line_bytes);
  MPI_Bcast(&padding, 1, MPI_LONG, 0, node_comm_);
  base = static_cast<char*>(base) + padding;
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

void NodeWindow::sync() const {
#if defined(__SSE2__)
  _mm_sfence();  // the streamed slots first (MPI_Win_sync is a full barrier in Open MPI's sm windows; be sure)
#endif
  MPI_Win_sync(window_);
}

void NodeWindow::stream_slot(double* slot, const double* from, std::size_t stride) {
#if defined(__SSE2__)
  for (std::size_t i = 0; i < stride; i += 2) _mm_stream_pd(slot + i, _mm_loadu_pd(from + i));
#else
  std::copy_n(from, stride, slot);
#endif
}

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
