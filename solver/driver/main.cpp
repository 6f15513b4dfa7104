// The raceway command line: the run driver (the one place besides scheduler/ and io/ where MPI
// lives). `raceway run [SCENE] -o OUT.h5`, `raceway check SCENE`, `raceway plan SCENE`
// (plan_command.hpp), `raceway report OUT.h5`, `raceway atlas FILE -o DIR` (atlas_command.hpp),
// `raceway --version`.
//
// Exit codes (every rank of `raceway run` exits with rank 0's): 0 success; 2 bad input (scene,
// output too large, start-up impossible, report input file, command-line option: one line naming
// it, an output path that cannot be written or is held by another run, a refused --resume);
// 3 integration failure (diagnosed, also past [solver] max_wall_time); 4 stopped by SIGINT,
// SIGTERM or SIGUSR1 after writing a checkpoint (continue with --resume); 1 other errors (including
// an error inside a contact task on any rank, or a rank that stops answering for --rank-timeout,
// which end all ranks through MPI_Abort).
//
// `mpirun -np P raceway run SCENE`: every rank parses the scene rank 0 read (its text is broadcast);
// rank 0 integrates and evaluates its share of the contact tasks, ranks 1.. evaluate theirs
// (scheduler::MpiExecutor). check and report run on rank 0 only.
#include <mpi.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <optional>
#include <chrono>
#include <cstdio>
#include <functional>
#include <memory>
#include <fmt/format.h>
#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "io/h5/h5_series.hpp"
#include "io/h5/output_lock.hpp"
#include "io/report/report.hpp"
#include "raceway/version.hpp"
#include "io/scene/catalogue.hpp"
#include "io/scene/scene_override.hpp"
#include "io/scene/scene_parser.hpp"
#include "io/json/summary_json.hpp"
#include "io/report/life.hpp"
#include "solver/driver/atlas_command.hpp"
#include "scheduler/mpi_executor.hpp"
#include "solver/bearing/model.hpp"
#include "solver/driver/plan_command.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/run/build_info.hpp"
#include "solver/run/output_writer.hpp"
#include "solver/run/checkpoint.hpp"
#include "solver/run/run.hpp"
#include "solver/run/stop_signals.hpp"
#include "solver/driver/parallel_output.hpp"
#include "solver/driver/scene_on_ranks.hpp"
#include "solver/driver/campaign_command.hpp"

namespace {

using namespace raceway;
using driver::exit_code_of;

scene::Scene load(const std::string& path, const std::vector<std::string>& overrides) {
  return scene::load_scene(path, overrides);
}

std::string clock_text(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long t = std::lround(s);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60) : fmt::format("{:02}:{:02}", t / 60, t % 60);
}

/// A progress bar on a terminal, redrawn at most 5 times a second and its line ended before any
/// other message (finish(), also when the run throws); plain log lines every 10 % otherwise.
class ProgressReporter {
 public:
  ProgressReporter() : tty_(isatty(STDERR_FILENO) != 0) {}
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;
  ~ProgressReporter() { finish(); }
  void operator()(const run::Progress& p) {
    const double frac = p.end_time > 0 ? p.time / p.end_time : 1.0;
    if (tty_) {
      const auto now = std::chrono::steady_clock::now();
      last_ = p, pending_ = true;
      if (open_ && frac < 1.0 && now - last_draw_ < std::chrono::milliseconds(200)) return;
      last_draw_ = now;
      draw(p);
      if (frac >= 1.0) finish();
    } else if (frac >= next_) {
      spdlog::info("t {:.6g} s of {:.6g} s ({:.0f} %), {:.2f} revolutions, wall {:.2f} s, eta {}, steps {}", p.time,
                   p.end_time, 100 * frac, p.revolutions, p.wall_seconds, clock_text(eta(p, frac)), p.steps);
      while (next_ <= frac) next_ += 0.1;
    }
  }
  /// Draws the last progress if it was skipped, then ends the bar's line so that the next message
  /// starts on its own line.
  void finish() {
    if (pending_) draw(last_);
    if (!open_) return;
    std::fputc('\n', stderr);
    std::fflush(stderr);
    open_ = false;
  }

