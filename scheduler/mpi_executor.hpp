// The MPI master/worker executor (parallelism across the contact tasks, after seed 000 section 2.6;
// docs/references.md).
//
// Rank 0 (the master) owns CVODE and calls run(); it also evaluates its share of the tasks. The
// other ranks (workers) loop in serve() on the master's commands:
//   evaluate (phase, context)  -> evaluate the tasks the phase's plan gives this rank, give back
//                                 their records and measured seconds: with every rank on rank 0's
//                                 node through a shared-memory window (the records in per-task
//                                 slots, then a word with the evaluation's number; mpi_replies.cpp),
//                                 else one message up a binomial tree to rank 0, with the replies of
//                                 the ranks below; of each record only the doubles the task fills
//                                 (TaskCatalogue::used_size, a size both sides know, so nothing
//                                 about sizes is exchanged per evaluation);
//   plan (phase), then owner per task in a second broadcast -> adopt a new plan for that phase;
//   output (payload)           -> call serve()'s output handler with the payload and the records of
//                                 this rank's last rhs evaluation (the parallel output's samples
//                                 and collective writes, solver/driver/parallel_output.hpp);
//   stop                       -> leave serve().
// With a tail (MpiExecutorOptions::tail_share; scheduler/mpi_tail.cpp) part of each evaluation's
// tasks are no rank's: every rank done with its fixed list claims them one by one (an atomic
// counter in a shared-memory window) and writes their records there, where rank 0 picks them up.
// Every command is one fixed-size buffer (header + context), so a worker never needs to know in
// advance which command comes: with every rank on rank 0's node and the shared exchange, written into
// the node window (scheduler/mpi_commands.cpp), else broadcast (MPI_Ibcast, non-blocking on every
// rank, so the master can bound its waits). The master places the records in
// task order; the equations sum them in that order, so results are bitwise identical for any rank
// count and any plan.
//
// Scheduling: per phase, a smoothed cost per task (exponential moving average of measured task
// seconds) feeds scheduler/plan.hpp's two-level plan; the re-planning policy is stated in
// mpi_replan.cpp.
//
// Faults: an exception inside a task, on any rank, prints "rank R: ..." with the message on that
// rank's stderr and calls MPI_Abort (exit code 1): every rank ends within seconds, never a hang. An
// exception on the master outside tasks (integration failure, output error) unwinds normally; the
// destructor then sends stop, so the workers leave serve() and the job ends with the master's exit
// code. A worker that stops answering (stopped, hung, lost) is found by the master's waits, each
// bounded by rank_timeout: the master names the rank(s) and calls MPI_Abort (exit code 1), which
// ends every rank. A stopped or lost master is found by the workers' waits when every rank is on
// one node (watch_master(): rank 0's heartbeat in shared memory, scheduler/mpi_heartbeat.cpp).
#pragma once

#include <mpi.h>

#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "scheduler/executor.hpp"
#include "scheduler/plan.hpp"
#include "scheduler/schedule_log.hpp"

