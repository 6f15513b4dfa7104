#include "scheduler/mpi_executor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "scheduler/schedule_logging.hpp"
#include "scheduler/task_clock.hpp"

namespace raceway::scheduler {

namespace {

/// Rank 0 takes master_share of a worker's work; alone it must take everything.
std::vector<double> rank_capacities(MPI_Comm comm, double master_share) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<double> capacity(static_cast<std::size_t>(size), 1.0);
  if (size > 1) capacity[0] = master_share;
  return capacity;
}

}  // namespace

MpiExecutor::MpiExecutor(MPI_Comm comm, MpiExecutorOptions options)
    : comm_(comm),
      options_(std::move(options)),
      watch_(comm, options_.rank_timeout),
      channel_(comm, watch_),
      replies_(comm, watch_, channel_, catalogue_),
      policy_(options_.policy, rank_capacities(comm, options_.master_share), 0.0) {
  if (!(options_.master_share >= 0 && std::isfinite(options_.master_share)))
    throw std::invalid_argument("master share must be finite and >= 0");
  if (!(options_.rank_timeout > 0 && std::isfinite(options_.rank_timeout)))
    throw std::invalid_argument("rank timeout must be finite and > 0");
  log_.ranks = size();
  log_.policy = schedule_policy_name(options_.policy);
  log_.master_share = options_.master_share;
  log_.sample_every = std::max(1, options_.sample_every);
  log_.rank_task_seconds.assign(static_cast<std::size_t>(size()), 0.0);
}

MpiExecutor::~MpiExecutor() {
  if (is_master() && !stopped_) stop();
  window_.close();  // collective: every rank gets here after stop
  watch_.close();   // collective too
}

void MpiExecutor::open_exchange(bool tail, bool shared_exchange, int max_record_size) {
  if (tail || shared_exchange)
    window_.open(comm_, catalogue_.task_count, command_header_size + static_cast<std::size_t>(catalogue_.context_size),
                 max_record_size, shared_exchange);
  channel_.open(catalogue_.context_size, shared_exchange ? &window_ : nullptr);
  replies_.open(&window_, shared_exchange);
  if (tail) tail_.open(window_, rank(), size(), options_.tail_share);
  policy_.set_tail_share(tail_.share());
}

void MpiExecutor::attach(const TaskCatalogue& catalogue) {
  if (!is_master()) throw std::logic_error("MpiExecutor::attach is for rank 0");
  if (attached_) throw std::logic_error("MpiExecutor::attach called twice");
  catalogue_ = catalogue;
  catalogue_.function = {};  // the master runs the function run() is given; keep no references
  CommandHeader start{.kind = CommandKind::start, .task_count = catalogue.task_count};
  start.record_size = *std::max_element(catalogue.record_size.begin(), catalogue.record_size.end());
  start.context_size = catalogue.context_size;
  start.tail = size() > 1 && options_.tail_share > 0;
  start.shared_exchange = size() > 1 && options_.shared_exchange;
  channel_.send_first(start, "the start of the run");
  open_exchange(start.tail, start.shared_exchange, start.record_size);
  if (start.tail && !tail_.is_on() && options_.on_event)
    options_.on_event("scheduler: no tail shared on demand (--tail-share): it needs every rank on rank 0's node");
  attached_ = true;
  log_catalogue(log_, catalogue);
  for (int p = 0; p < phase_count; ++p) {  // start plans: uniform costs (nothing measured yet)
    if (catalogue.record_size[static_cast<std::size_t>(p)] <= 0) continue;
    const double started = RankWatch::now_seconds();
    const std::vector<double> uniform(static_cast<std::size_t>(catalogue.task_count), 1.0);
    adopt_plan(p, make_plan(uniform, catalogue_, policy_.capacity()), PlanReason::initial, started);
  }
}

void MpiExecutor::stop() {
  if (!is_master() || stopped_) return;
  stopped_ = true;
  const CommandHeader stop{.kind = CommandKind::stop};
  if (!attached_)  // the workers wait in await_start() for a header alone
    channel_.send_first(stop, "the end of the run");
  else
    channel_.send(stop, {}, "the end of the run");
}

void MpiExecutor::set_owner(int phase, const std::vector<int>& owner) {
  auto& lists = tasks_of_[phase];
  lists.assign(static_cast<std::size_t>(size()), {});
  for (std::size_t t = 0; t < owner.size(); ++t)
    if (owner[t] >= 0) lists[static_cast<std::size_t>(owner[t])].push_back(static_cast<int>(t));
  tail_.adopt(phase, owner);  // the tail tasks (negative owners)
}

