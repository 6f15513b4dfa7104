// The re-planning policy (scheduler/replan_policy.hpp): warm-up, the Jacobian planned on the rhs
// costs, trigger, hysteresis, the gain test, the static and forced policies, the forced rotation.
#include <gtest/gtest.h>

#include "scheduler/replan_policy.hpp"

using namespace raceway::scheduler;

namespace {

constexpr int rhs = static_cast<int>(Phase::rhs), jacobian = static_cast<int>(Phase::jacobian);

TaskCatalogue catalogue(int tasks) {
  TaskCatalogue c;
  c.task_count = tasks;
  for (int t = 0; t < tasks; ++t) c.group.push_back(t), c.bodies.push_back({0, 1 + t});
  return c;
}

/// Per rank its tasks of `owner`.
std::vector<std::vector<int>> lists(const std::vector<int>& owner, int ranks) {
  std::vector<std::vector<int>> l(static_cast<std::size_t>(ranks));
  for (std::size_t t = 0; t < owner.size(); ++t) l[static_cast<std::size_t>(owner[t])].push_back(static_cast<int>(t));
  return l;
}

void measure(CostModel& m, int phase, const std::vector<double>& cost, double imbalance, int times) {
  for (int i = 0; i < times; ++i) m.measure(phase, cost, imbalance);
}

}  // namespace

TEST(ReplanPolicy, FirstMeasuredPlanAfterTheWarmUp) {
  const auto cat = catalogue(4);
  ReplanPolicy policy(SchedulePolicy::static_plan, {1.0, 1.0}, 0.0);
  CostModel m;
  const std::vector<double> cost{4.0, 1.0, 1.0, 2.0};
  measure(m, rhs, cost, 1.0, 2);
  EXPECT_FALSE(policy.decide(rhs, 2, 0, m, lists({0, 0, 1, 1}, 2), cat));
  measure(m, rhs, cost, 1.0, 1);
  const auto replan = policy.decide(rhs, 3, 0, m, lists({0, 0, 1, 1}, 2), cat);
  ASSERT_TRUE(replan);
  EXPECT_EQ(replan->reason, PlanReason::measured_costs);
  EXPECT_NEAR(replan->plan.predicted_imbalance, 1.0, 1e-12);  // {4} against {1, 1, 2}
  // Static: never again, however unbalanced.
  measure(m, rhs, {10.0, 1.0, 1.0, 1.0}, 3.0, 100);
  EXPECT_FALSE(policy.decide(rhs, 500, 1, m, lists({0, 0, 1, 1}, 2), cat));
}

TEST(ReplanPolicy, AJacobianIsPlannedOnTheRhsCostsBeforeItsOwnMeasurement) {
  const auto cat = catalogue(4);
  ReplanPolicy policy(SchedulePolicy::adaptive, {1.0, 1.0}, 0.0);
  CostModel m;
  EXPECT_FALSE(policy.decide(jacobian, 0, 0, m, lists({0, 0, 1, 1}, 2), cat));  // nothing measured
  m.measure(rhs, std::vector<double>{4.0, 1.0, 1.0, 2.0}, 1.0);
  const auto replan = policy.decide(jacobian, 1, 0, m, lists({0, 0, 1, 1}, 2), cat);
  ASSERT_TRUE(replan);
  EXPECT_EQ(replan->reason, PlanReason::measured_costs);
  EXPECT_NE(replan->plan.owner[0], replan->plan.owner[3]);  // the two heavy tasks apart
}

TEST(ReplanPolicy, AdaptiveReplansOnImbalanceAfterTheCooldownOnly) {
  const auto cat = catalogue(4);
  ReplanPolicy policy(SchedulePolicy::adaptive, {1.0, 1.0}, 0.0);
  CostModel m;
  const std::vector<int> bad{0, 0, 1, 1};  // loads 8 and 2 under the costs below
  measure(m, rhs, {4.0, 4.0, 1.0, 1.0}, 1.6, 5);
  policy.adopted(rhs, 100);
  EXPECT_FALSE(policy.decide(rhs, 100 + ReplanPolicy::cooldown_evaluations - 1, 1, m, lists(bad, 2), cat));
  const auto replan = policy.decide(rhs, 100 + ReplanPolicy::cooldown_evaluations, 1, m, lists(bad, 2), cat);
  ASSERT_TRUE(replan);
  EXPECT_EQ(replan->reason, PlanReason::imbalance);
  EXPECT_NEAR(replan->plan.predicted_imbalance, 1.0, 1e-12);
}

