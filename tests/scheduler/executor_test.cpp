// Executors on one process (MPI singleton): MpiExecutor gives the same records as SerialExecutor
// in task order, measures every task, keeps its schedule log bounded, and refuses mismatched
// calls. (Several ranks: tests/system/parallel.)
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

#include "scheduler/mpi_executor.hpp"

using namespace raceway::scheduler;

namespace {

TaskCatalogue catalogue(int tasks) {
  TaskCatalogue c;
  c.task_count = tasks;
  c.context_size = 3;
  for (int t = 0; t < tasks; ++t) c.group.push_back(t < tasks - 1 ? t / 2 : border_group), c.bodies.push_back({0, 1 + t / 2});
  c.function[0] = [](std::span<const double> ctx, int task, std::span<double> rec) {
    for (std::size_t i = 0; i < rec.size(); ++i) rec[i] = std::sin(ctx[0] * task + ctx[1] * static_cast<double>(i)) + ctx[2];
  };
  c.record_size[0] = 4;
  c.function[1] = c.function[0];
  c.record_size[1] = 7;
  return c;
}

}  // namespace

TEST(MpiExecutor, SameRecordsAsSerialInTaskOrder) {
  const auto cat = catalogue(9);
  for (auto policy : {SchedulePolicy::adaptive, SchedulePolicy::every_evaluation}) {
    MpiExecutorOptions o;
    o.policy = policy;
    MpiExecutor mpi(MPI_COMM_SELF, o);
    SerialExecutor serial;
    mpi.attach(cat);
    std::vector<double> a, b;
    for (int e = 0; e < 30; ++e) {
      const std::vector<double> ctx{0.1 * e, 0.3, -1.0 * e};
      const int p = e % 5 == 4 ? 1 : 0;
      mpi.run(static_cast<Phase>(p), ctx, 9, cat.record_size[p], cat.function[p], a);
      serial.run(static_cast<Phase>(p), ctx, 9, cat.record_size[p], cat.function[p], b);
      ASSERT_EQ(a, b) << "evaluation " << e;
      ASSERT_EQ(mpi.task_seconds(static_cast<Phase>(p)).size(), 9u);
    }
    const ScheduleLog* log = mpi.schedule_log();
    ASSERT_NE(log, nullptr);
    EXPECT_EQ(log->evaluations[0] + log->evaluations[1], 30);
    EXPECT_EQ(log->samples.size(), 30u);
    EXPECT_EQ(log->task_cost[0].size(), 9u);
    if (policy == SchedulePolicy::every_evaluation) {
      EXPECT_GE(log->plans.size(), 30u);
    }
    mpi.stop();
  }
}

TEST(MpiExecutor, RecordsCarryOnlyTheDoublesEachTaskUses) {
  // Each task declares how many leading doubles of its record it fills and writes zeros beyond
  // them; the records are those of the serial executor, and the schedule log has the sizes (what
  // crosses ranks: tests/system/parallel compares the results of several ranks bit for bit).
  auto cat = catalogue(6);
  cat.used_size[0] = {4, 1, 2, 4, 3, 0};
  cat.used_size[1] = {7, 7, 2, 5, 1, 3};
  for (int p = 0; p < 2; ++p)
    cat.function[static_cast<std::size_t>(p)] = [full = cat.function[static_cast<std::size_t>(p)], used = cat.used_size[static_cast<std::size_t>(p)]](
                                                   std::span<const double> ctx, int task, std::span<double> rec) {
      full(ctx, task, rec);
      std::fill(rec.begin() + used[static_cast<std::size_t>(task)], rec.end(), 0.0);
    };
  MpiExecutor mpi(MPI_COMM_SELF, {});
  SerialExecutor serial;
  mpi.attach(cat);
  std::vector<double> a, b;
  for (int p = 0; p < 2; ++p) {
    const std::vector<double> ctx{0.7, 0.2, 0.5};
    mpi.run(static_cast<Phase>(p), ctx, 6, cat.record_size[p], cat.function[p], a);
    serial.run(static_cast<Phase>(p), ctx, 6, cat.record_size[p], cat.function[p], b);
    const auto rs = static_cast<std::size_t>(cat.record_size[p]);
    for (std::size_t t = 0; t < 6; ++t)
      for (std::size_t i = 0; i < rs; ++i) {
        const bool used = i < static_cast<std::size_t>(cat.used_size[p][t]);
        ASSERT_EQ(a[t * rs + i], b[t * rs + i]) << "phase " << p << " task " << t << " slot " << i;
        ASSERT_EQ(used, a[t * rs + i] != 0.0) << "phase " << p << " task " << t << " slot " << i;
      }
    EXPECT_EQ(mpi.schedule_log()->task_record_size[static_cast<std::size_t>(p)], cat.used_size[p]);
  }
}

TEST(MpiExecutor, RejectsCallsThatDoNotMatchTheCatalogue) {
  const auto cat = catalogue(5);
  MpiExecutor mpi(MPI_COMM_SELF, {});
  std::vector<double> r;
  const std::vector<double> ctx{0, 0, 0};
  EXPECT_THROW(mpi.run(Phase::rhs, ctx, 5, 4, cat.function[0], r), std::logic_error);  // before attach
  mpi.attach(cat);
  EXPECT_THROW(mpi.run(Phase::rhs, ctx, 6, 4, cat.function[0], r), std::invalid_argument);
  EXPECT_THROW(mpi.run(Phase::rhs, ctx, 5, 5, cat.function[0], r), std::invalid_argument);
  EXPECT_THROW(mpi.run(Phase::rhs, std::vector<double>{0, 0}, 5, 4, cat.function[0], r), std::invalid_argument);
}

TEST(MpiExecutor, ImbalanceSamplesStayBounded) {
  const auto cat = catalogue(3);
  MpiExecutor mpi(MPI_COMM_SELF, {});
  mpi.attach(cat);
  std::vector<double> r;
  const std::vector<double> ctx{0, 0, 0};
  const long n = (1L << 17) + 5000;
  for (long e = 0; e < n; ++e) mpi.run(Phase::rhs, ctx, 3, 4, cat.function[0], r);
  const ScheduleLog* log = mpi.schedule_log();
  EXPECT_EQ(log->sample_every, 2);
  EXPECT_LT(log->samples.size(), std::size_t{1} << 17);
  for (const auto& s : log->samples) ASSERT_EQ(s.evaluation % 2, 0);
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  MPI_Finalize();
  return result;
}