void MpiExecutor::maybe_replan(int phase) {
  const double started = RankWatch::now_seconds();
  if (auto replan = policy_.decide(phase, evaluation_, version_[phase], costs_, tasks_of_[phase], catalogue_))
    adopt_plan(phase, std::move(replan->plan), replan->reason, started);
}

void MpiExecutor::adopt_plan(int phase, Plan plan, PlanReason reason, double started) {
  const std::vector<double> model = costs_.model(phase);
  const auto capacity = policy_.capacity();
  const double before = owner_[phase].empty() || model.empty() ? 0.0 : predicted_imbalance(owner_[phase], model, capacity);
  if (reason == PlanReason::forced && size() > 1) rotate_plan(plan, version_[phase], capacity, catalogue_, model);
  const bool first = owner_[phase].empty();
  if (!first) ++version_[phase];
  // The tail is claimed on demand; owner_ keeps the whole plan (its balance is what re-planning judges).
  std::vector<int> owner = plan.owner;
  if (tail_.is_on()) tail_.mark(owner, model.empty() ? std::vector<double>(owner.size(), 1.0) : model);
  set_owner(phase, owner);
  owner_[phase] = plan.owner;
  if (size() > 1) {
    channel_.send({.kind = CommandKind::plan, .phase = phase, .task_count = catalogue_.task_count, .number = version_[phase]},
                  {}, "a new plan");
    // The owners follow in a broadcast of their own: the command buffer holds a context, not a
    // task list, so every evaluation's command is no longer than it needs to be.
    channel_.broadcast_owners(owner);
  }
  PlanEvent e{.evaluation = evaluation_ + 1, .phase = phase, .version = version_[phase], .reason = reason,
              .method = plan.method, .split_groups = plan.split_groups, .split_parents = plan.split_parents,
              .measured_imbalance = costs_.smoothed_imbalance(phase), .predicted_before = before,
              .predicted_after = plan.predicted_imbalance, .plan_seconds = RankWatch::now_seconds() - started};
  for (const std::string& line : log_plan(log_, e))
    if (options_.on_event && size() > 1) options_.on_event(line);
  costs_.measure_plan_seconds(phase, e.plan_seconds);
  policy_.adopted(phase, evaluation_);
  if (!first) costs_.restart_imbalance(phase, plan.predicted_imbalance);  // judge the new plan on its own
}

void MpiExecutor::run_task(int phase, std::span<const double> context, const TaskFunction& function, int task,
                           std::span<double> record) const {
  try {
    function(context, task, record);
  } catch (const std::exception& e) {
    watch_.fail(std::string("in a ") + phase_name(phase) + " task at evaluation " + std::to_string(evaluation_) + ": " + e.what());
  } catch (...) {
    watch_.fail(std::string("unknown exception in a ") + phase_name(phase) + " task at evaluation " + std::to_string(evaluation_));
  }
}

template <class Place, class Done>
void MpiExecutor::evaluate_own(int phase, std::span<const double> context, std::size_t record_size,
                               const TaskFunction& task, Place place, Done done) const {
  if (rank() == options_.inject_failure_rank && evaluation_ == options_.inject_failure_evaluation)
    watch_.fail(std::string("in a ") + phase_name(phase) + " task at evaluation " + std::to_string(evaluation_) +
                ": injected failure at evaluation " + std::to_string(evaluation_) + " (test-only option --inject-failure)");
  const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank())];
  TaskClock clock;  // one reading per task: a task's seconds run to the next's start
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const auto [record, seconds] = place(i, mine[i]);
    run_task(phase, context, task, mine[i], std::span<double>(record, record_size));
    *seconds = clock.lap();
    done(i, mine[i]);
  }
}