namespace raceway::scheduler {

enum class SchedulePolicy {
  adaptive,          ///< re-plan when measured imbalance and predicted gain say so (the default)
  static_plan,       ///< one plan from the first measured costs, never changed (for comparison)
  every_evaluation,  ///< test only: a different plan before every evaluation (bitwise-identity tests)
};
const char* schedule_policy_name(SchedulePolicy p);
/// "rhs", "jacobian", "output" (Phase as int).
const char* phase_name(int phase);

struct MpiExecutorOptions {
  SchedulePolicy policy = SchedulePolicy::adaptive;
  /// Rank 0's share of the tasks relative to one worker's (1: same as a worker; 0: none).
  double master_share = 1.0;
  /// Test only: throw inside the tasks of this rank at this evaluation (1-based; all phases).
  int inject_failure_rank = -1;
  long inject_failure_evaluation = 0;
  /// Test only: rank 0 works (sleeps) this many seconds before it sends evaluation
  /// inject_pause_evaluation: a long stretch of rank 0's own work between two commands.
  long inject_pause_evaluation = 0;
  double inject_pause_seconds = 0;
  /// Every n-th evaluation's balance goes into ScheduleLog::samples.
  int sample_every = 1;
  /// Fraction of each rank's planned work handed out on demand within an evaluation (the plan's
  /// tail, mark_tail; scheduler/mpi_tail.cpp): every rank evaluates its fixed list, then claims
  /// tail tasks until none is left. 0: off (fixed lists only); 1: every task on demand; 0.1 is
  /// what perf/studies/results/parallel_notes.md measured best.
  double tail_share = 0.1;
  /// With every rank on rank 0's node: rank 0's commands reach the workers through a shared-memory
  /// window (the buffer, then a command word; scheduler/mpi_commands.cpp) and the workers' records
  /// come back through it (each worker writes its tasks' slots and then its reply word;
  /// scheduler/mpi_replies.cpp) instead of messages. false: broadcasts and messages, as between
  /// nodes (for tests and comparisons).
  bool shared_exchange = true;
  /// Master: seconds to wait for the workers' answer to one command before ending the job.
  /// Workers (after watch_master()): seconds without a heartbeat of rank 0 while waiting for it
  /// before ending the job.
  double rank_timeout = 60.0;
  /// Master: called with one line per plan event (logging).
  std::function<void(const std::string&)> on_event;
};

class MpiExecutor final : public Executor {
 public:
  /// Collective over comm only through later calls; construction does not communicate.
  MpiExecutor(MPI_Comm comm, MpiExecutorOptions options);
  /// Master: sends stop if not yet sent (also when no attach() happened: the workers are then
  /// released from await_start()). Workers: nothing.
  ~MpiExecutor() override;
  MpiExecutor(const MpiExecutor&) = delete;
  MpiExecutor& operator=(const MpiExecutor&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_master() const { return rank_ == 0; }

  /// Master: announces the task catalogue to the workers (releases await_start()).
  void attach(const TaskCatalogue& catalogue) override;
  /// Master: evaluates the tasks over all ranks. Throws std::invalid_argument when the sizes do
  /// not match the attached catalogue.
  void run(Phase phase, std::span<const double> context, int task_count, int record_size,
           const TaskFunction& task, std::vector<double>& records) override;
  /// Master: releases the workers from serve(). Idempotent.
  void stop() override;
  const ScheduleLog* schedule_log() const override { return &log_; }

  /// Every rank, collective over the communicator, before any other call: with every rank on rank
  /// 0's node, rank 0 starts a heartbeat (a word in shared memory a thread of its own renews every
  /// 50 ms; scheduler/mpi_heartbeat.cpp) and every wait of a worker for rank 0 ends the job (exit
  /// code 1, naming rank 0) when no beat comes for rank_timeout seconds: a stopped or lost rank 0.
  /// A long stretch of rank 0's own work between commands (output, checkpoints) keeps beating.
  /// Between nodes: nothing (the workers wait as long as it takes).
  void watch_master();
  /// Worker: waits for the master's attach() (returns true) or stop (false: the master failed
  /// before it had a model, and has reported why).
  bool await_start();
  /// Master: brings the workers into an output operation: each calls serve()'s output handler with
  /// `payload` (at most context size doubles) and the pieces it evaluated whole in
  /// its last rhs evaluation, with their records. Returns, per piece (TaskCatalogue::parent; per
  /// task without one), the rank holding its record in that evaluation (piece_holders).
  const std::vector<int>& output(std::span<const double> payload);

  /// A worker's part of output(): payload, the pieces (TaskCatalogue::parent, or tasks) of its last
  /// rhs evaluation that it evaluated whole, their records (a cut piece's parts are left out: rank 0
  /// combines them).
  using OutputHandler = std::function<void(std::span<const double> payload, std::span<const int> tasks,
                                           std::span<const double> records)>;
  /// Worker: evaluates tasks for the master until stop. The catalogue must be built from the
  /// same scene as the master's (checked: task count and context size).
  void serve(const TaskCatalogue& catalogue, const OutputHandler& on_output = {});

 private:
  static constexpr double command_start = 1, command_evaluate = 2, command_plan = 3, command_stop = 4,
                          command_output = 5;
  static constexpr int header_size = 6;
  /// int64s between two ranks' words in the node window: a 64-byte cache line each.
  static constexpr std::size_t window_word_stride = 8;
  /// In a worker's reply line: the last evaluation it replied to; the commands it has taken.
  static constexpr std::size_t reply_word = 0, taken_word = 1;

  [[noreturn]] void fail(const std::string& what) const;
  /// Worker, during one wait for rank 0 (after watch_master()): check() fails the job when rank 0's
  /// heartbeat has not changed for rank_timeout seconds since the wait began or the last beat.
  class MasterWatch {
   public:
    explicit MasterWatch(const MpiExecutor& executor);
    void check();

   private:
    const MpiExecutor& executor_;
    std::int64_t beat_;
    double since_;
  };
  /// Worker: waits for `requests` (to or from rank 0, or passing on to it), watched (MasterWatch).
  void await_master(std::vector<MPI_Request>& requests) const;
  void close_heartbeat();
  /// steady_clock seconds.
  static double now_seconds();
  /// A task of this rank's: evaluates `task` into record (whole). Everything it throws ends the job
  /// (the other ranks would wait for its record for ever).
  void run_task(int phase, std::span<const double> context, const TaskFunction& function, int task,
                  std::span<double> record) const;
  /// Master: waits for the requests, at most rank_timeout seconds; ranks[i] is the rank that
  /// completes requests[i] (-1: a broadcast). Past the timeout, fails naming the silent ranks.
  void wait_bounded(std::vector<MPI_Request>& requests, const std::vector<int>& ranks, const std::string& what);
  /// A command from the master to every rank (MPI_Ibcast); the master's send is bounded.
  void broadcast(double* buffer, int count, const std::string& what);
  void broadcast(void* buffer, int count, MPI_Datatype type, const std::string& what);
  /// A plan's owner per task, after its command (both sides: the master's is sent, a worker's filled).
  void broadcast_owners(std::vector<int>& owner);
  /// Doubles of the records of `tasks` that cross ranks in `phase` (TaskCatalogue::used_size).
  std::size_t packed_size(int phase, const std::vector<int>& tasks) const;
  /// The replies' binomial tree rooted at rank 0 (mpi_executor.cpp): rank r's children, the end of
  /// the ranks r.. whose replies r passes on, and the doubles of their combined reply in `phase`.
  std::vector<int> tree_children(int r) const;
  int subtree_end(int r) const;
  std::size_t subtree_reply_size(int phase, int r) const;
  /// Master: a worker's record of `task` (its used doubles at `values`, zeros after them) and its
  /// seconds into place, counted as rank `w`'s work.
  void place_record(int phase, int task, int w, const double* values, double task_seconds, std::vector<double>& records,
                    std::vector<double>& busy);
  /// Master: the replies of ranks r .. subtree_end(r) - 1 from `packed` into records, seconds, busy.
  void unpack_replies(int phase, int r, const double* packed, std::vector<double>& records, std::vector<double>& busy);
  /// Worker, replies by message: posts the receives of its subtree's replies into `reply` (sized
  /// here) before it computes, and after, packs its own tasks' `full` records and `seconds` in front
  /// of them and sends the whole to its parent.
  std::vector<MPI_Request> receive_subtree(int phase, std::vector<double>& reply);
  void send_reply(int phase, const double* full, const double* seconds, std::vector<double>& reply,
                  std::vector<MPI_Request>& from);
  /// Worker, shared exchange: its tasks' records and seconds into their slots, then its reply word.
  void post_shared_reply(int phase, const double* full, const double* seconds);
  /// Master, shared exchange: waits (bounded) for every worker's reply word, then copies the
  /// workers' records into place.
  void collect_shared_replies(int phase, std::vector<double>& records, std::vector<double>& busy);
  /// Master: message_ to every worker, through the node window (shared exchange) or broadcast
  /// (bounded; `what` names it in the failure). Worker: the next command into message_.
  /// (mpi_commands.cpp)
  void send_command(const char* what);
  void receive_command();
  /// Master: waits until every worker's `word` (reply_word, taken_word) in its reply line is at
  /// least `value`; past rank_timeout fails: "rank R did not <what> [the <phase>] evaluation N".
  void await_worker_words(std::size_t word, std::int64_t value, const char* what, int phase);
  void set_owner(int phase, const std::vector<int>& owner);
  /// This rank's tasks of the phase's plan: records and seconds in task order (at task t) or packed
  /// in the order of the rank's task list.
  void evaluate_own(int phase, std::span<const double> context, int record_size, const TaskFunction& task,
                    double* records, double* seconds, bool in_task_order);
  /// Both sides, right after the start command: the node's shared-memory window (per rank a tail
  /// claim word and a reply line, the command, per task a slot), when the tail or the shared
  /// exchange wants it and every rank is on rank 0's node. Collective. Sets tail_window_
  /// (MPI_WIN_NULL: none; then no tail, commands and replies by message), tail_on_, and with the
  /// shared exchange reply_done_, command_word_ and command_buffer_. Needs message_size_.
  void open_node_window(bool tail, bool shared_exchange, int record_size);
  void close_tail_window();
  /// Master: marks the plan's tail in `owner` (mark_tail), each task as a negative code that says
  /// its rank in the plan and its position in that rank's tail (largest first).
  void encode_tail(std::vector<int>& owner, const std::vector<double>& cost) const;
  /// Both sides: tail_ and tail_start_ from the codes (set_owner).
  void decode_tail(int phase, const std::vector<int>& owner);
  /// Master, before the command: every rank's tail whole again.
  void reset_tail_claims(int phase);
  /// The next tail position this rank evaluates (its own part's front, else the back of the part
  /// with the most left); -1 when the tail is gone.
  std::int64_t claim_tail_position(int phase);
  /// Claims and evaluates tail tasks until none is left: rank 0's into `records` (at their task)
  /// and `seconds`, a worker's into the window's slots. Returns the seconds this rank spent on them.
  double evaluate_tail(int phase, std::span<const double> context, const TaskFunction& function, double* records,
                       double* seconds);
  /// Master, after every reply: the workers' tail records from the window into place.
  void collect_tail(int phase, std::vector<double>& records, std::vector<double>& busy);
  /// Cost model bookkeeping after an evaluation: smoothed costs, imbalance, the log.
  void account(int phase, std::span<const double> context, const std::vector<double>& busy, double wall);
  void maybe_replan(int phase);
  /// The current plan's imbalance under the cost model (max over mean of the ranks' loads; with a
  /// tail, of their fixed lists, the tail filling the gaps up to the mean). Cheap: the costs are
  /// read in place, no tail is marked.
  double current_imbalance(int phase) const;
  /// Cost per task the plans use: the smoothed measured cost for rhs; for other phases the rhs
  /// cost times the measured per-task ratio (once measured), so they follow the moving work.
  std::vector<double> model_cost(int phase) const;
  void adopt_plan(int phase, Plan plan, PlanReason reason, double started);

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  MpiExecutorOptions options_;
  bool attached_ = false, stopped_ = false;
  TaskCatalogue catalogue_;                 ///< metadata only on the master (no functions)
  std::size_t message_size_ = header_size;  ///< doubles per command after start
  std::vector<double> message_;
  std::vector<double> capacity_;
  long evaluation_ = 0;  ///< evaluate commands so far (all phases)
  // Per phase:
  std::vector<int> owner_[phase_count];
  std::vector<std::vector<int>> tasks_of_[phase_count];  ///< per rank, ascending (its fixed list)
  std::vector<int> tail_[phase_count];  ///< the plan's tail: rank 0's, rank 1's, ... (each largest first)
  std::vector<int> tail_start_[phase_count];  ///< rank r's part of tail_ starts at [r], ends at [r + 1]
  // The node window (mpi_tail.cpp): on rank 0's memory, mapped by every rank.
  MPI_Comm node_comm_ = MPI_COMM_NULL;
  MPI_Win tail_window_ = MPI_WIN_NULL;
  bool tail_on_ = false;                  ///< the plans have a tail
  std::int64_t* tail_counter_ = nullptr;  ///< per rank a claim word (front, back), a cache line apart
  std::int64_t* reply_done_ = nullptr;    ///< per rank its reply line (reply_word, taken_word; shared exchange)
  std::int64_t* command_word_ = nullptr;  ///< the number of commands rank 0 has written (shared exchange)
  double* command_buffer_ = nullptr;      ///< the last command (message_size_ doubles)
  std::int64_t commands_ = 0;             ///< through the window: written (master), taken (worker)
  std::int64_t commands_taken_by_all_ = 0;  ///< master: every worker has taken this many
  // Rank 0's heartbeat (watch_master): a word on rank 0's memory, renewed by its thread.
  MPI_Comm heartbeat_comm_ = MPI_COMM_NULL;
  MPI_Win heartbeat_window_ = MPI_WIN_NULL;
  std::int64_t* heartbeat_word_ = nullptr;
  std::jthread heartbeat_thread_;
  double* tail_slots_ = nullptr;        ///< per task: rank, seconds, record
  std::size_t tail_slot_size_ = 0;
  std::vector<double> cost_[phase_count];                ///< smoothed task seconds
  std::vector<double> ratio_[phase_count];               ///< per task: cost / rhs cost (not rhs)
  int version_[phase_count] = {};
  long last_plan_run_[phase_count] = {}, last_check_run_[phase_count] = {};  ///< evaluation_ then
  double smoothed_imbalance_[phase_count] = {};
  double replan_seconds_[phase_count] = {};
  std::vector<std::vector<double>> receive_;
  std::vector<int> holder_;              ///< master: output()'s answer
  std::vector<int> last_rhs_tasks_;     ///< worker: the pieces it evaluated whole in the last rhs evaluation
  std::vector<double> last_rhs_records_;
  ScheduleLog log_;
};

/// Per piece (`parent`; per task when it is empty), the rank that holds the piece's final record
/// after an evaluation with `owner` per task: the owner of its task when it is one task, rank 0
/// (which combines the parts in a fixed order) when it is cut into several.
std::vector<int> piece_holders(std::span<const int> owner, std::span<const int> parent);

}  // namespace raceway::scheduler
