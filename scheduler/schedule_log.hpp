// What the scheduler did during a run: plans, re-plan events, sampled imbalance, smoothed task
// costs. Kept by the executor on the master, written by the run driver to /scheduler in the
// output file (docs/output_layout.md) and read by the replay model in perf/.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace raceway::scheduler {

inline constexpr int schedule_phase_count = 3;  ///< = phase_count (executor.hpp)

/// Why a plan was made.
enum class PlanReason { initial = 0, measured_costs = 1, imbalance = 2, forced = 3 };
/// How level 1 placed the rolling elements.
enum class PlanMethod { single_rank = 0, greedy_lpt = 1, metis_kway = 2, rotated = 3 };

struct PlanEvent {
  long evaluation = 0;  ///< evaluation number (all phases, from 1) before which the plan took effect
  int phase = 0;
  int version = 0;  ///< per phase, from 0
  PlanReason reason = PlanReason::initial;
  PlanMethod method = PlanMethod::greedy_lpt;
  int split_groups = 0;              ///< rolling elements whose tasks level 2 spread over several ranks
  int split_parents = 0;             ///< pieces (segments cut into sub-tasks) spread over several ranks
  double measured_imbalance = 0;     ///< smoothed measured imbalance when the plan was made (0: none yet)
  double predicted_before = 0;       ///< cost-model imbalance of the old plan
  double predicted_after = 0;        ///< cost-model imbalance of the new plan
  double plan_seconds = 0;           ///< time to make and send the plan
};

/// One evaluation's balance (sampled).
struct ImbalanceSample {
  long evaluation = 0;
  int phase = 0;
  double time = 0;           ///< context[0]: simulated time of the evaluation
  double imbalance = 0;      ///< max over mean of the ranks' (share-weighted) task seconds
  double max_rank_seconds = 0, mean_rank_seconds = 0;
  double wall_seconds = 0;   ///< master: command sent to last record received
  int plan_version = 0;
};

struct ScheduleLog {
  int ranks = 1;
  std::string policy;        ///< "adaptive", "static" or "every-evaluation"
  double master_share = 1;
  int sample_every = 1;      ///< every n-th evaluation is in samples
  std::vector<PlanEvent> plans;
  std::vector<ImbalanceSample> samples;
  /// Per phase over all evaluations: sums of the slowest and of the mean rank's task seconds
  /// (their ratio is the time-averaged imbalance), evaluations, master wall seconds in run().
  std::array<double, schedule_phase_count> sum_max_seconds{}, sum_mean_seconds{}, wall_seconds{};
  std::array<long, schedule_phase_count> evaluations{};
  std::vector<double> rank_task_seconds;  ///< per rank, all phases
  /// Smoothed cost per task at the end of the run, per phase (seconds).
  std::array<std::vector<double>, schedule_phase_count> task_cost;
  /// Doubles per task record (per phase) and per context: the message sizes of the replay model.
  std::array<int, schedule_phase_count> record_size{};
  /// Per phase and task: the doubles of its record that cross ranks (TaskCatalogue::used_size).
  std::array<std::vector<int>, schedule_phase_count> task_record_size;
  int context_size = 0;
  /// Per task: rolling element or -1 (border), as in the TaskCatalogue.
  std::vector<int> task_group;
  /// Per task: the piece (contact segment) it is a part of, as in the TaskCatalogue (empty: each
  /// task is its own).
  std::vector<int> task_parent;
};

}  // namespace raceway::scheduler
