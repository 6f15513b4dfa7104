#include "scheduler/schedule_logging.hpp"

#include <cstdio>

namespace raceway::scheduler {

namespace {

const char* method_name(PlanMethod m) {
  switch (m) {
    case PlanMethod::single_rank: return "single rank";
    case PlanMethod::greedy_lpt: return "greedy LPT";
    case PlanMethod::metis_kway: return "METIS k-way";
    case PlanMethod::rotated: return "rotated (forced)";
  }
  return "?";
}
const char* reason_name(PlanReason r) {
  switch (r) {
    case PlanReason::initial: return "initial (uniform costs)";
    case PlanReason::measured_costs: return "first measured costs";
    case PlanReason::imbalance: return "imbalance";
    case PlanReason::forced: return "forced";
  }
  return "?";
}

}  // namespace

void log_catalogue(ScheduleLog& log, const TaskCatalogue& catalogue) {
  log.task_group = catalogue.group;
  log.task_parent = catalogue.parent;
  log.context_size = catalogue.context_size;
  for (std::size_t p = 0; p < schedule_phase_count; ++p) {
    log.record_size[p] = catalogue.record_size[p];
    if (catalogue.record_size[p] <= 0) continue;
    auto& used = log.task_record_size[p];
    for (int t = 0; t < catalogue.task_count; ++t) used.push_back(catalogue.used(static_cast<int>(p), t));
  }
}

void log_evaluation(ScheduleLog& log, long evaluation, int phase, double time, const EvaluationBalance& balance,
                    std::span<const double> busy, double wall, int plan_version, const std::vector<double>& measured_cost) {
  const auto p = static_cast<std::size_t>(phase);
  for (std::size_t r = 0; r < busy.size(); ++r) log.rank_task_seconds[r] += busy[r];
  log.sum_max_seconds[p] += balance.worst;
  log.sum_mean_seconds[p] += balance.mean;
  log.wall_seconds[p] += wall;
  ++log.evaluations[p];
  log.task_cost[p] = measured_cost;  // measured (smoothed), not the rhs-based model
  if (evaluation % log.sample_every != 0) return;
  log.samples.push_back({evaluation, phase, time, balance.imbalance, balance.worst, balance.mean, wall, plan_version});
  constexpr std::size_t max_samples = std::size_t{1} << 17;
  if (log.samples.size() >= max_samples) {
    log.sample_every *= 2;
    std::erase_if(log.samples, [&](const ImbalanceSample& x) { return x.evaluation % log.sample_every != 0; });
  }
}

std::vector<std::string> log_plan(ScheduleLog& log, const PlanEvent& event) {
  log.plans.push_back(event);
  const std::size_t n = log.plans.size();
  std::vector<std::string> lines;
  if (n <= 20 || n % 100 == 0) lines.push_back(plan_event_line(event));
  if (n == 20) lines.emplace_back("scheduler: further plans are logged every 100th; all are kept in /scheduler/plans");
  return lines;
}

std::string plan_event_line(const PlanEvent& e) {
  char line[320];
  std::snprintf(line, sizeof line,
                "scheduler: %s plan v%d before evaluation %ld (%s, %s): predicted imbalance %.3f -> %.3f, "
                "measured %.3f, %d rolling element(s) and %d segment(s) split, %.3g ms",
                phase_name(e.phase), e.version, e.evaluation, reason_name(e.reason), method_name(e.method),
                e.predicted_before, e.predicted_after, e.measured_imbalance, e.split_groups, e.split_parents,
                1e3 * e.plan_seconds);
  return line;
}

}  // namespace raceway::scheduler
