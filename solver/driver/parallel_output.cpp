#include "solver/driver/parallel_output.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "io/h5/h5_parallel.hpp"

namespace raceway::driver {

const std::vector<int>& MpiSharedOutput::sample(long sample) {
  const double payload[2] = {static_cast<double>(OutputOperation::sample), static_cast<double>(sample)};
  return executor_.output(payload);
}

void MpiSharedOutput::write(const std::string& file, std::vector<h5::SharedRows>& rows) {
  const double payload[1] = {static_cast<double>(OutputOperation::write)};
  executor_.output(payload);
  std::string path = file;
  if (const std::string error = h5::write_shared_rows(comm_, path, rows, {}); !error.empty())
    throw std::runtime_error(error);
}

void WorkerOutput::operator()(std::span<const double> payload, std::span<const int> tasks,
                              std::span<const double> records) {
  const auto operation = static_cast<OutputOperation>(static_cast<int>(payload[0]));
  if (operation == OutputOperation::sample) {
    auto& sample = samples_[static_cast<long>(payload[1])];
    const std::size_t size = records.size() / std::max<std::size_t>(1, tasks.size());
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      const double* d = records.data() + i * size + bearing::SegmentRecord::diagnostics;
      std::copy_n(d, bearing::SegmentRecord::max_diagnostics, sample[tasks[i]].begin());
    }
    return;
  }
  std::string file;
  std::vector<h5::SharedRows> rows;
  const std::string error = h5::write_shared_rows(comm_, file, rows, [this](h5::SharedRows& r) { fill(r); });
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  if (!error.empty()) {  // rank 0 throws the same text and ends the run; this rank says it too
    std::fprintf(stderr, "[raceway] rank %d: error: %s\n", rank, error.c_str());
    std::fflush(stderr);
    return;
  }
  // The samples every shared series has in the file are not needed any more.
  std::size_t done = static_cast<std::size_t>(-1);
  long stride = 1;  // the segment series' rows are every stride-th output sample ([output] segment_every)
  for (const h5::SharedRows& r : rows) {
    done = std::min(done, written_[r.path] = r.first_row + r.rows);
    if (const auto s = series_.find(r.path); s != series_.end()) stride = s->second.stride;
  }
  samples_.erase(samples_.begin(), samples_.lower_bound(static_cast<long>(done) * stride));
}

void WorkerOutput::fill(h5::SharedRows& r) const {
  const auto series = series_.find(r.path);
  if (series == series_.end()) throw std::runtime_error("rank 0 writes a shared series this rank does not know: " + r.path);
  const auto& segments = series->second.segments;
  const auto field = static_cast<std::size_t>(series->second.field);
  if (segments.size() != r.row_size) throw std::runtime_error("the shared series " + r.path + " has another row size here");
  for (std::size_t row = 0; row < r.rows; ++row) {
    // A sample this rank did not see (the rows a resumed run took from its checkpoint): rank 0's.
    const auto sample = samples_.find(static_cast<long>(r.first_row + row) * series->second.stride);
    if (sample == samples_.end()) continue;
    for (std::size_t c = 0; c < segments.size(); ++c)
      if (const auto mine = sample->second.find(segments[c]); mine != sample->second.end()) {
        r.cells.push_back(row * r.row_size + c);
        r.values.push_back(mine->second[field]);
      }
  }
}

}  // namespace raceway::driver
