#include "scheduler/command_channel.hpp"

#include <algorithm>

#include "scheduler/executor.hpp"
#include "scheduler/replies.hpp"
#include "scheduler/spin_wait.hpp"

namespace raceway::scheduler {

void CommandChannel::broadcast(void* buffer, int count, MPI_Datatype type, const std::string& what) {
  std::vector<MPI_Request> request(1);
  MPI_Ibcast(buffer, count, type, 0, comm_, request.data());
  if (watch_.rank() == 0)
    watch_.wait_bounded(request, {-1}, what, [this](int r) { return subtree_end(r, watch_.size()); });
  else
    watch_.await_master(request);  // as long as rank 0 lives (its heartbeat, where there is one)
}

void CommandChannel::send_first(const CommandHeader& header, const char* what) {
  double first[command_header_size];
  write_header(header, first);
  broadcast(first, static_cast<int>(command_header_size), MPI_DOUBLE, what);
}

CommandHeader CommandChannel::receive_first() {
  double first[command_header_size];
  broadcast(first, static_cast<int>(command_header_size), MPI_DOUBLE, "the start of the run");
  try {
    return read_header(first, phase_count);
  } catch (const CommandError& e) {
    watch_.fail(e.what());
  }
}

void CommandChannel::open(int context_size, const NodeWindow* window) {
  buffer_.assign(command_header_size + static_cast<std::size_t>(context_size), 0.0);
  window_ = window && window->has_command() ? window : nullptr;
}

void CommandChannel::send(const CommandHeader& header, std::span<const double> payload, const char* what,
                          std::vector<MPI_Request>* pending, std::vector<int>* pending_ranks) {
  write_header(header, buffer_);
  if (header.kind == CommandKind::evaluate) evaluation_ = header.number;
  const auto after = std::copy(payload.begin(), payload.end(), buffer_.begin() + command_header_size);
  std::fill(after, buffer_.end(), 0.0);
  if (!window_) {
    if (!pending) return broadcast(buffer_.data(), static_cast<int>(buffer_.size()), MPI_DOUBLE, what);
    pending->emplace_back();
    pending_ranks->push_back(-1);
    MPI_Ibcast(buffer_.data(), static_cast<int>(buffer_.size()), MPI_DOUBLE, 0, comm_, &pending->back());
    return;
  }
  if (taken_by_all_ < commands_) {  // the buffer is free once every worker has copied it
    await_workers(NodeWindow::taken_word, commands_, "answer rank 0's command after", -1, evaluation_);
    taken_by_all_ = commands_;
  }
  std::copy(buffer_.begin(), buffer_.end(), window_->command_buffer());
  window_->sync();  // the buffer before the word
  store_word(window_->command_word(), ++commands_);
}

CommandHeader CommandChannel::receive() {
  if (!window_) {
    broadcast(buffer_.data(), static_cast<int>(buffer_.size()), MPI_DOUBLE, "a command");
  } else {
    // A worker waits for its master as long as it takes while rank 0 lives (its heartbeat; the
    // master bounds its own waits). Idle between commands, it yields at every look once the spin
    // is over.
    const std::int64_t next = commands_ + 1;
    RankWatch::MasterWatch watch(watch_);
    spin_then_yield(1, [&] { return load_word(window_->command_word()) >= next; },
                    [&](std::chrono::steady_clock::time_point) { watch.check(); });
    window_->sync();  // the word before the buffer
    std::copy_n(window_->command_buffer(), buffer_.size(), buffer_.begin());
    commands_ = next;
    store_word(window_->reply_line(watch_.rank(), NodeWindow::taken_word), next);
  }
  try {
    return read_header(buffer_, phase_count);
  } catch (const CommandError& e) {
    watch_.fail(e.what());
  }
}

void CommandChannel::broadcast_owners(std::vector<int>& owner) {
  broadcast(owner.data(), static_cast<int>(owner.size()), MPI_INT, "a new plan's owners");
}

void CommandChannel::await_workers(std::size_t word, std::int64_t value, const char* what, int phase, long evaluation) {
  const double deadline = RankWatch::now_seconds() + watch_.timeout();
  int first_silent = 0;
  const auto all_there = [&] {
    first_silent = 0;
    for (int r = 1; r < watch_.size() && first_silent == 0; ++r)
      if (load_word(window_->reply_line(r, word)) < value) first_silent = r;
    return first_silent == 0;
  };
  // Rank 0 yields only at the clock readings: a yield at every look delayed its noticing the
  // last reply (rank 0 beyond the slowest rank 0.023 -> 0.042 s per 20 ms run, medians of 9).
  spin_then_yield(looks_per_clock_reading, all_there, [&](std::chrono::steady_clock::time_point) {
    if (RankWatch::now_seconds() <= deadline) return;
    const std::string evaluation_text = (phase >= 0 ? std::string("the ") + phase_name(phase) + " " : std::string()) +
                                        "evaluation " + std::to_string(evaluation);
    watch_.fail("rank " + std::to_string(first_silent) + " did not " + what + " " + evaluation_text + " within " +
                watch_.timeout_text() + " s (--rank-timeout): stopped, hung or lost; ending the job");
  });
}

}  // namespace raceway::scheduler
