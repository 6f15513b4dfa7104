// The plan's tail, claimed on demand within one evaluation (MpiExecutorOptions::tail_share).
// Pure (no MPI): the words live in the node's shared-memory window (scheduler/node_window.hpp) in
// a run, in a plain array in tests/scheduler/tail_claims_test.cpp.
//
// Why: the plans balance smoothed task costs, but each rank's task time scatters from one
// evaluation to the next by a few % of its load, and every evaluation waits for the slowest rank.
// The scatter does not carry over from one evaluation to the next (perf/studies/results/parallel_notes.md,
// section (j)), so no plan removes it; handing the last part of the work to whichever rank is free
// first does.
//
// How: the plan marks its tail (mark_tail: of each rank's tasks its cheapest, tail_share of its
// load); each rank's part of it stays its own, ordered largest first, and every rank knows all the
// parts from the plan's owners (encode_tail: negative owner codes; decode_tail). In an evaluation
// each rank evaluates its fixed list, then claims its own tail tasks from the front, then, when its
// part is gone, steals from the back of the part with the most left (the smallest tasks, which fill
// the gaps best), until every part is gone. A part's claims are one 64-bit word (front index in the
// low 32 bits, back above) changed by compare-and-swap: no message, nothing rank 0 has to serve;
// at many ranks the claims spread over P cache lines instead of one. Every record lands at its task
// and the equations sum the records in task order: the bits depend on no rank count, plan or order
// of the claims.
//
// Why not messages: a claim protocol over point-to-point messages needs rank 0 to look for claims
// between its own tasks; with Open MPI's yield_when_idle every look that finds nothing yields the
// core, 1-2 us each here, and about a hundred looks per evaluation cost more than the imbalance
// they remove (measured, parallel_notes.md (j)). A window needs every rank on one node: on several
// nodes the tail is off (said at the start) and the fixed plan runs as before.
//
// The claim words are lock-free std::atomic_ref, written by hand instead of MPI_Compare_and_swap:
// Open MPI's shared-memory windows (osc sm) do their atomics under a spin lock, and a rank stopped
// (SIGSTOP) while holding it would hold rank 0 in its next claim for ever, beyond --rank-timeout; a
// single atomic instruction cannot be left half done.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace raceway::scheduler {

/// A plan's tail as every rank knows it: rank 0's part, rank 1's, ... (each largest first).
struct TailParts {
  std::vector<int> tasks;
  std::vector<int> start;  ///< rank r's part is tasks[start[r] .. start[r + 1])
  bool empty() const { return tasks.empty(); }
};

/// Marks the tail of the plan `owner` (mark_tail with `share` under `cost`) in place: each tail
/// task's owner becomes a negative code saying its rank in the plan and its position in that rank's
/// part (shared_task - (i * ranks + r) for rank r's i-th).
void encode_tail(std::vector<int>& owner, std::span<const double> cost, double share, int ranks);
/// The parts from the codes of encode_tail (tasks with owner >= 0 are in no part).
TailParts decode_tail(std::span<const int> owner, int ranks);

/// The claim words of one node: per rank a word, `stride` int64s apart (a cache line each).
class TailClaims {
 public:
  TailClaims() = default;
  TailClaims(std::int64_t* words, std::size_t stride, int ranks) : words_(words), stride_(stride), ranks_(ranks) {}
  bool is_open() const { return words_ != nullptr; }
  /// Every part whole again (rank 0, before the command that starts an evaluation).
  void reset(const TailParts& parts);
  /// The next position (in TailParts::tasks) rank `rank` evaluates: its own part's front, else the
  /// back of the part with the most left; -1 when the tail is gone. Safe from any number of threads
  /// or processes at once: each position is handed out exactly once.
  std::int64_t claim(int rank);

 private:
  std::int64_t& word(int rank) const { return words_[static_cast<std::size_t>(rank) * stride_]; }
  std::int64_t* words_ = nullptr;
  std::size_t stride_ = 1;
  int ranks_ = 0;
};

}  // namespace raceway::scheduler
