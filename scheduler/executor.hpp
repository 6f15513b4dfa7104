// Task execution. The scheduler knows tasks, records and ranks, not physics: the
// solver hands it a callback that evaluates task i into a fixed-size record of doubles, and gets
// the records back in task order (the canonical order in which the master sums them), with each
// task's measured time.
//
// A task depends only on a broadcast context (for the equations of motion: [t, z...]), so the
// same task function can run on any rank: the master passes it to run(), the workers get it from
// their own copy of the equations (TaskCatalogue) and evaluate it with the context the master sent.
//
// This file holds the interface and the serial executor; scheduler/mpi_executor.hpp holds the MPI
// master/worker executor.
#pragma once

#include <array>
#include <functional>
#include <span>
#include <vector>

#include "scheduler/schedule_log.hpp"

namespace raceway::scheduler {

/// Kinds of work a command carries (they are costed and planned separately).
enum class Phase { rhs = 0, jacobian = 1, output = 2 };
inline constexpr int phase_count = 3;
/// "rhs", "jacobian", "output" (Phase as int).
const char* phase_name(int phase);

/// Evaluates task `task` with the broadcast `context` and writes the phase's record size of
/// doubles to `record`. Must not depend on anything but the context and data every rank builds
/// identically from the scene (the model): it runs on whichever rank the plan says.
using TaskFunction = std::function<void(std::span<const double> context, int task, std::span<double> record)>;

/// Task group of a task that belongs to no rolling element (cage-land and ring segments).
inline constexpr int border_group = -1;

/// What the equations tell the executor about their tasks, once, on every rank.
struct TaskCatalogue {
  int task_count = 0;
  int context_size = 0;  ///< doubles in the context of every run() (equations: 1 + state size)
  /// Per task: index of its rolling element (>= 0), or border_group. Level 1 of the plan keeps a
  /// rolling element's tasks together.
  std::vector<int> group;
  /// Per task: bodies whose states the task reads (for the edge weights of the level-1 graph).
  std::vector<std::array<int, 2>> bodies;
  /// Per task: the piece of work it is a part of (equations: its contact segment, when a heavy
  /// segment's work is cut into sub-tasks whose records the master combines in a fixed order).
  /// Level 2 of the plan moves a piece's tasks together unless the piece is heavy against a rank's
  /// share. Empty: every task is a piece of its own.
  std::vector<int> parent;
  std::array<TaskFunction, phase_count> function;  ///< empty where a phase has no tasks
  std::array<int, phase_count> record_size{};
  /// Per phase and task: how many leading doubles of its record the task fills (a cut segment's
  /// later parts only their traction sums); it writes zeros over the rest of its record. What
  /// crosses ranks is these doubles only, a size both sides know from the catalogue; the master
  /// zeroes the rest, so a record is the same whichever rank computed it. Empty: the whole record.
  std::array<std::vector<int>, phase_count> used_size;
  /// Doubles task `task` fills in `phase` (record_size when used_size is empty).
  int used(int phase, int task) const {
    const auto& u = used_size[static_cast<std::size_t>(phase)];
    return u.empty() ? record_size[static_cast<std::size_t>(phase)] : u[static_cast<std::size_t>(task)];
  }
};

class Executor {
 public:
  virtual ~Executor() = default;
  /// Master: announces the task catalogue (once, before the first run()). Collective in the MPI
  /// executor: it releases the workers, which then build their own catalogue and serve().
  virtual void attach(const TaskCatalogue& catalogue) { (void)catalogue; }
  /// Runs tasks 0..task_count-1 with `context` and fills records (task-major, record_size each).
  /// Collective in the MPI executor (master side; the workers are in serve()).
  virtual void run(Phase phase, std::span<const double> context, int task_count, int record_size,
                   const TaskFunction& task, std::vector<double>& records) = 0;
  /// Master: tells the workers to leave serve(). Idempotent; also done by the MPI executor's
  /// destructor so an exception on the master never leaves workers waiting.
  virtual void stop() {}
  /// Scheduler history (plans, imbalance, re-plans); nullptr for executors without a plan.
  virtual const ScheduleLog* schedule_log() const { return nullptr; }

  /// Measured seconds of each task in the last run of `phase`.
  const std::vector<double>& task_seconds(Phase phase) const { return seconds_[static_cast<int>(phase)]; }
  /// Total task seconds per phase since construction (summed over all ranks).
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
  void run(Phase phase, std::span<const double> context, int task_count, int record_size,
           const TaskFunction& task, std::vector<double>& records) override;
};

}  // namespace raceway::scheduler
