// The cost model (scheduler/cost_model.hpp): smoothing, outlier clipping, the Jacobian's model from
// the right-hand side's costs, the imbalance of an evaluation and of a plan.
#include <gtest/gtest.h>

#include "scheduler/cost_model.hpp"

using namespace raceway::scheduler;

namespace {
constexpr int rhs = static_cast<int>(Phase::rhs), jacobian = static_cast<int>(Phase::jacobian);
}

TEST(CostModel, FirstMeasurementIsTakenAsItIsThenSmoothed) {
  CostModel m;
  m.measure(rhs, std::vector<double>{1.0, 2.0}, 1.0);
  EXPECT_EQ(m.measured(rhs), (std::vector<double>{1.0, 2.0}));
  m.measure(rhs, std::vector<double>{2.0, 2.0}, 1.0);
  // 1 + 0.2 (2 - 1) = 1.2; the unchanged task stays.
  EXPECT_DOUBLE_EQ(m.measured(rhs)[0], 1.2);
  EXPECT_DOUBLE_EQ(m.measured(rhs)[1], 2.0);
  EXPECT_EQ(m.evaluations(rhs), 2);
  EXPECT_EQ(m.evaluations(jacobian), 0);
}

TEST(CostModel, OutliersAreClippedToThreeTimesTheEstimate) {
  CostModel m;
  m.measure(rhs, std::vector<double>{1e-6}, 1.0);
  m.measure(rhs, std::vector<double>{1e-2}, 1.0);  // a task preempted for 10 ms
  // Clipped to 3e-6 (+1e-9): 1e-6 + 0.2 (3.001e-6 - 1e-6).
  EXPECT_NEAR(m.measured(rhs)[0], 1e-6 + 0.2 * (3e-6 + 1e-9 - 1e-6), 1e-18);
  // A steady rise gets through at up to 1.4x per evaluation.
  for (int i = 0; i < 60; ++i) m.measure(rhs, std::vector<double>{1e-3}, 1.0);
  EXPECT_NEAR(m.measured(rhs)[0], 1e-3, 1e-6);
}

TEST(CostModel, JacobianModelFollowsTheRhsCostTimesItsMeasuredRatio) {
  CostModel m;
  m.measure(rhs, std::vector<double>{1.0, 4.0}, 1.0);
  EXPECT_TRUE(m.model(jacobian).empty());  // nothing known of the Jacobian yet
  m.measure(jacobian, std::vector<double>{10.0, 8.0}, 1.0);  // ratios 10 and 2
  EXPECT_EQ(m.model(jacobian), (std::vector<double>{10.0, 8.0}));
  // The load moves: the rhs costs change, the Jacobian model follows without a Jacobian.
  for (int i = 0; i < 60; ++i) m.measure(rhs, std::vector<double>{3.0, 1.0}, 1.0);
  const auto model = m.model(jacobian);
  EXPECT_NEAR(model[0], 30.0, 1e-3);
  EXPECT_NEAR(model[1], 2.0, 1e-3);
  EXPECT_EQ(m.measured(jacobian), (std::vector<double>{10.0, 8.0}));  // its own measurement is unchanged
}

TEST(CostModel, ImbalanceIsSmoothedAndRestartsFromAPlansPrediction) {
  CostModel m;
  m.measure(rhs, std::vector<double>{1.0}, 2.0);
  EXPECT_DOUBLE_EQ(m.smoothed_imbalance(rhs), 2.0);
  m.measure(rhs, std::vector<double>{1.0}, 1.0);
  EXPECT_DOUBLE_EQ(m.smoothed_imbalance(rhs), 2.0 + 0.1 * (1.0 - 2.0));
  m.restart_imbalance(rhs, 1.02);
  EXPECT_DOUBLE_EQ(m.smoothed_imbalance(rhs), 1.02);
}

TEST(CostModel, PlanSecondsFirstAsTheyAreThenSmoothedAndClipped) {
  CostModel m;
  m.measure_plan_seconds(rhs, 1e-3);
  EXPECT_DOUBLE_EQ(m.plan_seconds(rhs), 1e-3);
  m.measure_plan_seconds(rhs, 1.0);  // one preempted plan: clipped to 3e-3
  EXPECT_DOUBLE_EQ(m.plan_seconds(rhs), 1e-3 + 0.2 * (3e-3 - 1e-3));
}

TEST(CostModel, CurrentImbalanceOfFixedListsWithAndWithoutATail) {
  CostModel m;
  m.measure(rhs, std::vector<double>{3.0, 1.0, 1.0, 1.0}, 1.0);
  const std::vector<double> capacity{1.0, 1.0};
  // Every task in a fixed list: loads 4 and 2, mean 3.
  EXPECT_DOUBLE_EQ(m.current_imbalance(rhs, {{0, 1}, {2, 3}}, capacity), 4.0 / 3.0);
  // Task 1 in the tail: fixed loads 3 and 2, the tail fills rank 1 up to the mean: no wait.
  EXPECT_DOUBLE_EQ(m.current_imbalance(rhs, {{0}, {2, 3}}, capacity), 1.0);
  EXPECT_DOUBLE_EQ(CostModel().current_imbalance(rhs, {{0}, {1}}, capacity), 1.0);  // nothing measured
}

TEST(EvaluationBalance, MaxOverMeanOfShareWeightedSeconds) {
  // Rank 0 at half a worker's share: its 1 s counts as 2.
  const auto b = evaluation_balance(std::vector<double>{1.0, 2.0, 3.0}, std::vector<double>{0.5, 1.0, 1.0});
  EXPECT_DOUBLE_EQ(b.total, 6.0);
  EXPECT_DOUBLE_EQ(b.mean, 6.0 / 2.5);
  EXPECT_DOUBLE_EQ(b.worst, 3.0);
  EXPECT_DOUBLE_EQ(b.imbalance, 3.0 / 2.4);
  // A rank of capacity 0 is left out of the worst and the mean, and nothing measured is balanced.
  EXPECT_DOUBLE_EQ(evaluation_balance(std::vector<double>{5.0, 1.0}, std::vector<double>{0.0, 1.0}).worst, 1.0);
  EXPECT_DOUBLE_EQ(evaluation_balance(std::vector<double>{0.0, 0.0}, std::vector<double>{1.0, 1.0}).imbalance, 1.0);
}
