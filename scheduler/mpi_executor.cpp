#include "scheduler/mpi_executor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <thread>

namespace raceway::scheduler {

namespace {

// ---- Cost model (the re-planning policy that uses it: mpi_replan.cpp) -----------------------------
// Cost model: per phase and task, an exponential moving average of measured task seconds, weight
// cost_smoothing on the newest evaluation (the first measurement is taken as it is). 0.2 follows a
// load that moves over ~5 evaluations (a ball entering the loaded zone takes hundreds of
// right-hand sides) while damping the timer noise of single microsecond-scale tasks.
constexpr double cost_smoothing = 0.2;
// A measurement enters the average clipped to cost_outlier_factor times the current estimate: a
// task preempted for milliseconds (another process on the core) would otherwise dominate the
// model of a microsecond task for dozens of evaluations. A real rise still gets through at up to
// (1 + 0.2 * (3 - 1)) = 1.4x per evaluation.
constexpr double cost_outlier_factor = 3.0;
// Measured imbalance per evaluation (max over mean of the ranks' share-weighted task seconds),
// smoothed with weight imbalance_smoothing: a single slow evaluation (an interrupt, another
// process on the core) must not trigger a re-plan.
constexpr double imbalance_smoothing = 0.1;

using clock_type = std::chrono::steady_clock;

const char* method_name(PlanMethod m) {
  switch (m) {
    case PlanMethod::single_rank: return "single rank";
    case PlanMethod::greedy_lpt: return "greedy LPT";
    case PlanMethod::metis_kway: return "METIS k-way";
    case PlanMethod::rotated: return "rotated (forced)";
  }
  return "?";
}
const char* reason_name(PlanReason r) {
  switch (r) {
    case PlanReason::initial: return "initial (uniform costs)";
    case PlanReason::measured_costs: return "first measured costs";
    case PlanReason::imbalance: return "imbalance";
    case PlanReason::forced: return "forced";
  }
  return "?";
}
std::string fmt_plan_line(const PlanEvent& e) {
  char line[320];
  std::snprintf(line, sizeof line,
                "scheduler: %s plan v%d before evaluation %ld (%s, %s): predicted imbalance %.3f -> %.3f, "
                "measured %.3f, %d rolling element(s) and %d segment(s) split, %.3g ms",
                phase_name(e.phase), e.version, e.evaluation, reason_name(e.reason), method_name(e.method),
                e.predicted_before, e.predicted_after, e.measured_imbalance, e.split_groups, e.split_parents,
                1e3 * e.plan_seconds);
  return line;
}

}  // namespace

double MpiExecutor::now_seconds() { return std::chrono::duration<double>(clock_type::now().time_since_epoch()).count(); }

const char* phase_name(int p) { return p == 0 ? "rhs" : p == 1 ? "jacobian" : "output"; }

const char* schedule_policy_name(SchedulePolicy p) {
  switch (p) {
    case SchedulePolicy::adaptive: return "adaptive";
    case SchedulePolicy::static_plan: return "static";
    case SchedulePolicy::every_evaluation: return "every-evaluation";
  }
  return "?";
}

MpiExecutor::MpiExecutor(MPI_Comm comm, MpiExecutorOptions options) : comm_(comm), options_(std::move(options)) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
  if (!(options_.master_share >= 0 && std::isfinite(options_.master_share)))
    throw std::invalid_argument("master share must be finite and >= 0");
  if (!(options_.rank_timeout > 0 && std::isfinite(options_.rank_timeout)))
    throw std::invalid_argument("rank timeout must be finite and > 0");
  capacity_.assign(static_cast<std::size_t>(size_), 1.0);
  // With workers, rank 0 takes master_share of a worker's work; alone it must take everything.
  if (size_ > 1) capacity_[0] = options_.master_share;
  log_.ranks = size_;
  log_.policy = schedule_policy_name(options_.policy);
  log_.master_share = options_.master_share;
  log_.sample_every = std::max(1, options_.sample_every);
  log_.rank_task_seconds.assign(static_cast<std::size_t>(size_), 0.0);
}

MpiExecutor::~MpiExecutor() {
  if (is_master() && !stopped_) stop();
  close_tail_window();  // collective: every rank gets here after stop
  close_heartbeat();    // collective too
}

void MpiExecutor::fail(const std::string& what) const {
  std::fprintf(stderr, "[raceway] rank %d of %d: error: %s\n", rank_, size_, what.c_str());
  std::fflush(stderr);
  MPI_Abort(comm_, 1);
  std::abort();  // MPI_Abort does not return; this keeps [[noreturn]] honest
}

