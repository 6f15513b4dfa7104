// Rank 0's commands to the workers, and the waits on the workers' words in the node window.
//
// Between nodes a command is a broadcast (MPI_Ibcast) of the command buffer. With every rank on
// rank 0's node and the shared exchange on (MpiExecutorOptions::shared_exchange), the command goes
// through the node window instead: rank 0 writes the buffer into the window and then stores the
// command's number in the command word; each worker spins on that word, copies the buffer out and
// stores the number in its own "taken" word. Rank 0 writes the next command only once every worker
// has taken the last (a reply implies its command was taken, so after an evaluation nothing is
// waited for; after an output or plan command the words are read).
//
// Why: the broadcast of a command of a few hundred doubles reached the worker 1.7-2.2 us after
// rank 0 posted it (clock readings on both ranks, the heavy scene at np=2), out of an evaluation of
// about 460 us, and rank 0's own send of an output command waits for MPI's progress; a store into
// shared memory is seen by the other core in about 0.1 us (perf/studies/results/parallel_notes.md (n), (o)).
// A plan's owner list still follows its command as a broadcast: plans are rare.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "scheduler/mpi_executor.hpp"

namespace raceway::scheduler {

namespace {

using clock_type = std::chrono::steady_clock;

// A waiting rank spins on the words while the wait is short (the ranks finish within a task of each
// other, and rank 0 comes back between two evaluations within tens of us), then gives its core away
// between looks: oversubscribed (more ranks than cores) a spinning rank would hold the core another
// rank needs. The clock is read every 64 looks.
constexpr double spin_seconds = 50e-6;
constexpr unsigned looks_per_clock_reading = 64;

// Inside a spin: x86's PAUSE, the processor makers' advice for spin-wait loops (the loop's exit
// when the word changes is not taken for a memory-order violation that flushes the pipeline; less
// power; an SMT sibling keeps the core's execution units).
inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#endif
}

std::int64_t load(const std::int64_t& word) {
  return std::atomic_ref<const std::int64_t>(word).load(std::memory_order_acquire);
}
void store(std::int64_t& word, std::int64_t value) {
  std::atomic_ref<std::int64_t>(word).store(value, std::memory_order_release);
}

/// Looks until done() is true: spinning for spin_seconds, then yielding every `looks_per_yield`
/// looks; past the spin, on_clock(now) at every clock reading (a bounded wait fails from there).
template <class Done, class OnClock>
void spin_then_yield(unsigned looks_per_yield, Done done, OnClock on_clock) {
  const auto spin_until = clock_type::now() + std::chrono::duration<double>(spin_seconds);
  bool spinning = true;
  for (unsigned look = 1; !done(); ++look) {  // unsigned: a long wait wraps
    relax();
    if (look % looks_per_clock_reading == 0) {
      const auto now = clock_type::now();
      spinning = spinning && now < spin_until;
      if (!spinning) on_clock(now);
    }
    if (!spinning && look % looks_per_yield == 0) std::this_thread::yield();
  }
}

}  // namespace

void MpiExecutor::send_command(const char* what) {
  if (!command_word_) {
    broadcast(message_.data(), static_cast<int>(message_size_), what);
    return;
  }
  if (commands_taken_by_all_ < commands_) {  // the buffer is free once every worker has copied it
    await_worker_words(taken_word, commands_, "answer rank 0's command after", -1);
    commands_taken_by_all_ = commands_;
  }
  std::copy(message_.begin(), message_.end(), command_buffer_);
  MPI_Win_sync(tail_window_);  // the buffer before the word
  store(*command_word_, ++commands_);
}

void MpiExecutor::receive_command() {
  if (!command_word_) {
    broadcast(message_.data(), static_cast<int>(message_size_), "a command");
    return;
  }
  // A worker waits for its master as long as it takes while rank 0 lives (its heartbeat:
  // mpi_heartbeat.cpp; the master bounds its own waits).
  const std::int64_t next = commands_ + 1;
  MasterWatch watch(*this);
  // Idle between commands, it yields at every look once the spin is over.
  spin_then_yield(1, [&] { return load(*command_word_) >= next; }, [&](clock_type::time_point) { watch.check(); });
  MPI_Win_sync(tail_window_);  // the word before the buffer
  std::copy_n(command_buffer_, message_size_, message_.begin());
  commands_ = next;
  store(reply_done_[static_cast<std::size_t>(rank_) * window_word_stride + taken_word], next);
}

void MpiExecutor::await_worker_words(std::size_t word, std::int64_t value, const char* what, int phase) {
  const auto deadline = clock_type::now() + std::chrono::duration<double>(options_.rank_timeout);
  int first_silent = 0;
  const auto all_there = [&] {
    first_silent = 0;
    for (int r = 1; r < size_ && first_silent == 0; ++r)
      if (load(reply_done_[static_cast<std::size_t>(r) * window_word_stride + word]) < value) first_silent = r;
    return first_silent == 0;
  };
  // Rank 0 yields only at the clock readings: a yield at every look delayed its noticing the
  // last reply (rank 0 beyond the slowest rank 0.023 -> 0.042 s per 20 ms run, medians of 9).
  spin_then_yield(looks_per_clock_reading, all_there, [&](clock_type::time_point now) {
    if (now <= deadline) return;
    char timeout[32];
    std::snprintf(timeout, sizeof timeout, "%g", options_.rank_timeout);
    const std::string evaluation = (phase >= 0 ? std::string("the ") + phase_name(phase) + " " : std::string()) +
                                   "evaluation " + std::to_string(evaluation_);
    fail("rank " + std::to_string(first_silent) + " did not " + what + " " + evaluation + " within " + timeout +
         " s (--rank-timeout): stopped, hung or lost; ending the job");
  });
}

}  // namespace raceway::scheduler
