// The executor's cost model: what a task costs, per phase, from the seconds measured at every
// evaluation, and how unbalanced the evaluations and the current plan are. Pure (no MPI): the MPI
// executor (scheduler/mpi_executor.hpp) feeds it and the re-planning policy
// (scheduler/replan_policy.hpp) reads it; unit-tested in tests/scheduler/cost_model_test.cpp.
//
// Per phase and task: an exponential moving average of measured task seconds, weight `smoothing`
// on the newest evaluation (the first measurement is taken as it is). 0.2 follows a load that moves
// over ~5 evaluations (a ball entering the loaded zone takes hundreds of right-hand sides) while
// damping the timer noise of single microsecond-scale tasks. A measurement enters the average
// clipped to `outlier_factor` times the current estimate: a task preempted for milliseconds
// (another process on the core) would otherwise dominate the model of a microsecond task for dozens
// of evaluations; a real rise still gets through at up to (1 + 0.2 * (3 - 1)) = 1.4x per evaluation.
// The measured imbalance per evaluation (max over mean of the ranks' share-weighted task seconds)
// is smoothed with weight `imbalance_smoothing`: a single slow evaluation must not trigger a
// re-plan. For the phases other than the right-hand side the model follows the right-hand side's
// cost times the phase's measured per-task ratio (once measured): Jacobians are rare, and their
// costs move with the same loaded zone.
#pragma once

#include <span>
#include <vector>

#include "scheduler/executor.hpp"

namespace raceway::scheduler {

/// One evaluation's balance from each rank's busy seconds and capacity (ranks of capacity 0 left
/// out): the slowest rank's share-weighted seconds, the capacity-weighted mean, their ratio (1 when
/// nothing was measured) and the total.
struct EvaluationBalance {
  double worst = 0, mean = 0, imbalance = 1, total = 0;
};
EvaluationBalance evaluation_balance(std::span<const double> busy, std::span<const double> capacity);

class CostModel {
 public:
  static constexpr double smoothing = 0.2;
  static constexpr double outlier_factor = 3.0;
  static constexpr double imbalance_smoothing = 0.1;

  /// Folds one evaluation of `phase` in: its tasks' measured seconds and its measured imbalance.
  void measure(int phase, std::span<const double> task_seconds, double imbalance);
  /// Folds the measured seconds of making and sending a plan in (smoothed and clipped like the task
  /// costs: one preempted plan must not block re-planning for the rest of the run).
  void measure_plan_seconds(int phase, double seconds);
  /// A new plan is judged on its own: the smoothed imbalance starts again from its prediction.
  void restart_imbalance(int phase, double predicted) { imbalance_[phase] = predicted; }

  /// Evaluations of `phase` measured so far.
  long evaluations(int phase) const { return evaluations_[phase]; }
  /// Smoothed measured seconds per task (empty before the first measurement).
  const std::vector<double>& measured(int phase) const { return cost_[phase]; }
  /// Cost per task the plans use: measured(rhs) for the right-hand side; for the other phases the
  /// right-hand side's cost times the phase's measured per-task ratio once there is one, else the
  /// phase's own measured cost.
  std::vector<double> model(int phase) const;
  double smoothed_imbalance(int phase) const { return imbalance_[phase]; }
  double plan_seconds(int phase) const { return plan_seconds_[phase]; }
  /// The model's imbalance of the ranks' fixed lists `lists` (per rank its tasks), the rest of the
  /// work (a tail) filling the gaps up to the mean (imbalance_with_tail_filling): without a tail
  /// this is predicted_imbalance of the plan. Cheap (costs read in place): it runs at every
  /// evaluation. 1 before any measurement.
  double current_imbalance(int phase, const std::vector<std::vector<int>>& lists, std::span<const double> capacity) const;

 private:
  bool follows_rhs(int phase) const;

  std::vector<double> cost_[phase_count];   ///< smoothed task seconds
  std::vector<double> ratio_[phase_count];  ///< per task: cost / rhs cost (not rhs)
  double imbalance_[phase_count] = {};
  double plan_seconds_[phase_count] = {};
  long evaluations_[phase_count] = {};
  long plans_[phase_count] = {};
};

}  // namespace raceway::scheduler