void MpiExecutor::run(Phase phase_enum, std::span<const double> context, int task_count, int record_size,
                      const TaskFunction& task, std::vector<double>& records) {
  const int phase = static_cast<int>(phase_enum);
  if (!is_master()) throw std::logic_error("MpiExecutor::run is for rank 0; workers serve()");
  if (!attached_ || stopped_) throw std::logic_error("MpiExecutor::run before attach() or after stop()");
  if (task_count != catalogue_.task_count || record_size != catalogue_.record_size[static_cast<std::size_t>(phase)] ||
      static_cast<int>(context.size()) != catalogue_.context_size)
    throw std::invalid_argument("MpiExecutor::run: task count, record size or context size differ from the catalogue");
  maybe_replan(phase);
  ++evaluation_;
  if (evaluation_ == options_.inject_pause_evaluation)
    std::this_thread::sleep_for(std::chrono::duration<double>(options_.inject_pause_seconds));
  const double wall_start = RankWatch::now_seconds();
  const auto rs = static_cast<std::size_t>(record_size);
  if (tail_.has_tail(phase)) tail_.reset(phase);  // before the command releases the workers
  // The command and the receives are posted before the master's own share, so worker records land
  // while it computes; all are waited for together (bounded).
  std::vector<MPI_Request> requests;
  std::vector<int> request_rank;
  if (size() > 1) {
    channel_.send({.kind = CommandKind::evaluate, .phase = phase, .task_count = task_count, .record_size = record_size,
                   .number = evaluation_},
                  context, "an evaluation", &requests, &request_rank);
    replies_.post_receives(phase, tasks_of_[phase], requests, request_rank);
  }
  records.resize(static_cast<std::size_t>(task_count) * rs);
  auto& seconds = seconds_[phase];
  seconds.resize(static_cast<std::size_t>(task_count));
  // The master's own tasks write their records in place (whole: zero beyond what they use, as a
  // worker's placed ones are).
  evaluate_own(phase, context, rs, task, [&](std::size_t, int t) {
    return std::pair{records.data() + static_cast<std::size_t>(t) * rs, seconds.data() + t};
  }, [](std::size_t, int) {});
  std::vector<double> busy(static_cast<std::size_t>(size()), 0.0);
  for (const int t : tasks_of_[phase][0]) busy[0] += seconds[static_cast<std::size_t>(t)];
  const auto run_one = [&](int t, std::span<double> record) { run_task(phase, context, task, t, record); };
  if (tail_.has_tail(phase) && policy_.capacity()[0] > 0)  // not with --master-share 0
    busy[0] += tail_.evaluate(phase, rs, run_one, records.data(), seconds.data(), [&] {
      return replies_.through_window() && replies_.place_announced(phase, tasks_of_[phase], evaluation_, records, seconds, busy);
    });
  if (size() > 1) replies_.collect(phase, tasks_of_[phase], requests, request_rank, evaluation_, records, seconds, busy);
  if (tail_.has_tail(phase)) tail_.collect(phase, rs, records, seconds, busy);
  account(phase, context, busy, RankWatch::now_seconds() - wall_start);
}

void MpiExecutor::account(int phase, std::span<const double> context, const std::vector<double>& busy, double wall) {
  const EvaluationBalance balance = evaluation_balance(busy, policy_.capacity());
  costs_.measure(phase, seconds_[phase], balance.imbalance);
  totals_[phase] += balance.total;
  ++runs_[phase];
  log_evaluation(log_, evaluation_, phase, context.empty() ? 0.0 : context[0], balance, busy, wall, version_[phase],
                 costs_.measured(phase));
}

const std::vector<int>& MpiExecutor::output(std::span<const double> payload) {
  if (!is_master() || !attached_ || stopped_) throw std::logic_error("MpiExecutor::output is for rank 0, between attach() and stop()");
  if (payload.size() > channel_.payload_size()) throw std::invalid_argument("MpiExecutor::output: payload too long");
  if (size() > 1) channel_.send({.kind = CommandKind::output}, payload, "an output command");
  // A tail task's record is on rank 0 whoever evaluated it (SharedTail::collect).
  std::vector<int> owner = owner_[static_cast<int>(Phase::rhs)];
  for (const int t : tail_.parts(static_cast<int>(Phase::rhs)).tasks) owner[static_cast<std::size_t>(t)] = 0;
  holder_ = piece_holders(owner, catalogue_.parent);
  return holder_;
}

bool MpiExecutor::await_start() {
  if (is_master()) throw std::logic_error("MpiExecutor::await_start is for workers");
  const CommandHeader start = channel_.receive_first();
  if (start.kind == CommandKind::stop) return false;
  if (start.kind != CommandKind::start) watch_.fail("protocol error: expected start or stop from rank 0");
  catalogue_.task_count = start.task_count;
  catalogue_.context_size = start.context_size;
  open_exchange(start.tail, start.shared_exchange, start.record_size);
  attached_ = true;
  return true;
}

