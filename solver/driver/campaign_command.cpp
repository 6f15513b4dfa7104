// The campaign command: one mpirun for a whole sweep. Every rank reads the campaign file; world rank
// 0 decides which scenes are left (finished ones are DIR/<id>.h5), splits the world into groups
// (scheduler/campaign_dispatch.hpp) and dispatches; each group runs its scenes as durable runs
// (checkpoints, resume) on its own communicator; at the end rank 0 writes DIR/campaign_status.json
// and the table and plots (io/report/campaign_table.py).
#include "solver/driver/campaign_command.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <mpi.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "io/h5/output_lock.hpp"
#include "io/json/summary_json.hpp"
#include "io/report/report.hpp"
#include "io/report/process.hpp"
#include "io/scene/scene_parser.hpp"
#include "scheduler/campaign_dispatch.hpp"
#include "solver/driver/campaign_check.hpp"
#include "solver/driver/campaign_file.hpp"
#include "solver/driver/campaign_record.hpp"
#include "solver/driver/campaign_plan.hpp"
#include "solver/driver/plan_command.hpp"
#include "solver/driver/scene_on_ranks.hpp"
#include "solver/numerics/petsc_runtime.hpp"
#include "solver/run/checkpoint.hpp"
#include "solver/run/run.hpp"
#include "solver/run/stop_signals.hpp"

namespace raceway::driver {

namespace fs = std::filesystem;

namespace {

double seconds_now() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

std::string clock(double s) {
  if (!std::isfinite(s) || s < 0) return "--:--";
  const long t = std::lround(s);
  return fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60);
}

/// "1.99 MB", "6.6 GB": a byte count in decimal units.
std::string size_text(double bytes) {
  constexpr std::pair<double, const char*> units[] = {{1e12, "TB"}, {1e9, "GB"}, {1e6, "MB"}, {1e3, "kB"}};
  for (const auto& [size, name] : units)
    if (bytes >= size) return fmt::format("{:.3g} {}", bytes / size, name);
  return fmt::format("{:.0f} B", bytes);
}

std::string output_of(const std::string& dir, const CampaignScene& s) { return (fs::path(dir) / (s.id + ".h5")).string(); }

/// DIR/campaign.json: the scenes, their axis values and overrides, run and settling times (what the
/// table script reads besides the outputs).
void write_manifest(const Campaign& c, const std::string& dir) {
  json::JsonObject m;
  m.add("campaign", c.name);
  m.add("file", c.file);
  m.add("scene", c.scene_path);
  m.add("sweep", c.sweep);
  json::JsonObject axes, metrics, scenes;
  for (std::size_t a = 0; a < c.axes.size(); ++a) axes.add(c.axes[a].name, c.axes[a].key);
  for (const std::string& name : c.metrics) metrics.add(name, true);
  for (const CampaignScene& s : c.scenes) {
    json::JsonObject one, values, overrides;
    for (std::size_t a = 0; a < c.axes.size(); ++a) values.add(c.axes[a].name, s.axis_values[a]);
    for (std::size_t i = 0; i < s.overrides.size(); ++i) overrides.add(fmt::format("{}", i), s.overrides[i]);
    one.add("axis_values", std::move(values));
    one.add("overrides", std::move(overrides));
    one.add("end_time_s", s.end_time);
    one.add("settling_time_s", s.settling_time);
    one.add("predicted_steps", s.predicted_steps);
    one.add("predicted_cost", s.predicted_cost);
    scenes.add(s.id, std::move(one));
  }
  m.add("axes", std::move(axes));
  m.add("metrics", std::move(metrics));
  m.add("scenes", std::move(scenes));
  // Array tasks write it at the same time: each through a file of its own, renamed (atomic).
  const fs::path own = fs::path(dir) / fmt::format(".campaign_{}.json", getpid());
  json::write_json_file(own.string(), m);
  fs::rename(own, fs::path(dir) / "campaign.json");
}

/// One scene on the ranks of the group; the leader's exit code and diagnosis.
scheduler::JobResult run_in_group(const scheduler::CampaignGroups& g, const Campaign& c, const std::string& dir,
                                  scheduler::JobAssignment job, bool resume, bool output_thread) {
  const CampaignScene& entry = c.scenes[static_cast<std::size_t>(job.job)];
  scheduler::JobResult result{job.job, 0, job.attempt, 0, {}};
  const double start = seconds_now();
  SceneSource source{c.base_text, c.scene_path, entry.overrides};
  scheduler::MpiExecutorOptions options;
  scheduler::MpiExecutor executor(g.group, options);
  if (!g.leader()) {
    if (broadcast_scene(g.group, source, true)) serve_scene_tasks(source, executor, g.group);
  } else {
    broadcast_scene(g.group, source, true);
    try {
      const scene::Scene scene = campaign_scene(c, entry);
      run::RunOptions run;
      run.executor = &executor;
      run.output_path = output_of(dir, entry);
      run.resume = resume && job.attempt == 0;  // a retry starts afresh
      run.stop_signal = &run::stop_request();
      run.mpi_library = mpi_library_version();
      run.output_thread = output_thread;
      run.on_info = [&](const std::string& s) { spdlog::debug("{}: {}", entry.id, s); };
      const auto summary = run::run_scene(scene, run);
      json::write_json_file((fs::path(dir) / (entry.id + ".json")).string(), summary.to_json());
    } catch (const run::ResumeRefused& e) {
      // A checkpoint this build cannot continue (another build, another scene): a failure that a
      // fresh start mends, so it is retried from the beginning like an integration failure.
      result.code = 1;
      result.diagnosis = e.what();
    } catch (const std::exception& e) {
      // Bad input (exit 2: a scene or path the run refuses) fails again the same way: not retried
      // (scheduler/campaign_dispatch.cpp).
      result.code = exit_code_for(e);
      result.diagnosis = e.what();
    }
    executor.stop();
  }
  MPI_Bcast(&result.code, 1, MPI_INT, 0, g.group);
  result.wall_seconds = seconds_now() - start;
  return result;
}

/// What the dispatcher saw, for progress lines and DIR/campaign_status.json (dispatcher thread only
/// until join()).
struct CampaignProgress {
  const Campaign& campaign;
  std::size_t total = 0, done = 0, running = 0, failed = 0;
  double start = seconds_now(), cost_done = 0, cost_left = 0;
  std::vector<scheduler::JobResult> finished;