void MpiExecutor::wait_bounded(std::vector<MPI_Request>& requests, const std::vector<int>& ranks,
                               const std::string& what) {
  // MPI_Waitall cannot be bounded; a worker stopped by a signal would hold the master (at 100 %
  // CPU) for ever. Polling with MPI_Testsome costs what MPI_Waitall's own progress loop does.
  const auto n = static_cast<int>(requests.size());
  std::vector<int> done(requests.size()), indices(requests.size());
  const auto deadline = clock_type::now() + std::chrono::duration<double>(options_.rank_timeout);
  int completed = 0;
  while (completed < n) {
    int count = 0;
    MPI_Testsome(n, requests.data(), &count, indices.data(), MPI_STATUSES_IGNORE);
    if (count == MPI_UNDEFINED) break;  // every request is inactive
    for (int i = 0; i < count; ++i) done[static_cast<std::size_t>(indices[static_cast<std::size_t>(i)])] = 1;
    completed += count;
    if (completed < n && clock_type::now() > deadline) {
      std::string silent;
      for (std::size_t i = 0; i < requests.size(); ++i)
        if (!done[i] && ranks[i] >= 0) {
          silent += (silent.empty() ? "" : ", ") + std::to_string(ranks[i]);
          if (const int end = subtree_end(ranks[i]); end > ranks[i] + 1)  // it passes on the replies of ranks below it
            silent += " (or one of ranks " + std::to_string(ranks[i] + 1) + "-" + std::to_string(end - 1) + " below it)";
        }
      char timeout[32];
      std::snprintf(timeout, sizeof timeout, "%g", options_.rank_timeout);
      fail((silent.empty() ? std::string("the workers") : "rank " + silent) + " did not answer " + what + " within " +
           timeout + " s (--rank-timeout): stopped, hung or lost; ending the job");
    }
  }
}

void MpiExecutor::broadcast(double* buffer, int count, const std::string& what) {
  broadcast(buffer, count, MPI_DOUBLE, what);
}

void MpiExecutor::broadcast(void* buffer, int count, MPI_Datatype type, const std::string& what) {
  std::vector<MPI_Request> request(1);
  MPI_Ibcast(buffer, count, type, 0, comm_, request.data());
  if (is_master())
    wait_bounded(request, {-1}, what);
  else
    await_master(request);  // as long as rank 0 lives (its heartbeat, where there is one)
}

void MpiExecutor::attach(const TaskCatalogue& catalogue) {
  if (!is_master()) throw std::logic_error("MpiExecutor::attach is for rank 0");
  if (attached_) throw std::logic_error("MpiExecutor::attach called twice");
  catalogue_ = catalogue;
  catalogue_.function = {};  // the master runs the function run() is given; keep no references
  const int max_record = *std::max_element(catalogue.record_size.begin(), catalogue.record_size.end());
  const bool tail = size_ > 1 && options_.tail_share > 0;
  const bool shared_exchange = size_ > 1 && options_.shared_exchange;
  double start[header_size] = {command_start, 0, static_cast<double>(catalogue.task_count),
                               static_cast<double>(catalogue.context_size), static_cast<double>(max_record),
                               (tail ? 1.0 : 0.0) + (shared_exchange ? 2.0 : 0.0)};
  broadcast(start, header_size, "the start of the run");
  message_size_ = header_size + static_cast<std::size_t>(catalogue.context_size);
  message_.assign(message_size_, 0.0);
  open_node_window(tail, shared_exchange, max_record);
  if (tail && tail_window_ == MPI_WIN_NULL && options_.on_event)
    options_.on_event("scheduler: no tail shared on demand (--tail-share): it needs every rank on rank 0's node");
  attached_ = true;
  receive_.resize(static_cast<std::size_t>(size_));
  log_.task_group = catalogue.group;
  log_.task_parent = catalogue.parent;
  log_.context_size = catalogue.context_size;
  for (std::size_t p = 0; p < schedule_phase_count; ++p) {
    log_.record_size[p] = catalogue.record_size[p];
    if (catalogue.record_size[p] <= 0) continue;
    auto& used = log_.task_record_size[p];
    for (int t = 0; t < catalogue.task_count; ++t) used.push_back(catalogue.used(static_cast<int>(p), t));
  }
  // Start plans: uniform costs (nothing measured yet).
  for (int p = 0; p < phase_count; ++p) {
    if (catalogue.record_size[static_cast<std::size_t>(p)] <= 0) continue;
    const double started = now_seconds();
    const std::vector<double> uniform(static_cast<std::size_t>(catalogue.task_count), 1.0);
    adopt_plan(p, make_plan(uniform, catalogue_, capacity_), PlanReason::initial, started);
  }
}

