#include "scheduler/executor.hpp"
#include "scheduler/task_clock.hpp"

namespace raceway::scheduler {

const char* phase_name(int p) { return p == 0 ? "rhs" : p == 1 ? "jacobian" : "output"; }

void SerialExecutor::run(Phase phase, std::span<const double> context, int task_count, int record_size,
                         const TaskFunction& task, std::vector<double>& records) {
  const int p = static_cast<int>(phase);
  records.resize(static_cast<std::size_t>(task_count) * record_size);
  seconds_[p].resize(task_count);
  TaskClock clock;
  for (int i = 0; i < task_count; ++i) {
    task(context, i, std::span<double>(records.data() + static_cast<std::size_t>(i) * record_size, record_size));
    seconds_[p][i] = clock.lap();
    totals_[p] += seconds_[p][i];
  }
  ++runs_[p];
}

}  // namespace raceway::scheduler