  void started(const scheduler::JobAssignment& job, int group) {
    ++running;
    const CampaignScene& s = campaign.scenes[static_cast<std::size_t>(job.job)];
    spdlog::info("campaign: {} on group {}{}", s.id, group, job.attempt > 0 ? " (retry)" : "");
  }
  void ended(const scheduler::JobResult& r, int group, bool retry) {
    --running;
    const CampaignScene& s = campaign.scenes[static_cast<std::size_t>(r.job)];
    if (r.code == 0) ++done, cost_done += s.predicted_cost, cost_left -= s.predicted_cost;
    else if (!retry && r.code != 4) ++failed, cost_left -= s.predicted_cost;
    if (!retry) finished.push_back(r);
    const double rate = cost_done > 0 ? (seconds_now() - start) / cost_done : NAN;
    if (r.code == 0)
      spdlog::info("campaign: {} done in {:.1f} s (group {}); {} done, {} running, {} failed of {}; eta {}", s.id,
                   r.wall_seconds, group, done, running, failed, total, clock(rate * cost_left));
    else
      spdlog::warn("campaign: {} {} (exit {}, group {}): {}", s.id,
                   r.code == 4   ? "stopped, left for --resume"
                   : retry        ? "failed, retried once"
                   : r.attempt > 0 ? "failed twice"
                                   : "failed, not retried (the same input fails again)",
                   r.code, group, r.diagnosis);
  }
};

void write_status(const std::string& dir, const std::string& only_id, const CampaignProgress& p,
                  const scheduler::DispatchRecord& rec, int groups, int ranks) {
  json::JsonObject status, scenes;
  for (const scheduler::JobResult& r : p.finished) {
    json::JsonObject one;
    one.add("exit_code", r.code);
    one.add("attempts", r.attempt + 1);
    one.add("wall_time_s", r.wall_seconds);
    one.add("diagnosis", r.diagnosis);
    scenes.add(p.campaign.scenes[static_cast<std::size_t>(r.job)].id, std::move(one));
  }
  status.add("groups", groups);
  status.add("ranks", ranks);
  const std::pair<const char*, double> seconds[] = {{"wall_time_s", rec.wall},
                                                    {"group_busy_s", rec.group_busy},
                                                    {"group_waiting_for_dispatch_s", rec.group_waiting},
                                                    {"group_idle_at_end_s", rec.group_idle_at_end}};
  for (const auto& [name, value] : seconds) status.add(name, value);
  status.add("scenes_this_call", std::move(scenes));
  // One file per call: a resumed campaign keeps the record of the earlier calls; an array task's
  // (--only) name holds its scene, so that tasks running at once never share one.
  const std::string stem = only_id.empty() ? "campaign_status_" : fmt::format("campaign_status_{}_", only_id);
  int n = 0;
  while (fs::exists(fs::path(dir) / fmt::format("{}{}.json", stem, n))) ++n;
  json::write_json_file((fs::path(dir) / fmt::format("{}{}.json", stem, n)).string(), status);
}

/// The table and plots of DIR (io/report/campaign_table.py); 0 on success.
int make_table(const std::string& dir) {
  const char* py = std::getenv("RACEWAY_PYTHON");
  // Beside the report's script (io/report/CMakeLists.txt: share/raceway/report of the build or install).
  const std::string report = report::report_script_path();
  if (report.empty()) {
    spdlog::error("campaign: no table script (share/raceway/report/campaign_table.py beside the executable)");
    return 1;
  }
  const std::vector<std::string> command{py && *py ? py : "/usr/bin/python3",
                                         (fs::path(report).parent_path() / "campaign_table.py").string(), dir};
  std::string error;
  const int status = report::run_process(command, error);
  if (status != 0)
    spdlog::error("campaign: the table of {} failed ({}: {})", dir, fmt::join(command, " "),
                  status < 0 ? error : fmt::format("exit {}", status));
  return status == 0 ? 0 : 1;
}

/// The scene --only names: its index in sweep order (a Slurm array task id) or its id; -1 for none.
int only_scene(const Campaign& c, const std::string& only) {
  if (only.empty()) return -1;
  for (std::size_t i = 0; i < c.scenes.size(); ++i)
    if (c.scenes[i].id == only || std::to_string(i) == only) return static_cast<int>(i);
  throw numerics::OptionsError(fmt::format("--only {}: no such scene in {} (indices 0..{} in sweep order, or ids s000..{})",
                                         only, c.file, c.scenes.size() - 1, c.scenes.back().id));
}

/// Rank 0: the campaign, the output folder and the scenes left to run; throws on bad input.
std::vector<int> prepare(const Campaign& c, const CampaignRequest& req) {
  const int only = only_scene(c, req.only);
  check_identity(c, req.output_dir);  // before the folder is touched
  fs::create_directories(req.output_dir);
  std::vector<int> left;
  for (std::size_t i = 0; i < c.scenes.size(); ++i) {
    if (only >= 0 && static_cast<int>(i) != only) continue;
    const std::string out = output_of(req.output_dir, c.scenes[i]);
    const bool started = fs::exists(out) || fs::exists(out + ".partial");
    if (started && !req.resume)
      throw h5::OutputPathError(fmt::format("campaign: {} already holds {}{}; continue with --resume or choose another "
                                            "folder (-o)", req.output_dir, c.scenes[i].id,
                                            fs::exists(out) ? ".h5" : ".h5.partial"));
    if (!fs::exists(out)) left.push_back(static_cast<int>(i));
  }
  record_identity(c, req.output_dir);
  write_manifest(c, req.output_dir);
  return left;
}

/// The predicted speed-up of the campaign's base scene: raceway plan's (driver::predicted_speedup over
/// the rank table's rows of the scene file's name).
SpeedupPrediction planned_speedup(const Campaign& c) {
  const std::string scene = fs::path(c.scene_path).stem().string();
  std::vector<driver::RankRow> rows;
  try {
    for (auto& r : driver::read_rank_table(driver::rank_table_path()))
      if (r.scene == scene) rows.push_back(std::move(r));
  } catch (const std::exception& e) {
    spdlog::warn("campaign: no predicted speed-up ({}): 1 rank per scene", e.what());
  }
  return [rows](int ranks) { return driver::predicted_speedup(rows, ranks); };
}

/// Rank 0: the ranks per scene. --only: all of them on its scene; fixed by the campaign file; or
/// chosen from the predicted speed-up and the scenes' predicted costs (logged with the reasons).
int group_size(const Campaign& c, const CampaignRequest& req, const std::vector<int>& left, int world) {
  if (!req.only.empty()) return world;
  if (c.ranks_per_scene > world)
    spdlog::warn("campaign: {}:{}: ranks_per_scene = {}, but the job has {} rank(s): one group of {}", c.file,
                 c.ranks_line, c.ranks_per_scene, world, world);
  if (c.ranks_per_scene > 0) return c.ranks_per_scene;
  std::vector<double> costs;
  for (const int j : left) costs.push_back(c.scenes[static_cast<std::size_t>(j)].predicted_cost);
  const GroupSizeChoice choice = choose_group_size(world, costs, planned_speedup(c));
  spdlog::info("campaign: ranks per scene not fixed by {}; from the predicted speed-up of {} ({}):", c.file,
               fs::path(c.scene_path).stem().string(), driver::rank_table_path());
  for (const std::string& line : choice.reasons) spdlog::info("campaign:   {}", line);
  return choice.ranks_per_group;
}

int run_campaign(const Campaign& c, const CampaignRequest& req, int rank) {
  std::vector<int> left;
  int decided[2] = {0, 1};  // exit code, ranks per scene
  int world = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &world);
  if (rank == 0) decided[0] = exit_code_of([&] {
      left = prepare(c, req);
      spdlog::info("campaign '{}': {} scenes, {} finished, {} to run{}, into {}", c.name, c.scenes.size(),
                   c.scenes.size() - left.size(), left.size(), req.only.empty() ? "" : " (--only " + req.only + ")",
                   req.output_dir);
      decided[1] = group_size(c, req, left, world);
      return 0;
    });
  MPI_Bcast(decided, 2, MPI_INT, 0, MPI_COMM_WORLD);
  if (decided[0] != 0) return decided[0];
  int code = 0;
  run::accept_stop_requests();
  // The groups fill the node's cores: then the output thread would take a rank's (no binding to a
  // free core here: every group leader would want one).
  const OutputThreadPlace thread_place = place_output_thread("auto", MPI_COMM_WORLD, false);
  const bool output_thread = thread_place.on;
  if (rank == 0) spdlog::info("campaign: {}", thread_place.why);
  scheduler::CampaignGroups g = scheduler::split_campaign_groups(MPI_COMM_WORLD, decided[1]);
  CampaignProgress progress{c, 0, 0, 0, 0, seconds_now(), 0, 0, {}};
  std::unique_ptr<scheduler::CampaignDispatcher> dispatcher;
  if (rank == 0) {
    spdlog::info("campaign: {} ranks in {} groups of {}{}", g.world_size, g.group_count, g.ranks_per_group,
                 g.world_size % g.ranks_per_group ? " (the last group takes the remaining ranks)" : "");
    std::vector<double> costs;
    for (const CampaignScene& s : c.scenes) costs.push_back(s.predicted_cost);
    progress.total = left.size();
    for (const int j : left) progress.cost_left += costs[static_cast<std::size_t>(j)];
    scheduler::DispatchEvents events{[&](const auto& job, int group) { progress.started(job, group); },
                                     [&](const auto& r, int group, bool retry) { progress.ended(r, group, retry); },
                                     [] { return run::stop_request().load() != 0; }};
    dispatcher = std::make_unique<scheduler::CampaignDispatcher>(g, costs, left, events);
  }
  {
    // PETSc on the group leaders only (PETSC_COMM_WORLD = MPI_COMM_SELF), one per process.
    std::unique_ptr<numerics::PetscRuntime> petsc = g.leader() ? std::make_unique<numerics::PetscRuntime>() : nullptr;
    scheduler::JobResult last;
    while (true) {
      scheduler::JobAssignment job = g.leader() ? scheduler::request_job(g, last) : scheduler::JobAssignment{};
      job = scheduler::share_job(g, job);
      if (job.job < 0) break;
      last = run_in_group(g, c, req.output_dir, job, req.resume, output_thread);
    }
  }
  if (rank == 0) {
    const scheduler::DispatchRecord record = dispatcher->join();
    const int only = only_scene(c, req.only);  // validated by prepare()
    write_status(req.output_dir, only < 0 ? "" : c.scenes[static_cast<std::size_t>(only)].id, progress, record,
                 g.group_count, g.world_size);
    const std::size_t finished = progress.done;
    spdlog::info("campaign: {} of {} scenes done, {} failed, in {} ({} groups; busy {:.1f} s, waiting for the "
                 "dispatcher {:.3f} s, idle at the end {:.1f} s)", finished, progress.total, progress.failed,
                 clock(record.wall), g.group_count, record.group_busy, record.group_waiting, record.group_idle_at_end);
    code = run::stop_request().load() != 0 ? 4 : progress.failed > 0 ? 1 : 0;
    if (code == 4) spdlog::warn("campaign stopped by a signal: continue with --resume");
    if (finished < progress.total && code == 0) code = 1;
    // The table records every scene, done, failed or not finished, whatever the exit code; an array
    // task (--only) leaves it to `raceway campaign report DIR` after the last one.
    if (req.only.empty()) {
      // Every rank is done: the table's plots may use the cores the ranks had (rank 0 is bound to one).
      const int cores = use_every_core_of_the_job();
      spdlog::debug("campaign: the table and plots on {} core(s)", cores);
      const int table = make_table(req.output_dir);
      if (code == 0) code = table;
    }
  }
  scheduler::free_campaign_groups(g);
  scheduler::broadcast_waiting_idle(code, MPI_COMM_WORLD);
  return code;
}