 private:
  static double eta(const run::Progress& p, double frac) {
    return frac > 0 ? p.wall_seconds * (1 - frac) / frac : NAN;
  }
  void draw(const run::Progress& p) {
    const double frac = p.end_time > 0 ? p.time / p.end_time : 1.0;
    const int width = 30, filled = static_cast<int>(std::clamp(frac, 0.0, 1.0) * width + 1e-6);
    std::fprintf(stderr, "\r[%s%s] %5.1f%%  t %.4g s  %.2f rev  wall %s  eta %s  steps %ld   ",
                 std::string(filled, '#').c_str(), std::string(width - filled, '.').c_str(), 100 * frac, p.time,
                 p.revolutions, clock_text(p.wall_seconds).c_str(), clock_text(eta(p, frac)).c_str(), p.steps);
    std::fflush(stderr);
    open_ = true, pending_ = false;
  }

  bool tty_;
  bool open_ = false;     ///< a bar is drawn and its line not ended
  bool pending_ = false;  ///< last_ has not been drawn (rate limit)
  run::Progress last_{};
  double next_ = 0.1;
  std::chrono::steady_clock::time_point last_draw_{};
};

/// Log lines name their level when it is not plain information: "[raceway] warning: ...",
/// "[raceway] error: ..." (the %* flag of the pattern).
class LevelPrefix : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    const std::string_view text = msg.level >= spdlog::level::err    ? "error: "
                                  : msg.level == spdlog::level::warn ? "warning: "
                                  : msg.level <= spdlog::level::debug ? "debug: "
                                                                      : "";
    dest.append(text.data(), text.data() + text.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<LevelPrefix>(); }
};

/// What `raceway run` was asked for besides the scene.
struct RunRequest {
  std::string output, summary_json, result_options;
  bool scheduler_log = false, resume = false;
  run::SharedOutput* shared_output = nullptr;  ///< the parallel output; nullptr: rank 0 writes all
  driver::OutputThreadPlace output_thread{true, -1, ""};  ///< driver::place_output_thread
};

/// The rating lives of the finished output (io/report/life.hpp: the report's calculation over its
/// window, the second half), or a note why there are none.
void add_life(json::JsonObject& summary, const std::string& output, const std::string& summary_json) {
  std::string why;
  const std::string life = report::life_json(output, summary_json + ".life", why);
  if (!life.empty()) {
    summary.add_raw("life", life);
    return;
  }
  json::JsonObject note;
  note.add("note", "no life: " + why);
  summary.add("life", std::move(note));
}

int run_command(const scene::Scene& scene, const RunRequest& request, scheduler::Executor& executor) {
  spdlog::info("scene '{}' from {}", scene.scene.name, scene.source);
  for (const std::string& o : scene.overrides) spdlog::info("--set {}", o);
  const std::string& output = request.output;
  const std::string& summary_json = request.summary_json;
  if (!summary_json.empty()) h5::check_output_path(summary_json, "run summary (--summary-json)");
  run::RunOptions options;
  options.executor = &executor;
  options.output_path = output;
  options.scheduler_log = request.scheduler_log;
  options.resume = request.resume;
  options.shared_output = request.shared_output;
  options.output_thread = request.output_thread.on;
  options.output_thread_core = request.output_thread.core;
  options.result_options = request.result_options;
  options.stop_signal = &run::stop_request();
  options.mpi_library = driver::mpi_library_version();
  ProgressReporter progress;
  options.on_progress = [&](const run::Progress& p) { progress(p); };
  options.on_info = [&](const std::string& s) {
    progress.finish();  // a message never shares the bar's line
    spdlog::info("{}", s);
  };
  const auto sum = run::run_scene(scene, options);
  progress.finish();
  executor.stop();
  auto json = sum.to_json();
  spdlog::info("done: {:.4g} s simulated ({:.2f} revolutions) in {:.2f} s wall; {} steps, {} rhs, {} jacobians, "
               "{} newton failures, {} error-test failures",
               sum.simulated_time_s, sum.driven_ring_revolutions, sum.wall_time_s, sum.stats.steps,
               sum.model_rhs_evaluations, sum.model_jacobian_evaluations, sum.stats.newton_failures,
               sum.stats.error_test_failures);
  spdlog::info("cage speed {:.3f} rpm (second half), kinematic at the loaded contact angle {:.3f} rpm, slip {:.3f} %",
               sum.cage_speed_rpm, sum.rolling_cage_speed_rpm, 100 * sum.cage_slip);
  if (const auto* log = executor.schedule_log(); log && log->ranks > 1) {
    auto ratio = [&](int p) {
      return log->sum_mean_seconds[p] > 0 ? log->sum_max_seconds[p] / log->sum_mean_seconds[p] : 1.0;
    };
    spdlog::info("scheduler: {} ranks, {} policy, {} plans; time-averaged imbalance rhs {:.3f}, jacobian {:.3f}",
                 log->ranks, log->policy, log->plans.size(), ratio(0), ratio(1));
  }
  spdlog::info("output written to {}", output);
  if (!summary_json.empty()) {
    add_life(json, output, summary_json);
    json::write_json_file(summary_json, json);
    spdlog::info("summary written to {}", summary_json);
  }
  if (const std::string note = run::output_share_note(sum); !note.empty()) spdlog::info("{}", note);
  for (const auto& [name, text] : sum.warnings) spdlog::warn("{}", text);  // the last lines of the run
  return 0;
}

