// The re-planning policy: when the MPI executor makes a new plan for a phase (maybe_replan,
// before each evaluation), from the cost model its evaluations keep (mpi_executor.cpp, account()).
#include <algorithm>

#include "scheduler/mpi_executor.hpp"

namespace raceway::scheduler {

namespace {

// The first plan from measured costs replaces the uniform start plan after this many evaluations
// of a phase (static and adaptive policies alike).
constexpr long warmup_evaluations = 3;
// Trigger: smoothed measured imbalance above replan_threshold (5 % of the evaluation time lost).
constexpr double replan_threshold = 1.05;
// Hysteresis: after a plan, no new plan for the same phase within cooldown_evaluations; after a
// check that kept the plan, the next check comes check_interval evaluations later. Both count
// evaluations of all phases (Jacobians are ~100 times rarer than right-hand sides, and their
// costs move with the same loaded zone). A phase's cost model changes only when that phase is
// measured, so a plan is never rebuilt from the costs it was made from.
constexpr long cooldown_evaluations = 20;
constexpr long check_interval = 10;
// Gain test: the candidate plan must lower the cost model's imbalance by at least
// min_predicted_gain, and the seconds it saves on the slowest rank over gain_horizon evaluations
// must exceed replan_cost_factor times the measured cost of making and sending a plan. The
// horizon is a plan's expected life: work moves with the balls' orbit and the load, over
// thousands of right-hand sides (6309 R3: a ball crosses the loaded zone in ~10 ms, ~2000 rhs).
constexpr double min_predicted_gain = 0.02;
constexpr double replan_cost_factor = 2.0;
constexpr long gain_horizon = 200;

// The cost model of a phase, task by task: the smoothed right-hand side cost times the phase's
// measured per-task ratio (once measured, for the phases other than the right-hand side), else the
// phase's own smoothed cost.
struct ModelCost {
  const std::vector<double>& base;
  const std::vector<double>* ratio;  // nullptr: base as it is
  double operator()(std::size_t t) const { return ratio ? base[t] * (*ratio)[t] : base[t]; }
};

ModelCost model_cost_of(const std::vector<double> (&cost)[phase_count], const std::vector<double> (&ratio)[phase_count],
                        int phase) {
  const auto& rhs = cost[static_cast<int>(Phase::rhs)];
  const auto& r = ratio[phase];
  if (phase == static_cast<int>(Phase::rhs) || r.empty() || rhs.size() != r.size()) return {cost[phase], nullptr};
  return {rhs, &r};
}

}  // namespace

std::vector<double> MpiExecutor::model_cost(int phase) const {
  const ModelCost cost = model_cost_of(cost_, ratio_, phase);
  std::vector<double> c(cost.base.size());
  for (std::size_t t = 0; t < c.size(); ++t) c[t] = cost(t);
  return c;
}

double MpiExecutor::current_imbalance(int phase) const {
  // model_cost's costs read in place, without building the vector: this runs at every evaluation.
  const ModelCost cost = model_cost_of(cost_, ratio_, phase);
  if (cost.base.empty()) return 1.0;
  // Per rank its fixed list (with a tail) or its whole share of the plan: without a tail the
  // slowest rank is at or above the mean, and this is predicted_imbalance.
  double total = 0;
  for (std::size_t t = 0; t < cost.base.size(); ++t) total += cost(t);
  std::vector<double> fixed_load(capacity_.size(), 0.0);
  for (std::size_t r = 0; r < capacity_.size(); ++r)
    for (const int t : tasks_of_[phase][r]) fixed_load[r] += cost(static_cast<std::size_t>(t));
  return imbalance_with_tail_filling(fixed_load, total, capacity_);
}

void MpiExecutor::maybe_replan(int phase) {
  const long runs = runs_[phase];
  const double started = now_seconds();
  if (options_.policy == SchedulePolicy::every_evaluation) {
    if (runs > 0) adopt_plan(phase, make_plan(model_cost(phase), catalogue_, capacity_), PlanReason::forced, started);
    return;
  }
  if (size_ == 1) return;
  if (version_[phase] == 0) {
    const auto& rhs_cost = cost_[static_cast<int>(Phase::rhs)];
    if (runs >= warmup_evaluations)
      adopt_plan(phase, make_plan(model_cost(phase), catalogue_, capacity_), PlanReason::measured_costs, started);
    else if (runs == 0 && phase != static_cast<int>(Phase::rhs) && !rhs_cost.empty())
      // Before its own first measurement, a phase is planned on the right-hand side's costs: the
      // same contacts are expensive in both (the Jacobian task evaluates its segment once per
      // column), and Jacobians are rare, so waiting for their own warm-up costs real time.
      adopt_plan(phase, make_plan(rhs_cost, catalogue_, capacity_), PlanReason::measured_costs, started);
    return;
  }
  if (options_.policy != SchedulePolicy::adaptive) return;
  if (evaluation_ - last_plan_run_[phase] < cooldown_evaluations || evaluation_ - last_check_run_[phase] < check_interval)
    return;
  // Trigger on what was measured, or on what the cost model predicts for the current plan (the
  // Jacobian's model follows the right-hand side's costs between the rare Jacobians). This look
  // comes at every evaluation until it finds a reason, so it must be cheap (current_imbalance).
  const double now = current_imbalance(phase);
  if (smoothed_imbalance_[phase] <= replan_threshold && now <= replan_threshold) return;
  last_check_run_[phase] = evaluation_;
  const std::vector<double> cost = model_cost(phase);
  Plan candidate = make_plan(cost, catalogue_, capacity_);
  // With a tail the ranks wait only where a fixed list outgrows what the tail can fill: judged
  // without it, the plans followed every move of the loaded zone (on the heavy scene at np=2 a plan
  // every 47 evaluations, 0.2 ms of rank 0's time each, while the measured imbalance stayed at 1.01).
  const double after = tail_on_ ? predicted_imbalance_with_tail(candidate.owner, cost, capacity_, options_.tail_share)
                                : candidate.predicted_imbalance;
  double total = 0, cap_sum = 0;
  for (double c : cost) total += c;
  for (double c : capacity_) cap_sum += c;
  const double saved_per_evaluation = (now - after) * total / cap_sum;
  if (now - after >= min_predicted_gain &&
      saved_per_evaluation * gain_horizon > replan_cost_factor * replan_seconds_[phase])
    adopt_plan(phase, std::move(candidate), PlanReason::imbalance, started);
}

}  // namespace raceway::scheduler
