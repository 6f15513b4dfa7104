// The output's work at each output time on a thread of its own, beside the integration: the run's
// thread copies the interpolated state into a queue and integrates on; this thread evaluates the
// right-hand side for the diagnostics, appends the rows and adds to the summary's sums
// (docs/output_layout.md, "Who writes"; perf/results/output_notes.md has the measurements). The
// samples are worked one at a time in the order given, by the same code as on the run's thread,
// so the file and the sums are bitwise the ones the run's thread would have made.
//
// Hand-written rather than a thread pool from a library: one consumer, in order, a fixed ring of
// preallocated states (no allocation per sample), and woken only once per `batch` samples (a
// wake-up per sample cost the run's thread a futex call each time).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace raceway::solver {

class OutputThread {
 public:
  /// work(t, sample, z): the output of one sample, called on this object's thread, in order.
  using Work = std::function<void(double t, long sample, const std::vector<double>& z)>;
  OutputThread(std::size_t state_size, Work work, std::size_t capacity = 64, std::size_t batch = 16);
  /// Works the queued samples (unless one failed), then ends the thread; errors are dropped.
  ~OutputThread();
  OutputThread(const OutputThread&) = delete;
  OutputThread& operator=(const OutputThread&) = delete;

  /// Queues a copy of (t, sample, z); waits only while the queue is full. Rethrows the failure of an
  /// earlier sample's work (the samples after a failed one are not worked).
  void submit(double t, long sample, const std::vector<double>& z);
  /// Waits until every queued sample has been worked; rethrows a failure if `rethrow`.
  void drain(bool rethrow = true);
  /// Wall seconds spent in work() so far (read after drain()).
  double busy_seconds() const;

 private:
  struct Slot {
    double t = 0;
    long sample = 0;
    std::vector<double> z;
  };
  void loop();

  Work work_;
  std::vector<Slot> ring_;
  const std::size_t batch_;
  mutable std::mutex mutex_;
  std::condition_variable queued_, worked_;
  std::size_t head_ = 0, count_ = 0;  // the oldest queued slot; queued (and in work) samples
  bool urgent_ = false, stop_ = false;
  std::exception_ptr error_;
  double busy_ = 0;
  std::thread thread_;  // last: started when everything above exists
};

}  // namespace raceway::solver
