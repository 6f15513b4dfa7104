// How the MPI executor's ranks notice one another stopping: rank 0 bounds every wait for the
// workers (rank_timeout), the workers watch rank 0's heartbeat (scheduler/rank_watch.cpp), and a
// failure on any rank ends every rank (MPI_Abort) with a diagnosis on that rank's stderr.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <string>
#include <thread>
#include <vector>

namespace raceway::scheduler {

class RankWatch {
 public:
  RankWatch(MPI_Comm comm, double rank_timeout);
  RankWatch(const RankWatch&) = delete;
  RankWatch& operator=(const RankWatch&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  double timeout() const { return timeout_; }
  /// The timeout as the diagnoses print it ("60").
  std::string timeout_text() const;

  /// Prints "[raceway] rank R of P: error: what" and ends every rank (MPI_Abort, exit code 1).
  [[noreturn]] void fail(const std::string& what) const;

  /// Every rank, collective: with every rank on rank 0's node, rank 0 starts a heartbeat (a word in
  /// shared memory a thread of its own renews every 50 ms) that the workers' waits watch.
  void watch_master();
  /// Collective: the heartbeat stopped and its window freed.
  void close();

  /// Master: waits for `requests`, at most the timeout; ranks[i] is the rank that completes
  /// requests[i] (-1: a broadcast). Past the timeout, fails naming the silent ranks (and the ranks
  /// whose replies they pass on: `subtree_end(r)`).
  template <class SubtreeEnd>
  void wait_bounded(std::vector<MPI_Request>& requests, const std::vector<int>& ranks, const std::string& what,
                    SubtreeEnd subtree_end) const;
  /// Worker: waits for `requests` (to or from rank 0, or passing on to it) as long as rank 0 lives.
  void await_master(std::vector<MPI_Request>& requests) const;

  /// Worker, during one wait for rank 0: check() fails the job when rank 0's heartbeat has not
  /// changed for the timeout since the wait began or the last beat. Nothing without a heartbeat.
  class MasterWatch {
   public:
    explicit MasterWatch(const RankWatch& watch);
    void check();

   private:
    const RankWatch& watch_;
    std::int64_t beat_;
    double since_;
  };

  /// steady_clock seconds.
  static double now_seconds();

 private:
  /// wait_bounded's diagnosis.
  [[noreturn]] void fail_silent(const std::string& silent, const std::string& what) const;

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  double timeout_;
  MPI_Comm heartbeat_comm_ = MPI_COMM_NULL;
  MPI_Win heartbeat_window_ = MPI_WIN_NULL;
  std::int64_t* heartbeat_word_ = nullptr;
  std::jthread heartbeat_thread_;
};

template <class SubtreeEnd>
void RankWatch::wait_bounded(std::vector<MPI_Request>& requests, const std::vector<int>& ranks,
                             const std::string& what, SubtreeEnd subtree_end) const {
  // MPI_Waitall cannot be bounded; a worker stopped by a signal would hold the master (at 100 %
  // CPU) for ever. Polling with MPI_Testsome costs what MPI_Waitall's own progress loop does.
  const auto n = static_cast<int>(requests.size());
  std::vector<int> done(requests.size()), indices(requests.size());
  const double deadline = now_seconds() + timeout_;
  int completed = 0;
  while (completed < n) {
    int count = 0;
    MPI_Testsome(n, requests.data(), &count, indices.data(), MPI_STATUSES_IGNORE);
    if (count == MPI_UNDEFINED) break;  // every request is inactive
    for (int i = 0; i < count; ++i) done[static_cast<std::size_t>(indices[static_cast<std::size_t>(i)])] = 1;
    completed += count;
    if (completed < n && now_seconds() > deadline) {
      std::string silent;
      for (std::size_t i = 0; i < requests.size(); ++i)
        if (!done[i] && ranks[i] >= 0) {
          silent += (silent.empty() ? "" : ", ") + std::to_string(ranks[i]);
          if (const int end = subtree_end(ranks[i]); end > ranks[i] + 1)  // it passes on the replies of ranks below it
            silent += " (or one of ranks " + std::to_string(ranks[i] + 1) + "-" + std::to_string(end - 1) + " below it)";
        }
      fail_silent(silent, what);
    }
  }
}

}  // namespace raceway::scheduler
