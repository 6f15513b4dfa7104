// The output's work at each output time on a thread of its own, beside the integration: the run's
// thread copies the interpolated state into a queue and integrates on; this thread evaluates the
// right-hand side for the diagnostics, appends the rows and adds to the summary's sums
// (docs/output_layout.md, "Who writes"; perf/studies/results/output_notes.md has the measurements). The
// samples are worked one at a time in the order given, by the same code as on the run's thread,
// so the file and the sums are bitwise the ones the run's thread would have made.
//
// Hand-written rather than a thread pool from a library: one consumer, in order, a fixed ring of
// preallocated states (no allocation per sample), and woken only once per `batch` samples (a
// wake-up per sample cost the run's thread a futex call each time).
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace raceway::run {

class OutputThread {
 public:
  /// work(t, sample, z, rows): the output of one sample, called on this object's thread, in order;
  /// `rows` the values the run's thread computed for it (the step-resolved pocket statistics).
  using Work =
      std::function<void(double t, long sample, const std::vector<double>& z, const std::vector<double>& rows)>;
  OutputThread(std::size_t state_size, Work work, std::size_t capacity = 256, std::size_t batch = 16);
  /// Works the queued samples (unless one failed), then ends the thread; errors are dropped.
  ~OutputThread();
  OutputThread(const OutputThread&) = delete;
  OutputThread& operator=(const OutputThread&) = delete;

  /// Queues a copy of (t, sample, z, rows); waits only while the queue is full. Rethrows the failure of an
  /// earlier sample's work (the samples after a failed one are not worked).
  void submit(double t, long sample, const std::vector<double>& z, const std::vector<double>& rows);
  /// Waits until every queued sample has been worked; rethrows a failure if `rethrow`.
  void drain(bool rethrow = true);
  /// Binds this object's thread alone to the logical CPU `core`; returns its affinity read back
  /// ("" when the system refused: h5::bind_thread_to_core).
  std::string bind_to_core(int core);
  /// Wall seconds spent in work() so far (read after drain()).
  double busy_seconds() const { return busy_; }

 private:
  struct Slot {
    double t = 0;
    long sample = 0;
    std::vector<double> z, rows;
  };
  void loop();
  void wake();

  Work work_;
  std::vector<Slot> ring_;
  const std::size_t batch_;
  // A single-producer, single-consumer ring without a lock (a lock held by a thread that the system
  // preempts stalls the other one: measured on a loaded machine): the run's thread alone writes
  // queued_ (samples queued so far), the output thread alone worked_ (samples worked so far);
  // slot i % capacity belongs to the run's thread while i >= queued_, to the output thread while
  // worked_ <= i < queued_. Both wait with C++20 atomic waits, which make no system call when
  // nobody waits.
  std::atomic<std::uint64_t> queued_{0}, worked_{0};
  std::atomic<std::uint32_t> signal_{0};  ///< bumped to wake the output thread: a batch, a drain, the stop
  std::atomic<bool> stop_{false}, failed_{false};
  std::exception_ptr error_;  ///< set before failed_ (release)
  double busy_ = 0;           ///< the output thread's; read after a drain
  std::thread thread_;  // last: started when everything above exists
};

}  // namespace raceway::run
