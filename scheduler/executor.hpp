// Task execution (DESIGN.md 5). The scheduler knows tasks, records and ranks, not physics: the
// solver hands it a callback that evaluates task i into a fixed-size record of doubles, and gets
// the records back in task order (the canonical order in which the master sums them), with each
// task's measured time.
//
// This file holds the interface and the serial executor; the MPI master/worker executor (issue 4)
// implements the same interface.
#pragma once

#include <functional>
#include <span>
#include <vector>

namespace raceway::scheduler {

/// Kinds of work a command carries (they are costed separately).
enum class Phase { rhs = 0, jacobian = 1, output = 2 };
inline constexpr int phase_count = 3;

/// Evaluates task `task` and writes `record_size` doubles to `record`.
using TaskFunction = std::function<void(int task, std::span<double> record)>;

class Executor {
 public:
  virtual ~Executor() = default;
  /// Runs tasks 0..task_count-1 and fills records (task-major, record_size each).
  /// Collective in the MPI executor.
  virtual void run(Phase phase, int task_count, int record_size, const TaskFunction& task,
                   std::vector<double>& records) = 0;
  /// Measured seconds of each task in the last run of `phase`.
  const std::vector<double>& task_seconds(Phase phase) const { return seconds_[static_cast<int>(phase)]; }
  /// Total task seconds per phase since construction.
  double total_seconds(Phase phase) const { return totals_[static_cast<int>(phase)]; }
  long runs(Phase phase) const { return runs_[static_cast<int>(phase)]; }

 protected:
  std::vector<double> seconds_[phase_count];
  double totals_[phase_count] = {};
  long runs_[phase_count] = {};
};

/// Runs every task on the calling process, timing each.
class SerialExecutor final : public Executor {
 public:
  void run(Phase phase, int task_count, int record_size, const TaskFunction& task,
           std::vector<double>& records) override;
};

}  // namespace raceway::scheduler