void MpiExecutor::stop() {
  if (!is_master() || stopped_) return;
  stopped_ = true;
  if (!attached_) {  // the workers wait in await_start(): a broadcast of the header
    double msg[header_size] = {command_stop};
    broadcast(msg, header_size, "the end of the run");
    return;
  }
  std::fill(message_.begin(), message_.end(), 0.0);
  message_[0] = command_stop;
  send_command("the end of the run");
}

void MpiExecutor::set_owner(int phase, const std::vector<int>& owner) {
  owner_[phase] = owner;
  auto& lists = tasks_of_[phase];
  lists.assign(static_cast<std::size_t>(size_), {});
  for (std::size_t t = 0; t < owner.size(); ++t)
    if (owner[t] >= 0) lists[static_cast<std::size_t>(owner[t])].push_back(static_cast<int>(t));
  decode_tail(phase, owner);  // the tail tasks (negative owners)
}

void MpiExecutor::broadcast_owners(std::vector<int>& owner) {
  broadcast(owner.data(), static_cast<int>(owner.size()), MPI_INT, "a new plan's owners");
}

void MpiExecutor::adopt_plan(int phase, Plan plan, PlanReason reason, double started) {
  const std::vector<double> model = model_cost(phase);
  const double before = owner_[phase].empty() || model.empty() ? 0.0 : predicted_imbalance(owner_[phase], model, capacity_);
  if (reason == PlanReason::forced && size_ > 1) {
    // Test only: turn the plan over the ranks by its version so every evaluation sees a different
    // assignment (the bitwise-identity tests need plans that really change).
    std::vector<int> active;
    for (int r = 0; r < size_; ++r)
      if (capacity_[static_cast<std::size_t>(r)] > 0) active.push_back(r);
    const auto shift = static_cast<std::size_t>(version_[phase] + 1);
    for (int& o : plan.owner) {
      const auto at = static_cast<std::size_t>(std::find(active.begin(), active.end(), o) - active.begin());
      o = active[(at + shift) % active.size()];
    }
    plan.method = PlanMethod::rotated;
    plan.split_groups = count_split_groups(plan.owner, catalogue_.group);
    plan.split_parents = count_split_parents(plan.owner, catalogue_.parent);
    if (!model.empty()) plan.predicted_imbalance = predicted_imbalance(plan.owner, model, capacity_);
  }
  const bool first = owner_[phase].empty();
  if (!first) ++version_[phase];
  // The tail (tail_share of each rank's planned work, its cheapest tasks) is claimed on demand
  // (encode_tail). owner_ keeps the whole plan (its predicted balance is what re-planning judges).
  std::vector<int> owner = plan.owner;
  if (tail_on_) encode_tail(owner, model.empty() ? std::vector<double>(owner.size(), 1.0) : model);
  set_owner(phase, owner);
  owner_[phase] = plan.owner;
  if (size_ > 1) {
    std::fill(message_.begin(), message_.end(), 0.0);
    message_[0] = command_plan;
    message_[1] = phase;
    message_[2] = catalogue_.task_count;
    message_[4] = version_[phase];
    send_command("a new plan");
    // The owners follow in a broadcast of their own: the command buffer holds a context, not a
    // task list, so every evaluation's broadcast is no longer than it needs to be.
    broadcast_owners(owner);
  }
  PlanEvent e;
  e.evaluation = evaluation_ + 1;
  e.phase = phase;
  e.version = version_[phase];
  e.reason = reason;
  e.method = plan.method;
  e.split_groups = plan.split_groups;
  e.split_parents = plan.split_parents;
  e.measured_imbalance = smoothed_imbalance_[phase];
  e.predicted_before = before;
  e.predicted_after = plan.predicted_imbalance;
  e.plan_seconds = now_seconds() - started;
  log_.plans.push_back(e);
  // Re-plan cost estimate: measured times to make and send a plan, smoothed and clipped like the
  // task costs (one preempted plan must not block re-planning for the rest of the run).
  replan_seconds_[phase] = first ? e.plan_seconds
                                 : replan_seconds_[phase] +
                                       cost_smoothing * (std::min(e.plan_seconds, cost_outlier_factor * replan_seconds_[phase]) -
                                                         replan_seconds_[phase]);
  last_plan_run_[phase] = last_check_run_[phase] = evaluation_;
  if (!first) smoothed_imbalance_[phase] = plan.predicted_imbalance;  // judge the new plan on its own
  // The log gets the first plans and then every 100th (a long adaptive run makes thousands);
  // all of them are in /scheduler/plans.
  const std::size_t n = log_.plans.size();
  if (options_.on_event && size_ > 1 && (n <= 20 || n % 100 == 0)) {
    options_.on_event(fmt_plan_line(e));
    if (n == 20) options_.on_event("scheduler: further plans are logged every 100th; all are kept in /scheduler/plans");
  }
}

