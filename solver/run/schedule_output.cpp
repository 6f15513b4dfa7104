#include "solver/run/schedule_output.hpp"

namespace raceway::solver {

void write_schedule_log(io::H5SeriesWriter& file, const scheduler::ScheduleLog& log) {
  const std::string g = "/scheduler";
  file.set_attribute(g, "ranks", log.ranks);
  file.set_attribute(g, "policy", log.policy);
  file.set_attribute(g, "master_share", log.master_share);
  file.set_attribute(g, "sample_every", log.sample_every);
  file.set_attribute(g, "context_size", log.context_size);
  const double sum_max = log.sum_max_seconds[0] + log.sum_max_seconds[1];
  const double sum_mean = log.sum_mean_seconds[0] + log.sum_mean_seconds[1];
  file.set_attribute(g, "time_averaged_imbalance", sum_mean > 0 ? sum_max / sum_mean : 1.0);
  const char* phase[2] = {"rhs", "jacobian"};
  for (std::size_t p = 0; p < 2; ++p) {
    const std::string ph = phase[p];
    file.set_attribute(g, "evaluations_" + ph, log.evaluations[p]);
    file.set_attribute(g, "record_size_" + ph, log.record_size[p]);
    file.set_attribute(g, "time_averaged_imbalance_" + ph,
                       log.sum_mean_seconds[p] > 0 ? log.sum_max_seconds[p] / log.sum_mean_seconds[p] : 1.0);
    file.set_attribute(g, "wall_seconds_" + ph, log.wall_seconds[p]);
    file.set_attribute(g, "max_rank_task_seconds_" + ph, log.sum_max_seconds[p]);
    file.set_attribute(g, "mean_rank_task_seconds_" + ph, log.sum_mean_seconds[p]);
    if (const auto& used = log.task_record_size[p]; !used.empty())
      file.write_array(g + "/task_record_size_" + ph, {used.size()}, std::vector<double>(used.begin(), used.end()), "-",
                       "doubles of each task's record that cross ranks (its reply carries these and its seconds)");
    const auto& cost = log.task_cost[p];
    if (!cost.empty())
      file.write_array(g + "/task_cost_" + ph, {cost.size()}, cost, "s",
                       "smoothed measured seconds per task (segment) at the end of the run");
  }
  if (!log.task_group.empty()) {
    std::vector<double> group(log.task_group.begin(), log.task_group.end());
    file.write_array(g + "/task_group", {group.size()}, group, "-", "rolling element of each task; -1: border task");
  }
  if (!log.task_parent.empty()) {
    std::vector<double> parent(log.task_parent.begin(), log.task_parent.end());
    file.write_array(g + "/task_segment", {parent.size()}, parent, "-",
                     "contact segment of each task (a heavy segment's work is cut into several tasks)");
  }
  file.write_array(g + "/rank_task_seconds", {log.rank_task_seconds.size()}, log.rank_task_seconds, "s",
                   "task seconds per rank, all phases");
  if (!log.plans.empty()) {
    constexpr std::size_t columns = 11;
    std::vector<double> rows;
    for (const auto& e : log.plans) {
      const double row[columns] = {static_cast<double>(e.evaluation), static_cast<double>(e.phase),
                                   static_cast<double>(e.version),    static_cast<double>(e.reason),
                                   static_cast<double>(e.method),     static_cast<double>(e.split_groups),
                                   e.measured_imbalance,              e.predicted_before,
                                   e.predicted_after,                 e.plan_seconds,
                                   static_cast<double>(e.split_parents)};
      rows.insert(rows.end(), row, row + columns);
    }
    file.write_array(g + "/plans", {log.plans.size(), columns}, rows, "-",
                     "one row per plan: evaluation, phase (0 rhs, 1 jacobian), version, reason (0 initial, 1 first "
                     "measured costs, 2 imbalance, 3 forced), method (0 single rank, 1 greedy LPT, 2 METIS k-way, 3 "
                     "rotated), split rolling elements, measured imbalance, predicted imbalance before, after, seconds "
                     "to make and send, split segments (cut into sub-tasks on several ranks)");
  }
  if (!log.samples.empty()) {
    constexpr std::size_t columns = 8;
    std::vector<double> rows;
    for (const auto& s : log.samples) {
      const double row[columns] = {static_cast<double>(s.evaluation), static_cast<double>(s.phase), s.time,
                                   s.imbalance, s.max_rank_seconds, s.mean_rank_seconds, s.wall_seconds,
                                   static_cast<double>(s.plan_version)};
      rows.insert(rows.end(), row, row + columns);
    }
    file.write_array(g + "/imbalance", {log.samples.size(), columns}, rows, "-",
                     "every sample_every-th evaluation: evaluation, phase, simulated time [s], imbalance (max over "
                     "mean rank task seconds, share-weighted), max rank task seconds, mean rank task seconds, master "
                     "wall seconds of the evaluation, plan version");
  }
}

}  // namespace raceway::solver