TEST(ReplanPolicy, ABalancedPlanIsKeptAndACheckWaitsForItsInterval) {
  const auto cat = catalogue(4);
  ReplanPolicy policy(SchedulePolicy::adaptive, {1.0, 1.0}, 0.0);
  CostModel m;
  measure(m, rhs, {1.0, 1.0, 1.0, 1.0}, 1.0, 5);
  EXPECT_FALSE(policy.decide(rhs, 1000, 1, m, lists({0, 0, 1, 1}, 2), cat));  // balanced: nothing
  // Unbalanced, but a candidate that gains less than the cost of a plan is refused: the check
  // that refused it starts the interval.
  CostModel tiny;
  measure(tiny, rhs, {1e-12, 1e-12, 1e-12, 3e-12}, 1.2, 5);
  tiny.measure_plan_seconds(rhs, 1.0);  // a plan costs 1 s; the gain is picoseconds
  EXPECT_FALSE(policy.decide(rhs, 1000, 1, tiny, lists({0, 0, 0, 0}, 2), cat));
  // With a plan that costs nothing the same look would re-plan, but the check interval holds it.
  CostModel cheap;
  measure(cheap, rhs, {1e-12, 1e-12, 1e-12, 3e-12}, 1.2, 5);
  EXPECT_FALSE(policy.decide(rhs, 1000 + ReplanPolicy::check_interval - 1, 1, cheap, lists({0, 0, 0, 0}, 2), cat));
  EXPECT_TRUE(policy.decide(rhs, 1000 + ReplanPolicy::check_interval, 1, cheap, lists({0, 0, 0, 0}, 2), cat));
}

TEST(ReplanPolicy, WithATailTheCandidateMustGainBeyondWhatTheTailFills) {
  const auto cat = catalogue(8);
  CostModel m;
  // Rank 0 holds 6, rank 1 4 of a total 10. Without a tail a balanced plan gains 0.2; with one task of
  // each rank in the tail the fixed lists are 5 and 3 and the tail fills the gap: nothing to gain.
  measure(m, rhs, {1.0, 1.0, 1.0, 1.0, 1.5, 1.5, 1.5, 1.5}, 1.1, 5);
  const std::vector<int> owner{0, 0, 0, 1, 0, 1, 1, 0};
  ReplanPolicy without(SchedulePolicy::adaptive, {1.0, 1.0}, 0.0), with(SchedulePolicy::adaptive, {1.0, 1.0}, 0.0);
  with.set_tail_share(0.1);
  EXPECT_TRUE(without.decide(rhs, 1000, 1, m, lists(owner, 2), cat));
  // The same plan, judged with the tail's lists (one cheap task of each rank in the tail).
  std::vector<std::vector<int>> fixed = lists(owner, 2);
  fixed[0].erase(fixed[0].begin());
  fixed[1].erase(fixed[1].begin());
  EXPECT_FALSE(with.decide(rhs, 1000, 1, m, fixed, cat));
}

TEST(ReplanPolicy, EveryEvaluationForcesAPlanOnceMeasuredEvenOnOneRank) {
  const auto cat = catalogue(3);
  ReplanPolicy policy(SchedulePolicy::every_evaluation, {1.0}, 0.0);
  CostModel m;
  EXPECT_FALSE(policy.decide(rhs, 0, 0, m, lists({0, 0, 0}, 1), cat));
  m.measure(rhs, std::vector<double>{1.0, 1.0, 1.0}, 1.0);
  const auto replan = policy.decide(rhs, 1, 0, m, lists({0, 0, 0}, 1), cat);
  ASSERT_TRUE(replan);
  EXPECT_EQ(replan->reason, PlanReason::forced);
}

TEST(RotatePlan, TurnsTheOwnersOverTheActiveRanks) {
  const auto cat = catalogue(4);
  Plan plan;
  plan.owner = {1, 1, 2, 3};
  const std::vector<double> capacity{0.0, 1.0, 1.0, 1.0};  // rank 0 takes nothing
  const std::vector<double> model{1.0, 1.0, 1.0, 1.0};
  rotate_plan(plan, 0, capacity, cat, model);  // one place on
  EXPECT_EQ(plan.owner, (std::vector<int>{2, 2, 3, 1}));
  EXPECT_EQ(plan.method, PlanMethod::rotated);
  EXPECT_NEAR(plan.predicted_imbalance, 2.0 / (4.0 / 3.0), 1e-12);
  rotate_plan(plan, 1, capacity, cat, model);  // two places on
  EXPECT_EQ(plan.owner, (std::vector<int>{1, 1, 2, 3}));
}
