// Rank 0's heartbeat: how a worker tells a stalled rank 0 from a busy one; and the bounded waits.
//
// A worker waits for rank 0's next command as long as rank 0 computes: between two commands rank 0
// may integrate, write a large output sample, a checkpoint or the final commit, for longer than
// any fixed timeout. Silence alone therefore says nothing. With every rank on rank 0's node, rank 0
// keeps a word in a small shared-memory window and a thread of its own stores a new number there
// every beat_seconds, whatever its run's thread is doing (that thread never calls MPI: MPI stays on
// the run's thread, as MPI_THREAD_FUNNELED asks). A rank 0 stopped (SIGSTOP), frozen or gone stops
// beating; a worker that waits for it and sees no new beat for --rank-timeout seconds ends the job
// with a diagnosis (MPI_Abort, exit code 1) instead of waiting for ever. A live rank 0 whose run's
// thread is blocked (a deadlock in a library) still beats: its own bounds (the step and wall-time
// budgets, its waits on the workers) cover that. Between nodes there is no shared window and the
// workers wait as before (docs: README.md, "In parallel").
#include "scheduler/rank_watch.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace raceway::scheduler {

namespace {

constexpr double beat_seconds = 0.05;

std::int64_t load_beat(const std::int64_t* word) {
  return std::atomic_ref<const std::int64_t>(*word).load(std::memory_order_acquire);
}

}  // namespace

RankWatch::RankWatch(MPI_Comm comm, double rank_timeout) : comm_(comm), timeout_(rank_timeout) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

double RankWatch::now_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string RankWatch::timeout_text() const {
  char text[32];
  std::snprintf(text, sizeof text, "%g", timeout_);
  return text;
}

void RankWatch::fail(const std::string& what) const {
  std::fprintf(stderr, "[raceway] rank %d of %d: error: %s\n", rank_, size_, what.c_str());
  std::fflush(stderr);
  MPI_Abort(comm_, 1);
  std::abort();  // MPI_Abort does not return; this keeps [[noreturn]] honest
}

void RankWatch::fail_silent(const std::string& silent, const std::string& what) const {
  fail((silent.empty() ? std::string("the workers") : "rank " + silent) + " did not answer " + what + " within " +
       timeout_text() + " s (--rank-timeout): stopped, hung or lost; ending the job");
}

void RankWatch::watch_master() {
  if (size_ < 2 || heartbeat_window_ != MPI_WIN_NULL) return;
  MPI_Comm node = MPI_COMM_NULL;
  MPI_Comm_split_type(comm_, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  int node_size = 0;
  MPI_Comm_size(node, &node_size);
  int all_on_one_node = node_size == size_ ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &all_on_one_node, 1, MPI_INT, MPI_MIN, comm_);
  if (!all_on_one_node) {
    MPI_Comm_free(&node);
    return;
  }
  heartbeat_comm_ = node;
  void* base = nullptr;
  MPI_Win_allocate_shared(rank_ == 0 ? MPI_Aint{64} : MPI_Aint{0}, 1, MPI_INFO_NULL, heartbeat_comm_, &base,
                          &heartbeat_window_);
  MPI_Aint bytes = 0;
  int unit = 0;
  MPI_Win_shared_query(heartbeat_window_, 0, &bytes, &unit, &base);
  heartbeat_word_ = static_cast<std::int64_t*>(base);
  if (rank_ == 0) {
    std::atomic_ref<std::int64_t>(*heartbeat_word_).store(0, std::memory_order_release);
    heartbeat_thread_ = std::jthread([word = heartbeat_word_](std::stop_token stop) {
      for (std::int64_t beat = 1; !stop.stop_requested(); ++beat) {
        std::atomic_ref<std::int64_t>(*word).store(beat, std::memory_order_release);
        std::this_thread::sleep_for(std::chrono::duration<double>(beat_seconds));
      }
    });
  }
  MPI_Barrier(heartbeat_comm_);  // the word is set before any worker reads it
}

void RankWatch::close() {
  if (heartbeat_thread_.joinable()) {
    heartbeat_thread_.request_stop();
    heartbeat_thread_.join();
  }
  heartbeat_word_ = nullptr;
  if (heartbeat_window_ != MPI_WIN_NULL) MPI_Win_free(&heartbeat_window_);
  if (heartbeat_comm_ != MPI_COMM_NULL) MPI_Comm_free(&heartbeat_comm_);
}

RankWatch::MasterWatch::MasterWatch(const RankWatch& watch)
    : watch_(watch), beat_(watch.heartbeat_word_ ? load_beat(watch.heartbeat_word_) : 0), since_(now_seconds()) {}

void RankWatch::MasterWatch::check() {
  if (!watch_.heartbeat_word_) return;
  const double now = now_seconds();
  if (const std::int64_t beat = load_beat(watch_.heartbeat_word_); beat != beat_) {
    beat_ = beat, since_ = now;
    return;
  }
  if (now - since_ <= watch_.timeout_) return;
  watch_.fail("rank 0 sent nothing for " + watch_.timeout_text() + " s and its heartbeat stopped (--rank-timeout): "
              "it is stopped (SIGSTOP), frozen or lost; ending the job");
}

void RankWatch::await_master(std::vector<MPI_Request>& requests) const {
  if (!heartbeat_word_) {  // between nodes: as long as it takes
    MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
    return;
  }
  MasterWatch watch(*this);
  for (;;) {
    int done = 0;
    MPI_Testall(static_cast<int>(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE);
    if (done) return;
    watch.check();
    std::this_thread::yield();
  }
}

}  // namespace raceway::scheduler