/// `raceway report OUT.h5`: the Python report (io/report/raceway_report.py) of a planar or spatial run.
int report_command(const report::ReportOptions& options) { return report::run_report(options); }

/// `--inject-pause EVALUATION:SECONDS` (test only).
void parse_pause(const std::string& spec, scheduler::MpiExecutorOptions& options) {
  const auto colon = spec.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    options.inject_pause_evaluation = std::stol(spec.substr(0, colon));
    options.inject_pause_seconds = std::stod(spec.substr(colon + 1));
  } catch (const std::exception&) {
    throw std::invalid_argument("--inject-pause expects EVALUATION:SECONDS (e.g. 40:5), got '" + spec + "'");
  }
}

/// `--inject-failure RANK:EVALUATION` (test only).
void parse_injection(const std::string& spec, scheduler::MpiExecutorOptions& options) {
  const auto colon = spec.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    options.inject_failure_rank = std::stoi(spec.substr(0, colon));
    options.inject_failure_evaluation = std::stol(spec.substr(colon + 1));
  } catch (const std::exception&) {
    throw std::invalid_argument("--inject-failure expects RANK:EVALUATION (e.g. 1:40), got '" + spec + "'");
  }
}

// ---- option values: every number finite and within its range, or a one-line reason (exit 2) ----
// CLI11's own range validators accept nan and print their bounds with 309 digits; these say what
// is expected in words.

/// The option's text as a finite number, or nullopt (trailing text, nan, inf, overflow).
std::optional<double> finite_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (*end != '\0' || errno == ERANGE || !std::isfinite(v)) return std::nullopt;
  return v;
}

/// A finite number >= lo (> lo when open); `whole`: an integer, at most hi.
CLI::Validator number_at_least(double lo, bool open, bool whole = false, double hi = 1e9) {
  const std::string wanted = fmt::format("{} {} {}{}", whole ? "a whole number" : "a finite number",
                                         open ? ">" : ">=", lo, whole ? fmt::format(" and <= {:g}", hi) : "");
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const std::optional<double> v = finite_number(text);
        const bool ok = v && (open ? *v > lo : *v >= lo) && (!whole || (*v == std::floor(*v) && *v <= hi));
        return ok ? std::string() : fmt::format("expected {}, got '{}'", wanted, text);
      },
      whole ? "INT" : "NUMBER");
}

