// Rank 0's commands to the workers (a header, scheduler/command_header.hpp, then the context or an
// output payload), and rank 0's waits on the workers' words in the node window.
//
// Between nodes a command is a broadcast (MPI_Ibcast) of the command buffer. With every rank on
// rank 0's node and the shared exchange on (MpiExecutorOptions::shared_exchange), the command goes
// through the node window instead (scheduler/node_window.hpp): rank 0 writes the buffer into the
// window and then stores the command's number in the command word; each worker spins on that word,
// copies the buffer out and stores the number in its own "taken" word. Rank 0 writes the next
// command only once every worker has taken the last (a reply implies its command was taken, so
// after an evaluation nothing is waited for; after an output or plan command the words are read).
//
// Why: the broadcast of a command of a few hundred doubles reached the worker 1.7-2.2 us after
// rank 0 posted it (clock readings on both ranks, the heavy scene at np=2), out of an evaluation of
// about 460 us, and rank 0's own send of an output command waits for MPI's progress; a store into
// shared memory is seen by the other core in about 0.1 us (perf/studies/results/parallel_notes.md (n), (o)).
// A plan's owner list still follows its command as a broadcast: plans are rare.
#pragma once

#include <mpi.h>

#include <span>
#include <string>
#include <vector>

#include "scheduler/command_header.hpp"
#include "scheduler/executor.hpp"
#include "scheduler/node_window.hpp"
#include "scheduler/rank_watch.hpp"

namespace raceway::scheduler {

class CommandChannel {
 public:
  CommandChannel(MPI_Comm comm, const RankWatch& watch) : comm_(comm), watch_(watch) {}

  /// Master: the start command, or stop before a start (a broadcast of the header alone: the workers
  /// do not know the context size yet). Worker: receives it.
  void send_first(const CommandHeader& header, const char* what);
  CommandHeader receive_first();
  /// Both, after the start: every later command carries `context_size` doubles after its header;
  /// through `window` when it has a command word, else broadcast.
  void open(int context_size, const NodeWindow* window);
  std::size_t payload_size() const { return buffer_.size() - command_header_size; }
  bool through_window() const { return window_ != nullptr; }

  /// Master: `header` and `payload` (zeros after it) to every worker; `what` names the command in a
  /// failure. With `pending`, a broadcast is only posted: its request is appended there (rank -1 in
  /// `pending_ranks`) for the caller's bounded wait.
  void send(const CommandHeader& header, std::span<const double> payload, const char* what,
            std::vector<MPI_Request>* pending = nullptr, std::vector<int>* pending_ranks = nullptr);
  /// Worker: the next command (its header; payload() holds the rest). Protocol errors end the job.
  CommandHeader receive();
  std::span<const double> payload() const { return std::span<const double>(buffer_).subspan(command_header_size); }

  /// Both: a plan's owner per task, after its command (rank 0's sent, a worker's filled).
  void broadcast_owners(std::vector<int>& owner);
  /// Master, through the window: waits until every worker's `word` (NodeWindow::reply_word,
  /// taken_word) is at least `value`; past the timeout fails: "rank R did not <what> [the <phase>]
  /// evaluation N" (phase < 0: no phase).
  void await_workers(std::size_t word, std::int64_t value, const char* what, int phase, long evaluation);
  /// Master: every worker has replied, so it has taken every command sent.
  void replies_in() { taken_by_all_ = commands_; }

 private:
  void broadcast(void* buffer, int count, MPI_Datatype type, const std::string& what);

  MPI_Comm comm_;
  const RankWatch& watch_;
  const NodeWindow* window_ = nullptr;
  std::vector<double> buffer_ = std::vector<double>(command_header_size, 0.0);
  std::int64_t commands_ = 0;      ///< through the window: written (master), taken (worker)
  std::int64_t taken_by_all_ = 0;  ///< master: every worker has taken this many
  long evaluation_ = 0;            ///< the last evaluate command's number (for the diagnoses)
};

}  // namespace raceway::scheduler
