#include "scheduler/replan_policy.hpp"

#include <algorithm>

namespace raceway::scheduler {

const char* schedule_policy_name(SchedulePolicy p) {
  switch (p) {
    case SchedulePolicy::adaptive: return "adaptive";
    case SchedulePolicy::static_plan: return "static";
    case SchedulePolicy::every_evaluation: return "every-evaluation";
  }
  return "?";
}

ReplanPolicy::ReplanPolicy(SchedulePolicy policy, std::vector<double> capacity, double tail_share)
    : policy_(policy), capacity_(std::move(capacity)), tail_share_(tail_share) {}

std::optional<Replan> ReplanPolicy::decide(int phase, long evaluation, int version, const CostModel& costs,
                                           const std::vector<std::vector<int>>& lists, const TaskCatalogue& catalogue) {
  const long runs = costs.evaluations(phase);
  if (policy_ == SchedulePolicy::every_evaluation) {
    if (runs == 0) return std::nullopt;
    return Replan{make_plan(costs.model(phase), catalogue, capacity_), PlanReason::forced};
  }
  if (capacity_.size() == 1) return std::nullopt;
  if (version == 0) {
    const auto& rhs_cost = costs.measured(static_cast<int>(Phase::rhs));
    if (runs >= warmup_evaluations)
      return Replan{make_plan(costs.model(phase), catalogue, capacity_), PlanReason::measured_costs};
    if (runs == 0 && phase != static_cast<int>(Phase::rhs) && !rhs_cost.empty())
      return Replan{make_plan(rhs_cost, catalogue, capacity_), PlanReason::measured_costs};
    return std::nullopt;
  }
  if (policy_ != SchedulePolicy::adaptive) return std::nullopt;
  if (evaluation - last_plan_[phase] < cooldown_evaluations || evaluation - last_check_[phase] < check_interval)
    return std::nullopt;
  // This look comes at every evaluation until it finds a reason, so it must be cheap.
  const double now = costs.current_imbalance(phase, lists, capacity_);
  if (costs.smoothed_imbalance(phase) <= replan_threshold && now <= replan_threshold) return std::nullopt;
  last_check_[phase] = evaluation;
  const std::vector<double> cost = costs.model(phase);
  Plan candidate = make_plan(cost, catalogue, capacity_);
  const double after = tail_share_ > 0 ? predicted_imbalance_with_tail(candidate.owner, cost, capacity_, tail_share_)
                                       : candidate.predicted_imbalance;
  double total = 0, cap_sum = 0;
  for (double c : cost) total += c;
  for (double c : capacity_) cap_sum += c;
  const double saved_per_evaluation = (now - after) * total / cap_sum;
  if (now - after >= min_predicted_gain &&
      saved_per_evaluation * gain_horizon > replan_cost_factor * costs.plan_seconds(phase))
    return Replan{std::move(candidate), PlanReason::imbalance};
  return std::nullopt;
}

void rotate_plan(Plan& plan, int version, std::span<const double> capacity, const TaskCatalogue& catalogue,
                 std::span<const double> model) {
  std::vector<int> active;
  for (std::size_t r = 0; r < capacity.size(); ++r)
    if (capacity[r] > 0) active.push_back(static_cast<int>(r));
  const auto shift = static_cast<std::size_t>(version + 1);
  for (int& o : plan.owner) {
    const auto at = static_cast<std::size_t>(std::find(active.begin(), active.end(), o) - active.begin());
    o = active[(at + shift) % active.size()];
  }
  plan.method = PlanMethod::rotated;
  plan.split_groups = count_split_groups(plan.owner, catalogue.group);
  plan.split_parents = count_split_parents(plan.owner, catalogue.parent);
  if (!model.empty()) plan.predicted_imbalance = predicted_imbalance(plan.owner, model, capacity);
}

}  // namespace raceway::scheduler