void MpiExecutor::serve(const TaskCatalogue& catalogue, const OutputHandler& on_output) {
  if (is_master() || !attached_) throw std::logic_error("MpiExecutor::serve is for workers, after await_start()");
  if (catalogue.task_count != catalogue_.task_count || catalogue.context_size != catalogue_.context_size)
    watch_.fail("this rank's model has " + std::to_string(catalogue.task_count) + " tasks and context " +
                std::to_string(catalogue.context_size) + ", rank 0's has " + std::to_string(catalogue_.task_count) +
                " and " + std::to_string(catalogue_.context_size) + " (different scene or build?)");
  catalogue_.record_size = catalogue.record_size;
  catalogue_.used_size = catalogue.used_size;
  const std::vector<int> piece_tasks = piece_task_counts(catalogue.parent);
  std::vector<double> full, seconds;
  for (;;) {
    const CommandHeader command = channel_.receive();
    const int phase = command.phase;
    if (command.kind == CommandKind::stop) return;
    if (command.kind == CommandKind::output) {
      if (!on_output) watch_.fail("protocol error: an output command, but this rank has no output handler");
      on_output(channel_.payload(), last_rhs_tasks_, last_rhs_records_);
      continue;
    }
    if (command.kind == CommandKind::plan) {
      std::vector<int> owner(static_cast<std::size_t>(catalogue_.task_count));
      channel_.broadcast_owners(owner);
      version_[phase] = static_cast<int>(command.number);
      set_owner(phase, owner);
      continue;
    }
    if (command.kind != CommandKind::evaluate)
      watch_.fail(std::string("protocol error: a ") + command_kind_name(command.kind) + " command from rank 0 while serving");
    const auto& function = catalogue.function[static_cast<std::size_t>(phase)];
    if (!function || command.record_size != catalogue.record_size[static_cast<std::size_t>(phase)] ||
        command.task_count != catalogue.task_count)
      watch_.fail(std::string("rank 0 asks for ") + phase_name(phase) + " tasks this rank's catalogue does not have");
    evaluation_ = command.number;
    const auto rs = static_cast<std::size_t>(command.record_size);
    serve_evaluation(phase, rs, function, full, seconds);
    if (on_output && phase == static_cast<int>(Phase::rhs)) {  // what an output command would sample
      const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank())];
      if (replies_.through_window())  // the records are in their slots: after the reply, off rank 0's way
        for (std::size_t i = 0; i < mine.size(); ++i) std::copy_n(replies_.slot_of(phase, mine[i]) + 2, rs, full.data() + i * rs);
      keep_whole_pieces(catalogue.parent, piece_tasks, mine, full, rs, last_rhs_tasks_, last_rhs_records_);
    }
  }
}

void MpiExecutor::serve_evaluation(int phase, std::size_t rs, const TaskFunction& function, std::vector<double>& full,
                                   std::vector<double>& seconds) {
  const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank())];
  replies_.expect_subtree(phase, tasks_of_[phase]);  // received while it computes
  full.resize(mine.size() * rs);
  seconds.resize(mine.size());
  const auto context = channel_.payload();
  if (replies_.through_window()) {
    const std::size_t stride = NodeWindow::slot_stride(rs);
    std::vector<double> scratch(stride, 0.0);
    scratch[0] = rank();
    evaluate_own(phase, context, rs, function, [&](std::size_t, int) { return std::pair{scratch.data() + 2, scratch.data() + 1}; },
                 [&](std::size_t, int t) {  // the lines that hold what crosses ranks (catalogue's used size)
                   const auto used = static_cast<std::size_t>(catalogue_.used(phase, t));
                   NodeWindow::stream_slot(replies_.slot_of(phase, t), scratch.data(), NodeWindow::whole_lines(2 + used));
                 });
    replies_.fixed_done(evaluation_);  // rank 0 may place them between its tail tasks
  } else {
    evaluate_own(phase, context, rs, function, [&](std::size_t i, int) {
      return std::pair{full.data() + i * rs, seconds.data() + i};
    }, [](std::size_t, int) {});
  }
  const auto run_one = [&](int t, std::span<double> record) { run_task(phase, context, function, t, record); };
  if (tail_.has_tail(phase)) tail_.evaluate(phase, rs, run_one, nullptr, nullptr, [] { return false; });
  replies_.send(phase, tasks_of_[phase], full.data(), seconds.data(), evaluation_);
}

}  // namespace raceway::scheduler