void MpiExecutor::run_task(int phase, std::span<const double> context, const TaskFunction& function, int task,
                           std::span<double> record) const {
  // Everything a task can throw ends the job here, on whichever rank: the other ranks are inside
  // a command and would otherwise wait for this rank's records for ever.
  try {
    function(context, task, record);
  } catch (const std::exception& e) {
    fail(std::string("in a ") + phase_name(phase) + " task at evaluation " + std::to_string(evaluation_) + ": " + e.what());
  } catch (...) {
    fail(std::string("unknown exception in a ") + phase_name(phase) + " task at evaluation " + std::to_string(evaluation_));
  }
}

void MpiExecutor::evaluate_own(int phase, std::span<const double> context, int record_size, const TaskFunction& task,
                               double* records, double* seconds, bool in_task_order) {
  if (rank_ == options_.inject_failure_rank && evaluation_ == options_.inject_failure_evaluation)
    fail(std::string("in a ") + phase_name(phase) + " task at evaluation " + std::to_string(evaluation_) +
         ": injected failure at evaluation " + std::to_string(evaluation_) + " (test-only option --inject-failure)");
  const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank_)];
  const auto rs = static_cast<std::size_t>(record_size);
  auto last = clock_type::now();  // one clock reading per task: a task's seconds run to the next's start
  for (std::size_t i = 0; i < mine.size(); ++i) {
    const auto at = in_task_order ? static_cast<std::size_t>(mine[i]) : i;
    run_task(phase, context, task, mine[i], std::span<double>(records + at * rs, rs));
    const auto now = clock_type::now();
    seconds[at] = std::chrono::duration<double>(now - last).count();
    last = now;
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
  const double wall_start = now_seconds();
  const auto rs = static_cast<std::size_t>(record_size);
  if (!tail_[phase].empty()) reset_tail_claims(phase);  // before the command releases the workers
  if (size_ > 1) {
    message_[0] = command_evaluate;
    message_[1] = phase;
    message_[2] = task_count;
    message_[3] = record_size;
    message_[4] = static_cast<double>(evaluation_);
    std::copy(context.begin(), context.end(), message_.begin() + header_size);
  }
  // The command and the receives are posted before the master's own share, so worker records land
  // while it computes; all are waited for together (bounded: wait_bounded, or through the window:
  // collect_shared_replies).
  std::vector<MPI_Request> requests;
  std::vector<int> request_rank;
  if (command_word_) {
    send_command("an evaluation");
  } else if (size_ > 1) {
    requests.emplace_back();
    request_rank.push_back(-1);
    MPI_Ibcast(message_.data(), static_cast<int>(message_size_), MPI_DOUBLE, 0, comm_, &requests.back());
  }
  // The replies come through the node window, or up a binomial tree: rank 0 hears from its
  // children only (ranks 1, 2, 4, ...), each passing on its subtree's replies with its own.
  const std::vector<int> children = reply_done_ ? std::vector<int>{} : tree_children(0);
  for (const int c : children) {
    auto& buf = receive_[static_cast<std::size_t>(c)];
    buf.resize(subtree_reply_size(phase, c));
    requests.emplace_back();
    request_rank.push_back(c);
    MPI_Irecv(buf.data(), static_cast<int>(buf.size()), MPI_DOUBLE, c, phase, comm_, &requests.back());
  }
  records.resize(static_cast<std::size_t>(task_count) * rs);
  auto& seconds = seconds_[phase];
  seconds.resize(static_cast<std::size_t>(task_count));
  // The master's own tasks write their records in place (whole: zero beyond what they use, as a
  // worker's unpacked ones are); the workers' are unpacked into theirs.
  evaluate_own(phase, context, record_size, task, records.data(), seconds.data(), true);
  std::vector<double> busy(static_cast<std::size_t>(size_), 0.0);
  for (const int t : tasks_of_[phase][0]) busy[0] += seconds[static_cast<std::size_t>(t)];
  if (!tail_[phase].empty() && capacity_[0] > 0)  // not with --master-share 0
    busy[0] += evaluate_tail(phase, context, task, records.data(), seconds.data());
  if (reply_done_)
    collect_shared_replies(phase, records, busy);
  else if (!requests.empty())
    wait_bounded(requests, request_rank, std::string("the ") + phase_name(phase) + " evaluation " + std::to_string(evaluation_));
  for (const int c : children) unpack_replies(phase, c, receive_[static_cast<std::size_t>(c)].data(), records, busy);
  if (!tail_[phase].empty()) collect_tail(phase, records, busy);
  account(phase, context, busy, now_seconds() - wall_start);
}

