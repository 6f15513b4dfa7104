// The MPI master/worker executor (parallelism across the contact tasks, after seed 000 section 2.6;
// docs/references.md).
//
// Rank 0 (the master) owns CVODE and calls run(); it also evaluates its share of the tasks. The
// other ranks (workers) loop in serve() on the master's commands (scheduler/command_header.hpp):
//   evaluate (phase, context)  -> evaluate the tasks the phase's plan gives this rank, give back
//                                 their records and measured seconds (scheduler/replies.hpp);
//   plan (phase), then owner per task in a second broadcast -> adopt a new plan for that phase;
//   output (payload)           -> call serve()'s output handler with the payload and the records of
//                                 this rank's last rhs evaluation (the parallel output's samples
//                                 and collective writes, solver/driver/parallel_output.hpp);
//   stop                       -> leave serve().
// The executor orchestrates objects that each do one thing:
//   CommandChannel (scheduler/command_channel.hpp)  the commands: broadcast, or through the node's
//                                                   shared-memory window with every rank on one node;
//   ReplyExchange (scheduler/replies.hpp)           the replies: up a binomial tree, or the window;
//   SharedTail (scheduler/shared_tail.hpp)          the plan's tail (MpiExecutorOptions::tail_share),
//                                                   claimed on demand within an evaluation;
//   CostModel (scheduler/cost_model.hpp)            smoothed task costs and imbalance (pure);
//   ReplanPolicy (scheduler/replan_policy.hpp)      when to make which plan (pure; plans:
//                                                   scheduler/plan.hpp);
//   RankWatch (scheduler/rank_watch.hpp)            bounded waits, rank 0's heartbeat, failures.
// The master places the records in task order; the equations sum them in that order, so results
// are bitwise identical for any rank count and any plan.
//
// Faults: an exception inside a task, on any rank, prints "rank R: ..." with the message on that
// rank's stderr and calls MPI_Abort (exit code 1): every rank ends within seconds, never a hang. An
// exception on the master outside tasks (integration failure, output error) unwinds normally; the
// destructor then sends stop, so the workers leave serve() and the job ends with the master's exit
// code. A worker that stops answering (stopped, hung, lost) is found by the master's waits, each
// bounded by rank_timeout: the master names the rank(s) and calls MPI_Abort (exit code 1), which
// ends every rank. A stopped or lost master is found by the workers' waits when every rank is on
// one node (watch_master(): rank 0's heartbeat in shared memory).
#pragma once

#include <mpi.h>

#include <functional>
#include <string>
#include <vector>

#include "scheduler/command_channel.hpp"
#include "scheduler/cost_model.hpp"
#include "scheduler/executor.hpp"
#include "scheduler/node_window.hpp"
#include "scheduler/plan.hpp"
#include "scheduler/rank_watch.hpp"
#include "scheduler/replan_policy.hpp"
#include "scheduler/replies.hpp"
#include "scheduler/schedule_log.hpp"
#include "scheduler/shared_tail.hpp"

namespace raceway::scheduler {

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
  /// tail, mark_tail; scheduler/tail_claims.hpp): every rank evaluates its fixed list, then claims
  /// tail tasks until none is left. 0: off (fixed lists only); 1: every task on demand; 0.1 is
  /// what perf/studies/results/parallel_notes.md measured best.
  double tail_share = 0.1;
  /// With every rank on rank 0's node: commands and replies through a shared-memory window
  /// (scheduler/command_channel.hpp, scheduler/replies.hpp) instead of messages. false: broadcasts
  /// and messages, as between nodes (for tests and comparisons).
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

  int rank() const { return watch_.rank(); }
  int size() const { return watch_.size(); }
  bool is_master() const { return rank() == 0; }

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
  /// 0's node, rank 0 starts a heartbeat and every wait of a worker for rank 0 ends the job (exit
  /// code 1, naming rank 0) when no beat comes for rank_timeout seconds (RankWatch::watch_master).
  void watch_master() { watch_.watch_master(); }
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
  /// Both, right after the start command: the command buffer's size, the node window (when the
  /// tail or the shared exchange wants it and every rank is on rank 0's node), the tail, the replies.
  void open_exchange(bool tail, bool shared_exchange, int max_record_size);
  /// Both: the phase's plan `owner` (tail tasks coded negative) as per-rank lists and the tail.
  void set_owner(int phase, const std::vector<int>& owner);
  /// Master: what the re-plan policy asks for before the next evaluation of `phase`.
  void maybe_replan(int phase);
  void adopt_plan(int phase, Plan plan, PlanReason reason, double started);
  /// A task of this rank's into record (whole). Everything it throws ends the job (the other ranks
  /// would wait for its record for ever).
  void run_task(int phase, std::span<const double> context, const TaskFunction& function, int task,
                std::span<double> record) const;
  /// This rank's fixed list of the phase's plan: the i-th task t's record (record_size doubles) and
  /// seconds where place(i, t) says ({record, seconds}: rank 0's in task order, a worker's in the
  /// order of its list or in a scratch slot), then done(i, t) (a worker streams the scratch slot
  /// into the node window).
  template <class Place, class Done>
  void evaluate_own(int phase, std::span<const double> context, std::size_t record_size, const TaskFunction& task,
                    Place place, Done done) const;
  /// Worker: its part of an evaluation (fixed list, tail, reply); the records it evaluated into `full`.
  void serve_evaluation(int phase, std::size_t record_size, const TaskFunction& function, std::vector<double>& full,
                        std::vector<double>& seconds);
  /// Master, after an evaluation: the cost model and the schedule log.
  void account(int phase, std::span<const double> context, const std::vector<double>& busy, double wall);

  MPI_Comm comm_;
  MpiExecutorOptions options_;
  RankWatch watch_;
  TaskCatalogue catalogue_;  ///< metadata only (no functions); a worker's from the start and serve()
  CommandChannel channel_;
  NodeWindow window_;
  SharedTail tail_;
  ReplyExchange replies_;
  CostModel costs_;
  ReplanPolicy policy_;
  bool attached_ = false, stopped_ = false;
  long evaluation_ = 0;  ///< evaluate commands so far (all phases)
  std::vector<int> owner_[phase_count];  ///< master: the whole plan per task (its tail included)
  RankTaskLists tasks_of_[phase_count];  ///< per rank its fixed list, ascending
  int version_[phase_count] = {};
  std::vector<int> holder_;             ///< master: output()'s answer
  std::vector<int> last_rhs_tasks_;     ///< worker: the pieces it evaluated whole in the last rhs evaluation
  std::vector<double> last_rhs_records_;
  ScheduleLog log_;
};

}  // namespace raceway::scheduler
