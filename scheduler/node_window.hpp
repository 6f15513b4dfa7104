// The node's shared-memory window, on rank 0's memory and mapped by every rank, when every rank is
// on rank 0's node and the tail or the shared exchange wants it. Its layout, a 64-byte cache line
// (word_stride int64s) per word so that no two ranks write one line:
//   per rank its tail claim word (scheduler/tail_claims.hpp);
//   per rank its reply line: reply_word (the last evaluation it replied to), taken_word (the
//     commands it has taken), fixed_word (the last evaluation whose fixed list is in its slots)
//     (scheduler/replies.cpp, scheduler/command_channel.cpp);
//   with the shared exchange: the command word (the commands rank 0 has written), then the command
//     buffer (command_size doubles, whole lines);
//   per task a slot: the rank that evaluated it, its seconds, its record. A phase's slots lie one
//     after the other, each whole cache lines (slot_stride of the phase's record size), so the
//     records of an evaluation are one dense block: the rhs's 24-double records take 4 lines a task,
//     not the Jacobian's 40, and no two tasks share a line (two ranks never write one).
//   The layout starts on a cache line, whatever address MPI hands out.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>

namespace raceway::scheduler {

class NodeWindow {
 public:
  static constexpr std::size_t word_stride = 8;
  static constexpr std::size_t reply_word = 0, taken_word = 1, fixed_word = 2;

  NodeWindow() = default;
  NodeWindow(const NodeWindow&) = delete;
  NodeWindow& operator=(const NodeWindow&) = delete;

  /// Collective over comm. Opens nothing (is_open() false) when some rank is on another node.
  void open(MPI_Comm comm, int task_count, std::size_t command_size, int record_size, bool shared_exchange);
  /// Collective.
  void close();
  bool is_open() const { return window_ != MPI_WIN_NULL; }
  bool has_command() const { return command_word_ != nullptr; }
  /// A memory barrier for the window's memory (MPI_Win_sync): what was written before is seen before
  /// what is written after.
  void sync() const;

  std::int64_t* claim_words() const { return words_; }
  std::int64_t& reply_line(int rank, std::size_t word) const {
    return reply_lines_[static_cast<std::size_t>(rank) * word_stride + word];
  }
  std::int64_t& command_word() const { return *command_word_; }
  double* command_buffer() const { return command_buffer_; }
  /// Doubles between two tasks' slots in a phase whose records have `record_size` doubles: the
  /// rank, the seconds and the record, rounded up to whole cache lines.
  static std::size_t slot_stride(std::size_t record_size) { return whole_lines(2 + record_size); }
  static std::size_t whole_lines(std::size_t n) { return (n + word_stride - 1) / word_stride * word_stride; }
  /// Writes the first `stride` doubles (whole lines) of a slot from `from` around the writer's caches (x86's
  /// non-temporal stores): the line goes to memory without first being fetched from the reader's
  /// cache, which held it since the last evaluation. Ordered before what sync() orders.
  static void stream_slot(double* slot, const double* from, std::size_t stride);
  /// Task `task`'s slot in a phase of slot_stride `stride`: [0] rank, [1] seconds, then the record.
  double* slot(int task, std::size_t stride) const { return slots_ + static_cast<std::size_t>(task) * stride; }

 private:
  MPI_Comm node_comm_ = MPI_COMM_NULL;
  MPI_Win window_ = MPI_WIN_NULL;
  std::int64_t* words_ = nullptr;
  std::int64_t* reply_lines_ = nullptr;
  std::int64_t* command_word_ = nullptr;
  double* command_buffer_ = nullptr;
  double* slots_ = nullptr;
};

}  // namespace raceway::scheduler
