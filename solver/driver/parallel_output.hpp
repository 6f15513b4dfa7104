// The parallel output's MPI side (docs/output_layout.md, "Who writes"): rank 0's SharedOutput,
// which brings the workers into the output through the executor's output command, and the
// workers' handler of that command, which keeps the diagnostics of the segments each evaluated at
// the output samples and takes part in the collective writes (io/h5/h5_parallel.hpp).
#pragma once

#include <mpi.h>

#include <array>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "scheduler/mpi_executor.hpp"
#include "solver/run/output_writer.hpp"
#include "solver/run/run.hpp"

namespace raceway::driver {

/// The output command's operations (its payload's first value).
enum class OutputOperation { sample = 1, write = 2 };

/// Rank 0: run::SharedOutput over the executor's workers.
class MpiSharedOutput final : public run::SharedOutput {
 public:
  MpiSharedOutput(MPI_Comm comm, scheduler::MpiExecutor& executor) : comm_(comm), executor_(executor) {}
  const std::vector<int>& sample(long sample) override;
  void write(const std::string& file, std::vector<h5::SharedRows>& rows) override;

 private:
  MPI_Comm comm_;
  scheduler::MpiExecutor& executor_;
};

/// A worker: the output handler of MpiExecutor::serve.
class WorkerOutput {
 public:
  WorkerOutput(MPI_Comm comm, std::map<std::string, run::SegmentSeries> series)
      : comm_(comm), series_(std::move(series)) {}
  void operator()(std::span<const double> payload, std::span<const int> tasks, std::span<const double> records);

 private:
  using Diagnostics = std::array<double, bearing::SegmentRecord::max_diagnostics>;
  void fill(h5::SharedRows& rows) const;

  MPI_Comm comm_;
  std::map<std::string, run::SegmentSeries> series_;
  std::map<long, std::map<int, Diagnostics>> samples_;  ///< by output sample: this rank's segments
  std::map<std::string, std::size_t> written_;          ///< rows of each series in the file
};

}  // namespace raceway::driver
