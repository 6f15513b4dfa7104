// Why a tree: the executor needs variable sizes and a master that can bound its waits, and
// MPI_Gatherv and the non-blocking MPI_Igather(v) of Open MPI (coll basic, libnbc) receive from every
// rank one by one, which is what the tree avoids: rank 0 takes ceil(log2 P) messages per evaluation
// instead of P - 1.
//
// Why not messages on one node: rank 0's wait for a worker's reply of a few kB that finished at the
// same moment was measured at a median of 4.5-6.6 us by message (a rendezvous past Open MPI's 4 KiB
// eager limit: three legs, each waiting on the other side's progress loop) against 1.2-2.1 us
// through the window, on the heavy scene at np=2 (perf/studies/results/parallel_notes.md (n)).
// Through the window a reply is the records in their slots and one word stored after them.
#include "scheduler/replies.hpp"

#include <algorithm>

#include "scheduler/spin_wait.hpp"

namespace raceway::scheduler {

std::vector<int> tree_children(int r, int size) {
  std::vector<int> children;
  const int below = r == 0 ? size : (r & -r);
  for (int m = 1; m < below && r + m < size; m <<= 1) children.push_back(r + m);
  return children;
}

int subtree_end(int r, int size) { return r == 0 ? size : std::min(size, r + (r & -r)); }

void ReplyExchange::open(const NodeWindow* window, bool shared_exchange) {
  window_ = shared_exchange && window && window->is_open() ? window : nullptr;
  receive_.resize(static_cast<std::size_t>(watch_.size()));
}

std::size_t ReplyExchange::packed_size(int phase, const std::vector<int>& tasks) const {
  std::size_t n = 0;
  for (const int t : tasks) n += static_cast<std::size_t>(catalogue_.used(phase, t));
  return n;
}

std::size_t ReplyExchange::subtree_reply_size(int phase, const RankTaskLists& lists, int r) const {
  std::size_t n = 0;
  for (int w = r; w < subtree_end(r, watch_.size()); ++w) {
    const auto& list = lists[static_cast<std::size_t>(w)];
    n += packed_size(phase, list) + list.size();
  }
  return n;
}

void ReplyExchange::place_record(int phase, int task, int w, const double* values, double task_seconds,
                                 std::vector<double>& records, std::vector<double>& seconds,
                                 std::vector<double>& busy) const {
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  const auto t = static_cast<std::size_t>(task);
  const auto used = static_cast<std::size_t>(catalogue_.used(phase, task));
  std::copy_n(values, used, records.data() + t * rs);
  std::fill_n(records.data() + t * rs + used, rs - used, 0.0);
  seconds[t] = task_seconds;
  busy[static_cast<std::size_t>(w)] += task_seconds;
}

void ReplyExchange::place_slots(int phase, const std::vector<int>& list, int w, std::vector<double>& records,
                                std::vector<double>& seconds, std::vector<double>& busy) const {
  const std::size_t stride = NodeWindow::slot_stride(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  for (const int task : list) {
    const double* slot = window_->slot(task, stride);
    place_record(phase, task, w, slot + 2, slot[1], records, seconds, busy);
  }
}

bool ReplyExchange::place_announced(int phase, const RankTaskLists& lists, long evaluation, std::vector<double>& records,
                                    std::vector<double>& seconds, std::vector<double>& busy) {
  bool placed = false;
  for (int w = 1; w < watch_.size(); ++w) {
    auto& done = placed_[static_cast<std::size_t>(w)];
    if (done || load_word(window_->reply_line(w, NodeWindow::fixed_word)) < evaluation) continue;
    window_->sync();  // the word before the slots
    place_slots(phase, lists[static_cast<std::size_t>(w)], w, records, seconds, busy);
    done = placed = true;
  }
  return placed;
}

void ReplyExchange::fixed_done(long evaluation) const {
  window_->sync();  // the slots before the word
  store_word(window_->reply_line(watch_.rank(), NodeWindow::fixed_word), evaluation);
}

void ReplyExchange::post_receives(int phase, const RankTaskLists& lists, std::vector<MPI_Request>& requests,
                                  std::vector<int>& ranks) {
  if (window_) {
    placed_.assign(static_cast<std::size_t>(watch_.size()), 0);
    return;
  }
  for (const int c : tree_children(0, watch_.size())) {
    auto& buf = receive_[static_cast<std::size_t>(c)];
    buf.resize(subtree_reply_size(phase, lists, c));
    requests.emplace_back();
    ranks.push_back(c);
    MPI_Irecv(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, c, phase, comm_, &requests.back());
  }
}

void ReplyExchange::collect(int phase, const RankTaskLists& lists, std::vector<MPI_Request>& requests,
                            const std::vector<int>& ranks, long evaluation, std::vector<double>& records,
                            std::vector<double>& seconds, std::vector<double>& busy) {
  if (window_) {
    channel_.await_workers(NodeWindow::reply_word, evaluation, "answer", phase, evaluation);
    channel_.replies_in();  // a worker takes a command before it replies to it
    window_->sync();        // the words before the slots
    for (int w = 1; w < watch_.size(); ++w)
      if (!placed_[static_cast<std::size_t>(w)]) place_slots(phase, lists[static_cast<std::size_t>(w)], w, records, seconds, busy);
    return;
  }
  if (!requests.empty())
    watch_.wait_bounded(requests, ranks, std::string("the ") + phase_name(phase) + " evaluation " + std::to_string(evaluation),
                        [this](int r) { return subtree_end(r, watch_.size()); });
  for (const int c : tree_children(0, watch_.size())) {
    const double* packed = receive_[static_cast<std::size_t>(c)].data();
    for (int w = c; w < subtree_end(c, watch_.size()); ++w) {  // each rank's: its records' used doubles, then its seconds
      const auto& list = lists[static_cast<std::size_t>(w)];
      const double* secs = packed + packed_size(phase, list);
      for (std::size_t i = 0; i < list.size(); ++i) {
        place_record(phase, list[i], w, packed, secs[i], records, seconds, busy);
        packed += catalogue_.used(phase, list[i]);
      }
      packed = secs + list.size();
    }
  }
}

void ReplyExchange::expect_subtree(int phase, const RankTaskLists& lists) {
  if (window_) return;
  const int rank = watch_.rank();
  const std::vector<int> children = tree_children(rank, watch_.size());
  reply_.resize(subtree_reply_size(phase, lists, rank));
  from_.assign(children.size(), MPI_REQUEST_NULL);
  const auto& mine = lists[static_cast<std::size_t>(rank)];
  std::size_t at = packed_size(phase, mine) + mine.size();  // the children's replies after its own, in rank order
  for (std::size_t i = 0; i < children.size(); ++i) {
    const auto count = subtree_reply_size(phase, lists, children[i]);
    MPI_Irecv(reply_.data() + at, static_cast<int>(count), MPI_DOUBLE, children[i], phase, comm_, &from_[i]);
    at += count;
  }
}

double* ReplyExchange::slot_of(int phase, int task) const {
  return window_->slot(task, NodeWindow::slot_stride(catalogue_.record_size[static_cast<std::size_t>(phase)]));
}

void ReplyExchange::send(int phase, const RankTaskLists& lists, const double* full, const double* seconds,
                         long evaluation) {
  const int rank = watch_.rank();
  const auto& mine = lists[static_cast<std::size_t>(rank)];
  const auto rs = static_cast<std::size_t>(catalogue_.record_size[static_cast<std::size_t>(phase)]);
  if (window_) {  // the tasks wrote their records and seconds into their slots: the reply word
    window_->sync();  // the slots before the word
    store_word(window_->reply_line(rank, NodeWindow::reply_word), evaluation);
    return;
  }
  double* out = reply_.data();
  for (std::size_t i = 0; i < mine.size(); ++i) out = std::copy_n(full + i * rs, catalogue_.used(phase, mine[i]), out);
  std::copy_n(seconds, mine.size(), out);
  watch_.await_master(from_);  // as long as it takes while rank 0 lives, like the commands
  std::vector<MPI_Request> to(1);
  MPI_Isend(reply_.data(), static_cast<int>(reply_.size()), MPI_DOUBLE, rank & (rank - 1), phase, comm_, to.data());
  watch_.await_master(to);
}

std::vector<int> piece_holders(std::span<const int> owner, std::span<const int> parent) {
  if (parent.empty()) return {owner.begin(), owner.end()};
  const int pieces = *std::max_element(parent.begin(), parent.end()) + 1;
  std::vector<int> tasks(static_cast<std::size_t>(pieces), 0), holder(static_cast<std::size_t>(pieces), 0);
  for (std::size_t t = 0; t < parent.size(); ++t) {
    const auto p = static_cast<std::size_t>(parent[t]);
    ++tasks[p];
    holder[p] = owner[t];
  }
  for (std::size_t p = 0; p < holder.size(); ++p)
    if (tasks[p] > 1) holder[p] = 0;  // a piece cut into tasks: the master combines its records
  return holder;
}

std::vector<int> piece_task_counts(std::span<const int> parent) {
  std::vector<int> count;
  for (const int p : parent) {
    if (static_cast<std::size_t>(p) >= count.size()) count.resize(static_cast<std::size_t>(p) + 1, 0);
    ++count[static_cast<std::size_t>(p)];
  }
  return count;
}

void keep_whole_pieces(std::span<const int> parent, std::span<const int> piece_tasks, std::span<const int> mine,
                       std::span<const double> full, std::size_t record_size, std::vector<int>& pieces,
                       std::vector<double>& records) {
  pieces.clear();
  records.clear();
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const int task = mine[i];
    const int piece = parent.empty() ? task : parent[static_cast<std::size_t>(task)];
    if (!parent.empty() && piece_tasks[static_cast<std::size_t>(piece)] != 1) continue;
    pieces.push_back(piece);
    const auto record = full.subspan(i * record_size, record_size);
    records.insert(records.end(), record.begin(), record.end());
  }
}

}  // namespace raceway::scheduler
