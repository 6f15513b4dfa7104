// The re-planning policy: before each evaluation of a phase, whether the MPI executor makes a new
// plan, and which. Pure (no MPI): it reads the cost model (scheduler/cost_model.hpp) and makes plans
// with scheduler/plan.hpp; unit-tested in tests/scheduler/replan_policy_test.cpp.
//
// - Warm-up: the first plan from measured costs replaces the uniform start plan after
//   warmup_evaluations of a phase (static and adaptive policies alike). Before its own first
//   measurement, a phase other than the right-hand side is planned on the right-hand side's costs:
//   the same contacts are expensive in both, and Jacobians are rare, so waiting for their own
//   warm-up costs real time.
// - Trigger (adaptive only): the smoothed measured imbalance, or the cost model's imbalance of the
//   current plan, above replan_threshold (5 % of the evaluation time lost).
// - Hysteresis: after a plan, no new plan for the same phase within cooldown_evaluations; after a
//   check that kept the plan, the next check comes check_interval evaluations later. Both count
//   evaluations of all phases (Jacobians are ~100 times rarer than right-hand sides, and their costs
//   move with the same loaded zone).
// - Gain test: the candidate must lower the model's imbalance by at least min_predicted_gain, and
//   the seconds it saves on the slowest rank over gain_horizon evaluations must exceed
//   replan_cost_factor times the measured cost of making and sending a plan. The horizon is a plan's
//   expected life: work moves with the balls' orbit and the load, over thousands of right-hand sides
//   (6309 R3: a ball crosses the loaded zone in ~10 ms, ~2000 rhs). With a tail the candidate is
//   judged with its tail filling the gaps: judged without, the plans followed every move of the
//   loaded zone (on the heavy scene at np=2 a plan every 47 evaluations, 0.2 ms of rank 0's time
//   each, while the measured imbalance stayed at 1.01).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "scheduler/cost_model.hpp"
#include "scheduler/plan.hpp"

namespace raceway::scheduler {

enum class SchedulePolicy {
  adaptive,          ///< re-plan when measured imbalance and predicted gain say so (the default)
  static_plan,       ///< one plan from the first measured costs, never changed (for comparison)
  every_evaluation,  ///< test only: a different plan before every evaluation (bitwise-identity tests)
};
const char* schedule_policy_name(SchedulePolicy p);

/// A plan the policy asks for, and why.
struct Replan {
  Plan plan;
  PlanReason reason = PlanReason::initial;
};

class ReplanPolicy {
 public:
  static constexpr long warmup_evaluations = 3;
  static constexpr double replan_threshold = 1.05;
  static constexpr long cooldown_evaluations = 20;
  static constexpr long check_interval = 10;
  static constexpr double min_predicted_gain = 0.02;
  static constexpr double replan_cost_factor = 2.0;
  static constexpr long gain_horizon = 200;

  /// `tail_share`: the plans' tail (0: none), which the gain test counts on.
  ReplanPolicy(SchedulePolicy policy, std::vector<double> capacity, double tail_share);

  /// Before the evaluation after `evaluation` (all phases counted) of `phase`, whose current plan
  /// has version `version` and fixed lists `lists` (per rank): the plan to adopt, if any.
  std::optional<Replan> decide(int phase, long evaluation, int version, const CostModel& costs,
                               const std::vector<std::vector<int>>& lists, const TaskCatalogue& catalogue);
  /// A plan of `phase` was adopted after `evaluation`: the cooldown and the check interval start.
  void adopted(int phase, long evaluation) { last_plan_[phase] = last_check_[phase] = evaluation; }

  /// The plans have a tail of this share (the node window opened; 0: none).
  void set_tail_share(double share) { tail_share_ = share; }
  std::span<const double> capacity() const { return capacity_; }

 private:
  SchedulePolicy policy_;
  std::vector<double> capacity_;
  double tail_share_;
  long last_plan_[phase_count] = {}, last_check_[phase_count] = {};
};

/// Test only (SchedulePolicy::every_evaluation): `plan` turned over the ranks of capacity > 0 by
/// version + 1 places, so every evaluation sees a different assignment (the bitwise-identity tests
/// need plans that really change); its counts and prediction (under `model`, when not empty) redone.
void rotate_plan(Plan& plan, int version, std::span<const double> capacity, const TaskCatalogue& catalogue,
                 std::span<const double> model);

}  // namespace raceway::scheduler