/// `raceway campaign check FILE`: the scenes the campaign would run.
int check_campaign(const Campaign& c, int ranks) {
  const std::string per_scene =
      c.ranks_per_scene > 0 ? fmt::format("{} rank(s) per scene", c.ranks_per_scene) : "ranks per scene not fixed";
  std::printf("campaign '%s': %zu scenes from %s (%s sweep), %s\n", c.name.c_str(), c.scenes.size(),
              c.scene_path.c_str(), c.sweep.c_str(), per_scene.c_str());
  std::puts("  (predicted for one rank from the speed: steps and wall time, solver/driver/campaign_plan.hpp;"
            " output from the sampling and the model)");
  double bytes = 0;
  for (const CampaignScene& s : c.scenes) {
    std::string values;
    for (std::size_t a = 0; a < c.axes.size(); ++a) values += fmt::format("  {}={}", c.axes[a].name, s.axis_values[a]);
    std::printf("  %s  %.6g s (settling %.6g s)  predicted %.0f steps, %.1f s, output %s%s\n", s.id.c_str(),
                s.end_time, s.settling_time, s.predicted_steps, s.predicted_cost, size_text(s.output_bytes).c_str(),
                values.c_str());
    bytes += s.output_bytes;
  }
  std::printf("  outputs of all scenes: %s\n", size_text(bytes).c_str());
  if (ranks > 0 && c.ranks_per_scene == 0) {
    std::vector<double> costs;
    for (const CampaignScene& s : c.scenes) costs.push_back(s.predicted_cost);
    std::printf("on %d ranks, from the predicted speed-up of %s (%s):\n", ranks,
                fs::path(c.scene_path).stem().string().c_str(), driver::rank_table_path().c_str());
    for (const std::string& line : choose_group_size(ranks, costs, planned_speedup(c)).reasons)
      std::printf("  %s\n", line.c_str());
  }
  std::puts("campaign OK");
  return 0;
}

}  // namespace

