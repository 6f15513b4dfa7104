#include "solver/run/schedule_output.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace raceway::run {

namespace {

constexpr std::size_t kPlanColumns = 11, kSampleColumns = 8;

double task_array_bytes(const scheduler::ScheduleLog& log) {
  double values = static_cast<double>(log.task_group.size() + log.task_parent.size() + log.rank_task_seconds.size());
  for (std::size_t p = 0; p < 2; ++p)
    values += static_cast<double>(log.task_record_size[p].size() + log.task_cost[p].size());
  return values * sizeof(double);
}

double row_bytes(std::size_t rows, std::size_t columns) { return static_cast<double>(rows * columns * sizeof(double)); }

}  // namespace

double schedule_log_array_bytes(const scheduler::ScheduleLog& log) {
  return task_array_bytes(log) + row_bytes(log.plans.size(), kPlanColumns) + row_bytes(log.samples.size(), kSampleColumns);
}

void write_schedule_log(h5::H5SeriesWriter& file, const scheduler::ScheduleLog& full, double budget_bytes) {
  // Within the budget: thin the samples first (every other one, as the executor does past its own
  // bound), then keep only the first and last plans, then leave out the per-task arrays.
  scheduler::ScheduleLog log = full;
  std::string left_out;
  while (schedule_log_array_bytes(log) > budget_bytes && !log.samples.empty()) {
    if (log.sample_every >= (1 << 30)) {
      log.samples.clear();
      break;
    }
    log.sample_every *= 2;
    std::erase_if(log.samples, [&](const scheduler::ImbalanceSample& x) { return x.evaluation % log.sample_every != 0; });
  }
  if (log.sample_every != full.sample_every || log.samples.size() != full.samples.size())
    left_out = fmt::format("imbalance samples thinned to every {}th evaluation ({} of {} kept)", log.sample_every,
                           log.samples.size(), full.samples.size());
  if (schedule_log_array_bytes(log) > budget_bytes && log.plans.size() > 2) {
    log.plans = {full.plans.front(), full.plans.back()};
    left_out += fmt::format("{}plans: the first and the last of {} kept", left_out.empty() ? "" : "; ", full.plans.size());
  }
  if (schedule_log_array_bytes(log) > budget_bytes) {
    log.task_group.clear(), log.task_parent.clear(), log.rank_task_seconds.clear();
    for (std::size_t p = 0; p < 2; ++p) log.task_record_size[p].clear(), log.task_cost[p].clear();
    log.plans.clear(), log.samples.clear();
    left_out += fmt::format("{}the arrays (per task, plans, samples) left out", left_out.empty() ? "" : "; ");
  }
  const std::string g = "/scheduler";
  if (!left_out.empty())
    file.set_attribute(g, "left_out_for_max_size",
                       fmt::format("{} to keep the file within [output] max_size ({:.0f} bytes were left for these "
                                   "arrays, {:.0f} needed)",
                                   left_out, std::max(0.0, budget_bytes), schedule_log_array_bytes(full)));
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
  if (!log.rank_task_seconds.empty())
    file.write_array(g + "/rank_task_seconds", {log.rank_task_seconds.size()}, log.rank_task_seconds, "s",
                     "task seconds per rank, all phases");
  if (!log.plans.empty()) {
    constexpr std::size_t columns = kPlanColumns;
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
    constexpr std::size_t columns = kSampleColumns;
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

}  // namespace raceway::run