void MpiExecutor::account(int phase, std::span<const double> context, const std::vector<double>& busy, double wall) {
  const auto& seconds = seconds_[phase];
  auto& cost = cost_[phase];
  if (cost.empty()) cost = seconds;
  else
    for (std::size_t t = 0; t < cost.size(); ++t)
      cost[t] += cost_smoothing * (std::min(seconds[t], cost_outlier_factor * cost[t] + 1e-9) - cost[t]);
  if (phase != static_cast<int>(Phase::rhs) && !cost_[static_cast<int>(Phase::rhs)].empty()) {
    // Per task, this phase's cost relative to the right-hand side's at the same time: about the
    // number of segment evaluations per task, steady while the costs themselves move.
    const auto& rhs = cost_[static_cast<int>(Phase::rhs)];
    auto& ratio = ratio_[phase];
    const bool first = ratio.empty();
    ratio.resize(rhs.size());
    for (std::size_t t = 0; t < rhs.size(); ++t) {
      const double r = seconds[t] / std::max(rhs[t], 1e-9);
      ratio[t] = first ? r : ratio[t] + cost_smoothing * (std::min(r, cost_outlier_factor * ratio[t]) - ratio[t]);
    }
  }
  double total = 0, cap_sum = 0, worst = 0;
  for (std::size_t r = 0; r < busy.size(); ++r) {
    total += busy[r];
    log_.rank_task_seconds[r] += busy[r];
    if (capacity_[r] <= 0) continue;
    cap_sum += capacity_[r];
    worst = std::max(worst, busy[r] / capacity_[r]);
  }
  const double mean = total / cap_sum;
  const double imbalance = total > 0 ? worst / mean : 1.0;
  smoothed_imbalance_[phase] = runs_[phase] == 0 ? imbalance
                                                 : smoothed_imbalance_[phase] + imbalance_smoothing * (imbalance - smoothed_imbalance_[phase]);
  totals_[phase] += total;
  ++runs_[phase];
  log_.sum_max_seconds[static_cast<std::size_t>(phase)] += worst;
  log_.sum_mean_seconds[static_cast<std::size_t>(phase)] += mean;
  log_.wall_seconds[static_cast<std::size_t>(phase)] += wall;
  ++log_.evaluations[static_cast<std::size_t>(phase)];
  log_.task_cost[static_cast<std::size_t>(phase)] = cost;  // measured (smoothed), not the rhs-based model
  if (evaluation_ % log_.sample_every == 0) {
    log_.samples.push_back({evaluation_, phase, context.empty() ? 0.0 : context[0], imbalance, worst, mean, wall,
                            version_[phase]});
    // Bounded memory over long runs (10^7 evaluations): past max_samples, keep every other sample
    // and sample half as often.
    constexpr std::size_t max_samples = std::size_t{1} << 17;
    if (log_.samples.size() >= max_samples) {
      log_.sample_every *= 2;
      std::erase_if(log_.samples, [&](const ImbalanceSample& x) { return x.evaluation % log_.sample_every != 0; });
    }
  }
}

bool MpiExecutor::await_start() {
  if (is_master()) throw std::logic_error("MpiExecutor::await_start is for workers");
  double start[header_size];
  broadcast(start, header_size, "the start of the run");
  if (start[0] == command_stop) return false;
  if (start[0] != command_start) fail("protocol error: expected start or stop from rank 0");
  catalogue_.task_count = static_cast<int>(start[2]);
  catalogue_.context_size = static_cast<int>(start[3]);
  message_size_ = header_size + static_cast<std::size_t>(catalogue_.context_size);
  message_.assign(message_size_, 0.0);
  const int window_use = static_cast<int>(start[5]);  // 1: tail, 2: shared exchange
  open_node_window((window_use & 1) != 0, (window_use & 2) != 0, static_cast<int>(start[4]));
  attached_ = true;
  return true;
}