CLI::App* add_campaign_command(CLI::App& app, CampaignRequest& request) {
  auto* c = app.add_subcommand("campaign", "run a sweep of scenes on groups of ranks (docs/campaigns.md): "
                               "campaign FILE -o DIR [--resume], campaign check FILE, campaign report DIR");
  c->add_option("args", request.args, "FILE, or check FILE, or report DIR")->required()->expected(1, 2);
  c->add_option("-o,--output-dir", request.output_dir, "folder of the scenes' outputs, the table and the plots");
  c->add_flag("--resume", request.resume, "skip finished scenes, resume interrupted ones from their checkpoints");
  c->add_flag("--check", request.check, "validate the campaign and list its scenes (like campaign check FILE)");
  c->add_option("--only", request.only,
                "run one scene, its index in sweep order (a Slurm array task id) or its id (s003), on all ranks; "
                "no table: `campaign report DIR` makes it (jobs/campaigns/slurm_array.sh)");
  c->add_option("--ranks", request.check_ranks, "with check: the ranks per scene a campaign on N ranks would choose")
      ->check(CLI::PositiveNumber);
  return c;
}

int campaign_command(const CampaignRequest& req) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const bool check = req.check || req.args[0] == "check";
  if (req.args[0] == "report") {
    if (req.args.size() != 2) return rank == 0 ? (spdlog::error("campaign report DIR: no folder given"), 2) : 2;
    return rank == 0 ? make_table(req.args[1]) : 0;
  }
  const std::string file = req.args.back();
  Campaign c;
  int code = 0;
  if (rank == 0) {
    // Rank 0 also builds every scene's model for its output size: a scene that would exceed its
    // max_size fails the same way every time, so it is refused here, before anything runs.
    code = exit_code_of([&] {
      c = load_campaign(file);
      check_campaign_outputs(c);
      return 0;
    });
  } else {
    try {  // every rank reads the campaign; rank 0 says what is wrong with it
      c = load_campaign(file);
    } catch (const std::exception& e) {
      code = exit_code_for(e);
    }
  }
  const int own = code;
  MPI_Allreduce(&own, &code, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  if (rank == 0 && own == 0 && code != 0) spdlog::error("campaign: {} could not be read on every rank", file);
  if (code != 0 || check) return rank == 0 && code == 0 ? check_campaign(c, req.check_ranks) : code;
  if (req.output_dir.empty()) {
    if (rank == 0) spdlog::error("campaign: no output folder; give -o DIR");
    return 2;
  }
  return run_campaign(c, req, rank);
}

}  // namespace raceway::driver
