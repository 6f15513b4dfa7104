// Two-level plans (seed 000 section 2.6, docs/references.md): which rank evaluates which task.
// Pure functions of measured costs: no MPI, unit-tested in tests/scheduler.
//
// Level 1 gives whole rolling elements (all their tasks) to ranks; border tasks (cage-land, ring
// segments) are units of their own. Two level-1 partitioners are tried and the one with the
// smaller predicted makespan is kept:
//   - greedy LPT (largest unit first to the rank that finishes it earliest, capacity-weighted):
//     balance-only, within 4/3 of optimal, and exact enough with tens of units;
//   - METIS k-way on the level-1 graph (vertex weight = smoothed cost, edge weight = bodies whose
//     states two units both read, target part weights = rank capacities).
// Why LPT usually wins here: every task receives the whole broadcast context [t, z], so the data
// two units share costs nothing extra when they sit on different ranks; and every rolling element
// reads the same rings and cage, so the level-1 graph is (nearly) complete with equal edge
// weights: any k-way cut is about as good as any other, and the edge-cut objective only constrains
// METIS's balance. METIS is kept where it balances as well (ties go to METIS: a smaller cut is
// what would matter if the context were ever distributed by halo instead of broadcast).
//
// Level 2 then splits the heaviest rolling elements when level 1 cannot balance (more ranks than
// rolling elements, or a narrow loaded zone): while the most loaded rank is above the mean by more
// than level2_tolerance, it moves single tasks, from its heaviest rolling element first, to the
// least loaded rank, choosing the task closest to the amount that would equalise the two; when
// every piece it could give is larger than the gap, it exchanges one for a cheaper piece of another
// rank (the exchange that lowers the larger of the two ranks' loads the most).
// What it moves is a piece (TaskCatalogue::parent: a contact segment), all of the piece's tasks on
// that rank together; a heavy piece (more than split_share of a rank's share of the work) is cut,
// its sub-tasks (traction-grid blocks, Jacobian columns) moved one by one. Cutting costs no
// arithmetic (the sub-tasks exist at every rank count, and the master combines their records in
// one fixed order), only a few doubles of messages, so heavy is set low.
#pragma once

#include <span>
#include <vector>

#include "scheduler/executor.hpp"
#include "scheduler/schedule_log.hpp"

namespace raceway::scheduler {

struct Plan {
  std::vector<int> owner;   ///< per task: rank
  PlanMethod method = PlanMethod::greedy_lpt;
  int split_groups = 0;     ///< rolling elements with tasks on more than one rank
  int split_parents = 0;    ///< pieces (TaskCatalogue::parent) with tasks on more than one rank
  double predicted_imbalance = 1;
};

struct PlanOptions {
  /// Level 2 stops when the most loaded rank is within this fraction of the capacity-weighted
  /// mean: 2 % is below the measurement noise of one evaluation's task times.
  double level2_tolerance = 0.02;
  /// A piece whose tasks on a rank cost more than this fraction of a rank's mean share may be cut
  /// (its tasks moved separately); lighter pieces move whole.
  double split_share = 0.1;
  bool try_metis = true;
};

/// Capacity-weighted imbalance of an assignment: max_r(load_r / cap_r) / (sum load / sum cap),
/// over ranks with capacity > 0. 1 is perfect balance.
double predicted_imbalance(std::span<const int> owner, std::span<const double> cost,
                           std::span<const double> capacity);

/// Makes a plan for `capacity.size()` ranks (capacity = relative share of the work; 0: no tasks).
/// cost and catalogue.group/bodies are per task.
Plan make_plan(std::span<const double> cost, const TaskCatalogue& catalogue, std::span<const double> capacity,
               const PlanOptions& options = {});

/// Owner of a task handed out on demand during an evaluation (the plan's tail, mark_tail): the
/// rank that is free first evaluates it (scheduler/tail_claims.hpp).
inline constexpr int shared_task = -1;

/// Takes the plan's tail out of `owner`: of each rank's tasks that cost at least tail_floor times
/// the largest task's cost, its cheapest whose costs add up to at most `share` of its load become
/// shared_task (share 1: every task, whatever its cost), so every rank keeps about the same
/// fraction of its planned work as its fixed list. Returns the tail in the order it is handed out:
/// by decreasing cost (the largest first, the small ones fill the gaps at the end), ties by task
/// index. Nothing changes for share <= 0.
std::vector<int> mark_tail(std::vector<int>& owner, std::span<const double> cost, double share, double tail_floor = 0.1);

/// predicted_imbalance of `owner` when its tail (mark_tail with `share`) goes to whichever rank is
/// free first: the ranks evaluate their fixed lists and the tail fills the gaps, so only a fixed
/// list longer than the mean load (the tail too small to cover it) leaves ranks waiting:
/// max(max_r fixed_r / cap_r, mean) / mean. share <= 0: predicted_imbalance.
double predicted_imbalance_with_tail(std::span<const int> owner, std::span<const double> cost,
                                     std::span<const double> capacity, double share);
/// The same from the ranks' fixed loads: each rank r evaluates fixed_load[r] and the rest of
/// `total` (the tail) fills the gaps; ranks with capacity 0 are left out.
double imbalance_with_tail_filling(std::span<const double> fixed_load, double total, std::span<const double> capacity);

/// Groups (rolling elements) whose tasks are on more than one rank.
int count_split_groups(std::span<const int> owner, std::span<const int> group);
/// Pieces (TaskCatalogue::parent) whose tasks are on more than one rank; 0 when parent is empty.
int count_split_parents(std::span<const int> owner, std::span<const int> parent);

}  // namespace raceway::scheduler