/// A command-line error as one line on rank 0: "[raceway] error: --master-share: expected ...".
int command_line_error(const CLI::App& app, const CLI::ParseError& e, int rank, int argc, char** argv) {
  if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
  if (rank == 0) {
    std::string what = e.what();
    // CLI11 reports an unknown command as a missing one.
    const auto known = [&](const char* word) {
      return !app.get_subcommands([&](const CLI::App* c) { return c->check_name(word); }).empty();
    };
    if (argc > 1 && argv[1][0] != '-' && !known(argv[1]))
      what = fmt::format("unknown command '{}'; the commands are run, check, plan, report, campaign and atlas", argv[1]);
    std::replace(what.begin(), what.end(), '\n', ' ');
    std::fprintf(stderr, "[raceway] error: %s (see raceway --help)\n", what.c_str());
  }
  return 2;
}

/// The command line: its subcommands and the values of their options.
struct CommandLine {
  std::string scene_path, output = "raceway.h5", summary_json, petsc_options;
  scheduler::MpiExecutorOptions exec_options;
  std::string schedule = "adaptive", exchange = "shared", inject, inject_pause;
  std::string method;  ///< --method: the scene's [solver] method, replaced
  std::vector<std::string> overrides;  ///< --set section.key=VALUE
  bool replan_every_evaluation = false, scheduler_log = false, resume = false, parallel_output = false;
  std::string output_thread = "auto";
  report::ReportOptions report_options;
  double window_start = NAN;
  bool no_plots = false, animate = false, xdmf = false, vtk = false;
  double contact_threshold = NAN;
  CLI::App* run = nullptr;
  CLI::App* check = nullptr;
  CLI::App* report = nullptr;
  CLI::App* plan = nullptr;
  driver::PlanOptions plan_options;
};

/// --set section.key=VALUE, repeatable: a scene key set on the command line.
void add_set_option(CLI::App& command, CommandLine& cl) {
  command.add_option("--set", cl.overrides,
                     "set a scene key, validated like the file's: --set inner_ring.speed=\"3000 rpm\" (repeatable)")
      ->allow_extra_args(false);
}

void add_run_command(CLI::App& app, CommandLine& cl) {
  auto* run = cl.run = app.add_subcommand("run", "simulate a scene (the built-in default when none is given)");
  run->add_option("scene", cl.scene_path, "scene file (TOML)");
  run->add_option("-o,--output", cl.output, "HDF5 output file")->capture_default_str();
  run->add_option("--summary-json", cl.summary_json, "write the run summary as JSON");
  add_set_option(*run, cl);
  run->add_option("--petsc-options", cl.petsc_options,
                  "PETSc options for the petsc-bordered linear solver, e.g. \"-fieldsplit_1_pc_factor_mat_solver_type "
                  "mumps\"; override the scene's [solver] petsc_options");
  run->add_option("--method", cl.method,
                  "time integration method, replacing the scene's [solver] method: bdf, adams (CVODE), erk, ark "
                  "(ARKODE); its max_order then defaults to the method's unless the scene gives one")
      ->check(CLI::IsMember({"bdf", "adams", "erk", "ark"}));
  run->add_option("--schedule", cl.schedule, "task plan under mpirun: adaptive (re-planned from measured task times) "
                  "or static (one plan from the first measured times)")
      ->check(CLI::IsMember({"adaptive", "static"}))
      ->capture_default_str();
  run->add_option("--master-share", cl.exec_options.master_share,
                  "rank 0's share of the contact tasks relative to a worker's (0: none)")
      ->check(number_at_least(0, false))
      ->capture_default_str();
  run->add_option("--tail-share", cl.exec_options.tail_share,
                  "under mpirun: fraction of each rank's planned contact work handed out on demand within an "
                  "evaluation, to whichever rank is free first (0: off; 1: every task)")
      ->check(number_at_least(0, false) & CLI::Range(0.0, 1.0))
      ->capture_default_str();
  run->add_option("--exchange", cl.exchange,
                  "under mpirun, how rank 0's commands reach the workers and their results come back: shared "
                  "(through shared memory when every rank is on rank 0's node; else messages) or messages "
                  "(always, as between nodes)")
      ->check(CLI::IsMember({"shared", "messages"}))
      ->capture_default_str();
  run->add_option("--rank-timeout", cl.exec_options.rank_timeout,
                  "seconds rank 0 waits for a worker's answer, and a worker for a sign of life of rank 0, before it "
                  "ends the job naming the rank")
      ->check(number_at_least(0, true))
      ->capture_default_str();
  run->add_option("--schedule-sample-every", cl.exec_options.sample_every,
                  "keep every n-th evaluation's imbalance in /scheduler/imbalance")
      ->check(number_at_least(0, true, true))
      ->capture_default_str();
  run->add_flag("--resume", cl.resume,
                "continue OUT.h5.partial from its last checkpoint (OUT.h5.checkpoint); start afresh when there is none");
  run->add_flag("--parallel-output", cl.parallel_output,
                "with several ranks each writes the segment diagnostics it evaluated (HDF5 MPI-IO, collective "
                "writes); default: rank 0 writes the whole file (perf/studies/results/output_notes.md: faster here)");
  run->add_option("--output-thread", cl.output_thread,
                  "the output's work at output times on a thread of rank 0's own: auto (when it gets a core no "
                  "rank uses; under mpirun's binding it is bound to such a core), on, off; the same results either way")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  run->add_flag("--scheduler-log", cl.scheduler_log,
                "write the task scheduler's log (/scheduler) also for a serial run (always with several ranks)");
  // Test-only options (hidden: empty group).
  run->add_flag("--replan-every-step", cl.replan_every_evaluation, "test only: a new plan before every evaluation")
      ->group("");
  run->add_option("--inject-failure", cl.inject, "test only: RANK:EVALUATION throws inside a task")->group("");
  run->add_option("--inject-pause", cl.inject_pause, "test only: EVALUATION:SECONDS rank 0 works that long before it")
      ->group("");
}