void MpiExecutor::serve(const TaskCatalogue& catalogue, const OutputHandler& on_output) {
  if (is_master() || !attached_) throw std::logic_error("MpiExecutor::serve is for workers, after await_start()");
  if (catalogue.task_count != catalogue_.task_count || catalogue.context_size != catalogue_.context_size)
    fail("this rank's model has " + std::to_string(catalogue.task_count) + " tasks and context " +
         std::to_string(catalogue.context_size) + ", rank 0's has " + std::to_string(catalogue_.task_count) + " and " +
         std::to_string(catalogue_.context_size) + " (different scene or build?)");
  catalogue_.record_size = catalogue.record_size;
  catalogue_.used_size = catalogue.used_size;
  std::vector<int> piece_tasks;  // per piece (catalogue.parent): its task count
  for (const int p : catalogue.parent) {
    if (static_cast<std::size_t>(p) >= piece_tasks.size()) piece_tasks.resize(static_cast<std::size_t>(p) + 1, 0);
    ++piece_tasks[static_cast<std::size_t>(p)];
  }
  std::vector<double> reply, full, seconds;
  for (;;) {
    receive_command();
    const double command = message_[0];
    const int phase = static_cast<int>(message_[1]);
    if (command == command_stop) return;
    if (command == command_output) {
      if (!on_output) fail("protocol error: an output command, but this rank has no output handler");
      on_output(std::span<const double>(message_.data() + header_size, message_size_ - header_size), last_rhs_tasks_,
                last_rhs_records_);
      continue;
    }
    if (phase < 0 || phase >= phase_count) fail("protocol error: bad phase from rank 0");
    if (command == command_plan) {
      std::vector<int> owner(static_cast<std::size_t>(catalogue_.task_count));
      broadcast_owners(owner);
      version_[phase] = static_cast<int>(message_[4]);
      set_owner(phase, owner);
      continue;
    }
    if (command != command_evaluate) fail("protocol error: unknown command from rank 0");
    const int record_size = static_cast<int>(message_[3]);
    const auto& function = catalogue.function[static_cast<std::size_t>(phase)];
    if (!function || record_size != catalogue.record_size[static_cast<std::size_t>(phase)] ||
        static_cast<int>(message_[2]) != catalogue.task_count)
      fail(std::string("rank 0 asks for ") + phase_name(phase) + " tasks this rank's catalogue does not have");
    evaluation_ = static_cast<long>(message_[4]);
    const auto& mine = tasks_of_[phase][static_cast<std::size_t>(rank_)];
    const auto n = mine.size();
    const auto rs = static_cast<std::size_t>(record_size);
    // The reply: each task's used doubles (catalogue) and its seconds, through the node window or
    // by message with the replies of this rank's subtree (tree_children), received while it computes.
    std::vector<MPI_Request> from;
    if (!reply_done_) from = receive_subtree(phase, reply);
    full.resize(n * rs);
    seconds.resize(n);
    const std::span<const double> context(message_.data() + header_size, static_cast<std::size_t>(catalogue_.context_size));
    evaluate_own(phase, context, record_size, function, full.data(), seconds.data(), false);
    if (!tail_[phase].empty()) evaluate_tail(phase, context, function, nullptr, nullptr);
    if (reply_done_)
      post_shared_reply(phase, full.data(), seconds.data());
    else
      send_reply(phase, full.data(), seconds.data(), reply, from);
    if (on_output && phase == static_cast<int>(Phase::rhs)) {  // what an output command would sample
      // Only whole pieces: a cut piece's tasks hold parts, which the master combines and writes.
      last_rhs_tasks_.clear();
      last_rhs_records_.clear();
      for (std::size_t i = 0; i < n; ++i) {
        const int task = mine[i];
        const int piece = catalogue.parent.empty() ? task : catalogue.parent[static_cast<std::size_t>(task)];
        if (!catalogue.parent.empty() && piece_tasks[static_cast<std::size_t>(piece)] != 1) continue;
        last_rhs_tasks_.push_back(piece);
        last_rhs_records_.insert(last_rhs_records_.end(), full.begin() + static_cast<std::ptrdiff_t>(i * rs),
                                 full.begin() + static_cast<std::ptrdiff_t>((i + 1) * rs));
      }
    }
  }
}

}  // namespace raceway::scheduler
