// The clock the executors time tasks with (scheduler/task_clock.hpp) and the node window's slot
// layout (scheduler/node_window.hpp).
#include <gtest/gtest.h>

#include <chrono>

#include "scheduler/node_window.hpp"
#include "scheduler/task_clock.hpp"

using namespace raceway::scheduler;

TEST(TaskClock, LapsAddUpToSteadyClockAndEachCoversItsOwnWork) {
  using clock = std::chrono::steady_clock;
  TaskClock warm;  // the first list of the process calibrates
  const auto start = clock::now();
  TaskClock timer;
  double laps = 0;
  for (int i = 0; i < 6; ++i) {  // tasks of 1, 2, 1, 2, ... ms of busy work
    const double busy = 1e-3 * (1 + i % 2);
    const auto until = clock::now() + std::chrono::duration<double>(busy);
    while (clock::now() < until) {
    }
    const double s = timer.lap();
    laps += s;
    EXPECT_GE(s, 0.99 * busy) << "task " << i;  // at least its own work (more when the machine took the core)
  }
  const double wall = std::chrono::duration<double>(clock::now() - start).count();
  EXPECT_NEAR(laps, wall, 0.01 * wall);  // the counter's scale against steady_clock
}

TEST(NodeWindow, SlotsAreWholeCacheLinesHoldingRankSecondsAndRecord) {
  EXPECT_EQ(NodeWindow::slot_stride(24), 32u);  // an rhs record: 2 + 24 doubles in 4 lines
  EXPECT_EQ(NodeWindow::slot_stride(6), 8u);    // exactly one line
  EXPECT_EQ(NodeWindow::slot_stride(7), 16u);
  EXPECT_EQ(NodeWindow::slot_stride(312), 320u);
  for (std::size_t n = 1; n < 100; ++n) {
    EXPECT_EQ(NodeWindow::slot_stride(n) % NodeWindow::word_stride, 0u);
    EXPECT_GE(NodeWindow::slot_stride(n), n + 2);
    EXPECT_LT(NodeWindow::slot_stride(n), n + 2 + NodeWindow::word_stride);
  }
}