void add_check_command(CLI::App& app, CommandLine& cl) {
  auto* check = cl.check = app.add_subcommand("check", "validate a scene and print the model it would build");
  check->add_option("scene", cl.scene_path, "scene file (TOML); the built-in default when none is given");
  check->add_option("--petsc-options", cl.petsc_options, "PETSc options to validate with the scene's");
  add_set_option(*check, cl);
}

void add_report_command(CLI::App& app, CommandLine& cl) {
  auto* report = cl.report =
      app.add_subcommand("report", "the report of a run's output file: summary.json, figures, report.html");
  report->add_option("output_file", cl.report_options.input, "HDF5 output of a run (planar or spatial)")->required();
  report->add_option("-o,--output-dir", cl.report_options.output_dir, "folder for summary.json, the PNGs and "
                     "report.html (default: <stem>_report beside the file)");
  report->add_option("--window-start", cl.window_start, "start of the analysis window in s (default: second half)")
      ->check(number_at_least(0, false));
  report->add_option("--bin-width", cl.report_options.bin_width_deg, "azimuth bin width in deg (0 to 360]")
      ->check(number_at_least(0, true))
      ->capture_default_str();
  report->add_option("--contact-threshold", cl.contact_threshold, "pocket contact threshold in N (default: 1 % of "
                     "the peak pocket force)")->check(number_at_least(0, true));
  report->add_flag("--no-plots", cl.no_plots, "write summary.json only");
  report->add_flag("--animate", cl.animate, "also an animation of the bearing along its axis (MP4 with ffmpeg, else GIF)");
  report->add_flag("--xdmf", cl.xdmf, "also OUT.xdmf beside the .h5: the bodies over time for ParaView");
  report->add_flag("--vtk", cl.vtk, "also OUT_vtk/OUT.pvd: the bodies over time as VTK PolyData files");
}

/// `raceway check SCENE`: the model the scene builds and the Newton linear solver it would use.
int check_command(const std::string& scene_path, const std::vector<std::string>& overrides) {
  const scene::Scene scene = load(scene_path, overrides);
  for (const std::string& o : scene.overrides) spdlog::info("--set {}", o);
  std::fputs(scene::describe_catalogue_values(scene).c_str(), stdout);
  const auto model = bearing::build_model(scene);
  std::fputs(model.describe().c_str(), stdout);
  const numerics::BorderedLayout layout{model.border_size, model.element_count, model.block_size};
  std::puts(numerics::prepare_linear_solver(scene.solver, layout).c_str());
  const run::OutputEstimate output = run::estimate_output(model, scene);
  std::puts(output.describe(scene.output.max_size).c_str());
  run::check_output_size(output, scene);
  std::puts("scene OK");
  return 0;
}

/// `raceway run` on every rank of `comm`: its rank 0 reads the scene and integrates, all ranks
/// evaluate tasks. Returns this rank's exit code (rank 0's, on every rank); MPI is still initialised.
int run_on_all_ranks(CommandLine& cl, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  driver::SceneSource source;
  scene::Scene scene;
  bool ok = true;
  int code = 0;
  if (rank == 0) {
    try {
      scene = load(cl.scene_path, cl.overrides);
      // --method edits the scene text, so the output's stored scene says what ran.
      if (!cl.method.empty())
        scene = scene::parse_scene(scene::override_scene_key(scene.text, "solver", "method", fmt::format("\"{}\"", cl.method)),
                                scene.source, scene.overrides);
      source = {scene.text, scene.source, scene.overrides};
    } catch (const scene::SceneError& e) {
      spdlog::error("{}", e.what());
      code = 2, ok = false;
    }
  }
  if (!driver::broadcast_scene(comm, source, ok)) return rank == 0 ? code : 0;
  cl.exec_options.policy = cl.replan_every_evaluation ? scheduler::SchedulePolicy::every_evaluation
                           : cl.schedule == "static"  ? scheduler::SchedulePolicy::static_plan
                                                      : scheduler::SchedulePolicy::adaptive;
  cl.exec_options.shared_exchange = cl.exchange == "shared";
  try {
    if (!cl.inject.empty()) parse_injection(cl.inject, cl.exec_options);
    if (!cl.inject_pause.empty()) parse_pause(cl.inject_pause, cl.exec_options);
  } catch (const std::exception& e) {
    if (rank == 0) spdlog::error("{}", e.what());
    return 2;
  }
  cl.exec_options.on_event = [](const std::string& line) { spdlog::info("{}", line); };
  scheduler::MpiExecutor executor(comm, cl.exec_options);
  executor.watch_master();  // a stopped rank 0 ends the workers after --rank-timeout
  const driver::OutputThreadPlace output_thread = driver::place_output_thread(cl.output_thread, comm);
  if (rank != 0) {
    driver::serve_scene_tasks(source, executor, comm, cl.parallel_output);
  } else {
    if (size > 1) spdlog::info("{} ranks: contact tasks on all ranks, {} schedule", size,
                               scheduler::schedule_policy_name(cl.exec_options.policy));
    code = exit_code_of([&] {
      // PETSc on rank 0 only (PETSC_COMM_WORLD = MPI_COMM_SELF): the Newton systems live there.
      const numerics::PetscRuntime petsc(cl.petsc_options);
      // --parallel-output: with several ranks each writes the segment diagnostics it evaluated
      // (MPI-IO); by default rank 0 writes everything (measured cheaper, output_notes.md).
      driver::MpiSharedOutput shared(comm, executor);
      const RunRequest request{cl.output, cl.summary_json, cl.petsc_options, cl.scheduler_log, cl.resume,
                               size > 1 && cl.parallel_output ? &shared : nullptr, output_thread};
      if (!request.shared_output) spdlog::info("{}", output_thread.why);
      return run_command(scene, request, executor);
    });
    executor.stop();  // releases the workers (also after a failure)
  }
  // Every rank exits with rank 0's code (a stop by a signal, a failed integration).
  MPI_Bcast(&code, 1, MPI_INT, 0, comm);
  return code;
}

/// `raceway check` or `raceway report`, on rank 0 only.
int check_or_report(CommandLine& cl) {
  // PETSc after MPI (so it leaves MPI_Finalize to us), on rank 0 only: the Newton systems and their
  // linear algebra live there (README.md, "In parallel"). Destroyed before MPI_Finalize.
  return exit_code_of([&] {
    const numerics::PetscRuntime petsc(cl.petsc_options);
    if (*cl.check) return check_command(cl.scene_path, cl.overrides);
    if (*cl.plan) return driver::plan_command(cl.plan_options);
    if (!std::isnan(cl.window_start)) cl.report_options.window_start = cl.window_start;
    if (!std::isnan(cl.contact_threshold)) cl.report_options.contact_threshold = cl.contact_threshold;
    cl.report_options.plots = !cl.no_plots;
    cl.report_options.animate = cl.animate;
    cl.report_options.xdmf = cl.xdmf;
    cl.report_options.vtk = cl.vtk;
    return report_command(cl.report_options);
  });
}

/// Whether the command line is a run or a campaign that runs scenes (not `campaign check` or
/// `campaign report`): read before the parser exists, since the stop signals are taken first.
bool takes_stop_requests(int argc, char** argv) {
  if (argc < 2) return false;
  const std::string_view command = argv[1];
  if (command == "run") return true;
  if (command != "campaign") return false;
  for (int i = 2; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--check" || arg == "--help" || arg == "-h" || (i == 2 && (arg == "check" || arg == "report")))
      return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  // First, before MPI or anything else starts a thread: SIGINT, SIGTERM and SIGUSR1 go to one thread
  // that waits for them, blocked in all others (solver/run/stop_signals.hpp says why). A run or a
  // campaign takes them as stop requests from here on (Slurm's SIGUSR1 may come at once).
  run::take_stop_signals(takes_stop_requests(argc, argv));
  // A file-size limit (ulimit -f, a quota) is reported by the write that hits it, as an error with
  // the file's name, rather than ending the process with SIGXFSZ.
  std::signal(SIGXFSZ, SIG_IGN);
  h5::prepare_hdf5_library();  // before MPI_Init
  // A campaign's dispatcher is a thread beside world rank 0's own scenes (scheduler/campaign_dispatch.hpp).
  const bool campaign = argc > 1 && std::string_view(argv[1]) == "campaign";
  // Otherwise rank 0 has threads that never call MPI (the output thread, the chunk compressor).
  int threads = 0;
  MPI_Init_thread(&argc, &argv, campaign ? MPI_THREAD_MULTIPLE : MPI_THREAD_FUNNELED, &threads);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  spdlog::set_default_logger(spdlog::stderr_color_mt("raceway"));  // messages on stderr, data on stdout
  auto formatter = std::make_unique<spdlog::pattern_formatter>();
  formatter->add_flag<LevelPrefix>('*').set_pattern("[raceway] %*%v");
  spdlog::set_formatter(std::move(formatter));

  CLI::App app{"raceway: rolling-bearing dynamics (rings, rollers, cage) with CVODE"};
  app.require_subcommand(1);
  std::string libraries;
  for (const auto& [name, value] : run::build_info(driver::mpi_library_version()))
    if (name != "raceway_version" && name != "raceway_commit") libraries += fmt::format("\n  {}: {}", name, value);
  app.set_version_flag("--version", fmt::format("raceway {} (commit {}){}", kVersion, kGitCommit, libraries));
  CommandLine cl;
  add_run_command(app, cl);
  add_check_command(app, cl);
  add_report_command(app, cl);
  cl.plan = driver::add_plan_command(app, cl.plan_options);
  driver::CampaignRequest campaign_request;
  CLI::App* campaign_app = driver::add_campaign_command(app, campaign_request);
  driver::AtlasRequest atlas_request;
  CLI::App* atlas_app = driver::add_atlas_command(app, atlas_request);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {  // also --help and --version, with code 0
    const int code = command_line_error(app, e, rank, argc, argv);
    MPI_Finalize();
    return code;
  }
  if (campaign && threads < MPI_THREAD_MULTIPLE) {
    if (rank == 0) spdlog::error("campaign: the MPI library gives no MPI_THREAD_MULTIPLE, which the dispatcher needs");
    MPI_Finalize();
    return 1;
  }
  const int code = *cl.run            ? run_on_all_ranks(cl, MPI_COMM_WORLD)
                   : *campaign_app    ? driver::campaign_command(campaign_request)
                   : *atlas_app       ? driver::atlas_command(atlas_request, rank, size)
                   : rank == 0        ? check_or_report(cl)
                                      : 0;
  MPI_Finalize();
  return code;
}
