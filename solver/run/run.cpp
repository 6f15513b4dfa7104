// One simulation from a validated scene to an output file (docs/output_layout.md) and a summary:
// model, start-up state (or a checkpoint), CVODE, output at fixed times by interpolation,
// checkpoints. One loop for every bearing kind; what a sample writes comes from the output table
// (solver/run/output_writer.hpp), what the summary sums from solver/run/run_totals.hpp.
#include "solver/run/run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <optional>

#include "io/h5/h5_series.hpp"
#include "io/scene/scene_overrides.hpp"
#include "io/scene/scene_parser.hpp"
#include "raceway/version.hpp"
#include "io/h5/output_lock.hpp"
#include "solver/run/build_info.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/bearing/thermal_network.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/run/checkpoint.hpp"
#include "solver/run/output_thread.hpp"
#include "solver/run/output_writer.hpp"
#include "solver/run/housing_sensor.hpp"
#include "solver/run/pocket_steps.hpp"
#include "solver/run/power_balance.hpp"
#include "solver/run/run_profile.hpp"
#include "solver/run/run_totals.hpp"
#include "solver/run/scene_summary.hpp"
#include "solver/run/schedule_output.hpp"

namespace raceway::run {

json::JsonObject RunSummary::to_json() const {
  json::JsonObject j;
  j.add("simulated_time_s", simulated_time_s);
  j.add("wall_time_s", wall_time_s);
  j.add("steps", stats.steps);
  j.add("rhs_evaluations", model_rhs_evaluations);
  j.add("jacobian_evaluations", model_jacobian_evaluations);
  j.add("newton_iterations", stats.newton_iterations);
  j.add("newton_failures", stats.newton_failures);
  j.add("error_test_failures", stats.error_test_failures);
  j.add("linear_setups", stats.linear_setups);
  j.add("segment_evaluations", segment_evaluations);
  j.add("time_per_rhs_s", model_rhs_evaluations > 0 ? rhs_seconds / static_cast<double>(model_rhs_evaluations) : 0.0);
  j.add("time_per_jacobian_s",
        model_jacobian_evaluations > 0 ? jacobian_seconds / static_cast<double>(model_jacobian_evaluations) : 0.0);
  j.add("cage_speed_rpm", cage_speed_rpm);
  j.add("epicyclic_cage_speed_rpm", epicyclic_cage_speed_rpm);
  j.add("rolling_cage_speed_rpm", rolling_cage_speed_rpm);
  j.add("cage_slip", cage_slip);
  j.add("driven_ring_revolutions", driven_ring_revolutions);
  j.add("inner_ring_contact_force_n", inner_ring_contact_force_n);
  j.add("inner_ring_load_n", inner_ring_load_n);
  if (model_kind == "spatial") j.add(spatial_rollers ? "max_roller_load_n" : "max_ball_load_n", max_ball_load_n);
  j.add("model_kind", model_kind);
  j.add("energy_initial_j", energy_initial_j);
  j.add("energy_final_j", energy_final_j);
  j.add("energy_max_drift_j", energy_max_drift_j);
  j.add("output_samples", static_cast<long long>(output_samples));
  j.add("method", method);
  j.add("order_choice", order_choice);
  j.add("step_limiting_states", step_limiting_json(step_limiting));
  j.add("time_split_s", time_split_json(timing, output_seconds, wall_time_s));
  j.add("output_time_s", output_seconds);
  j.add("output_write_time_s", output_write_seconds);
  j.add("output_thread_time_s", output_thread_seconds);
  if (!pocket_step_totals.empty()) j.add("pocket_step_totals", pocket_step_totals);
  if (!power_balance.empty()) j.add("power_balance", power_balance);
  if (!thermal.empty()) j.add("thermal", thermal);
  json::JsonObject named_warnings;
  for (const auto& [name, text] : warnings) named_warnings.add(name, text);
  j.add("warnings", std::move(named_warnings));
  j.add("scene_overrides", scene_overrides);
  j.add("scene_parameters", scene_parameters);
  return j;
}

std::vector<std::pair<std::string, std::string>> regime_warnings(const RunSummary& sum) {
  std::vector<std::pair<std::string, std::string>> out;
  if (std::fabs(sum.cage_slip) >= kCageSlipFarFromRolling && std::fabs(sum.driven_ring_revolutions) > 0)
    out.emplace_back(
        "cage_slip",
        fmt::format("the cage slips {:.1f} % against its epicyclic speed (cage {:.4g} rpm, epicyclic {:.4g} rpm, "
                    "second half of the run): the rolling elements hardly roll, far from a bearing's running "
                    "regime; the run may have ended inside its transient or the drive may be unphysical (check the "
                    "ring speed's ramp, the load and end_time)",
                    100 * sum.cage_slip, sum.cage_speed_rpm, sum.epicyclic_cage_speed_rpm));
  if (!std::isfinite(sum.energy_final_j) || !std::isfinite(sum.cage_speed_rpm))
    out.emplace_back("energy", fmt::format("the run ended with a non-finite energy ({}) or cage speed ({}): its "
                                           "state is not physical",
                                           sum.energy_final_j, sum.cage_speed_rpm));
  return out;
}

std::string output_share_note(const RunSummary& sum) {
  if (!(sum.wall_time_s > 0) || sum.output_seconds <= kOutputShareToMention * sum.wall_time_s) return "";
  return fmt::format("the output took {:.1f} % of the run ({:.3f} s of {:.3f} s wall for {} samples: at each a "
                     "right-hand side for the diagnostics, the rows, their compression); sample less often "
                     "([scene] output_interval: the pocket contacts' events, peaks and impulses are observed at "
                     "every step whatever the sampling), store the segment diagnostics less often ([output] "
                     "segment_every) or leave them out ([output] segments = false) to make it smaller",
                     100 * sum.output_seconds / sum.wall_time_s, sum.output_seconds, sum.wall_time_s,
                     sum.output_samples);
}

namespace {

/// Checks the Newton linear solver (and PETSc's options) before any output exists, then creates the
/// output (OUT.h5.partial), or opens it to continue from a checkpoint, with the attributes every
/// run has.
h5::H5SeriesWriter open_run_output(const scene::Scene& scene, const RunOptions& options, const bearing::Equations& eq,
                                   const Checkpoint* resumed) {
  const std::string solver_line =
      numerics::prepare_linear_solver(scene.solver, {eq.border_size(), eq.block_count(), eq.block_size()});
  if (options.on_info) options.on_info(solver_line);
  const bearing::Model& model = eq.model();
  h5::H5WriterOptions storage;
  // Written by the output thread (not the parallel output): flushed every 4 MiB of rows there, so
  // that the commit at the end, on the run's thread, has little left to store and to sync.
  if (!options.shared_output && options.output_thread) {
    storage.max_buffered_bytes = std::size_t{4} << 20;
    storage.compressor_core = options.output_thread_core;  // beside the output thread, off the rank's core
  }
  auto file = resumed ? h5::H5SeriesWriter::reopen(options.output_path, static_cast<std::size_t>(resumed->sample + 1),
                                                   resumed->unwritten_rows, storage, resumed->partial_crc)
                      : h5::H5SeriesWriter::create(options.output_path, storage);
  if (options.shared_output)  // the segment diagnostics: written by every rank together
    file.share_series_with([shared = options.shared_output, path = file.partial_path()](std::vector<h5::SharedRows>& rows) {
      shared->write(path, rows);
    });
  file.set_attribute("/", "scene_text", scene.text);
  file.set_attribute("/", "scene_source", scene.source);
  // --set section.key=VALUE, one per line as given (applied over scene_text)
  if (!scene.overrides.empty()) file.set_attribute("/", "scene_overrides", scene_overrides_text(scene));
  file.set_attribute("/", "layout_version", kOutputLayoutVersion);
  for (const auto& [name, value] : build_info(options.mpi_library)) file.set_attribute("/", name, value);
  file.set_attribute("/", "model", model.describe());
  write_bearing_attributes(file, model, scene);
  return file;
}

/// The checkpoint to continue from, or none (a fresh run). Says which through on_info; a checkpoint
/// of an earlier run is removed when the run starts fresh, so that it can never be matched with the
/// new run's .partial file.
std::optional<Checkpoint> checkpoint_to_resume(const RunOptions& options, const RunFingerprint& now) {
  const std::string path = checkpoint_path(options.output_path);
  auto say = [&](const std::string& s) {
    if (options.on_info) options.on_info(s);
  };
  if (!options.resume) {
    std::error_code ec;
    if (std::filesystem::remove(path, ec))
      say(fmt::format("discarded the checkpoint of an earlier run ({}); --resume would have continued it", path));
    return std::nullopt;
  }
  std::optional<Checkpoint> cp = read_checkpoint(path);
  if (!cp) {
    say(fmt::format("--resume: no checkpoint of {} ({}): starting from the beginning", options.output_path, path));
    return std::nullopt;
  }
  require_same_run(cp->fingerprint, now, path);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(options.output_path + ".partial", ec))
    throw ResumeRefused(fmt::format("cannot resume: the checkpoint {} belongs to {}.partial, which is missing; run "
                                    "without --resume to start again", path, options.output_path));
  say(fmt::format("resuming {} from its {} checkpoint at t = {:.9g} s (output sample {}){}", options.output_path,
                  checkpoint_kind_name(cp->kind), cp->time, cp->sample,
                  cp->kind == CheckpointKind::periodic
                      ? ""
                      : ": CVODE restarts there, so the rest agrees with an uninterrupted run to the tolerances, "
                        "not bitwise"));
  return cp;
}

/// The last output sample of the run (samples 0..this).
long run_samples(const scene::Scene& scene) {
  return std::lround(std::floor(scene.scene.end_time / scene.scene.output_interval + 1e-9));
}

/// When checkpoints are due: every `every` output samples (periodic, CVODE restarts), after
/// `wall_interval` seconds of wall clock, and at a stop signal; never at the last sample (the run
/// ends there and commits its output).
struct CheckpointPlan {
  long every = 0;            // output samples; 0: no periodic checkpoints
  double wall_interval = 0;  // s; 0: none
  const std::atomic<int>* stop_signal = nullptr;

  std::optional<CheckpointKind> due(long sample, long samples, double wall_since_last) const {
    if (sample >= samples) return std::nullopt;
    if (stop_signal && stop_signal->load(std::memory_order_relaxed) != 0) return CheckpointKind::signal;
    if (every > 0 && sample % every == 0) return CheckpointKind::periodic;
    if (wall_interval > 0 && wall_since_last >= wall_interval) return CheckpointKind::wall_clock;
    return std::nullopt;
  }
};

bearing::StartupReport startup_naming_keys(const bearing::Model& model, const scene::Scene& scene, double t0, double azimuth_offset,
                                  bearing::Equations& eq);

/// One run from its first sample (0, or the one after a checkpoint) to the end: integration, output
/// samples, checkpoints and the summary.
class RunLoop {
 public:
  RunLoop(const scene::Scene& scene, const RunOptions& options, const bearing::Model& model, bearing::Equations& eq,
          scheduler::Executor& executor, const RunFingerprint& fingerprint)
      : scene_(scene), options_(options), model_(model), eq_(eq), executor_(executor), fingerprint_(fingerprint),
        dt_(scene.scene.output_interval), samples_(run_samples(scene)),
        plan_{scene.output.checkpoint_interval > 0 ? std::max(1L, std::lround(scene.output.checkpoint_interval / dt_))
                                                   : 0,
              scene.output.checkpoint_wall_interval, options.stop_signal},
        totals_(model, scene.scene.end_time), pockets_(model), power_(model), sensor_(model, dt_) {}

  RunSummary run(const std::optional<Checkpoint>& resumed);

 private:
  double wall() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  void record(double t, long sample);
  /// The output of one sample: the right-hand side at (t, z) for the diagnostics on `eq`, the rows,
  /// the summary's sums (on the output thread, or on this one with the parallel output). Returns the
  /// right-hand side's wall seconds.
  double write_sample(bearing::Equations& eq, double t, long sample, const std::vector<double>& z, std::vector<double>& zdot,
                      const std::vector<double>& pocket_row);
  /// A new integrator from (t, z), its accepted steps observed by the pocket statistics.
  void start_integrator(double t);
  /// Waits for the output thread's samples (before anything reads the file, the sums or the counts).
  void drain_output(bool rethrow = true);
  void start_output_thread();  // and binds it to options_.output_thread_core
  void checkpoint(CheckpointKind kind, long sample, double t);
  /// The summary into the file (after the output thread's samples; their failure is rethrown if
  /// `rethrow`, else left to the failure being reported).
  RunSummary finish(double t, bool rethrow = true);

  const scene::Scene& scene_;
  const RunOptions& options_;
  const bearing::Model& model_;
  bearing::Equations& eq_;
  scheduler::Executor& executor_;
  const RunFingerprint& fingerprint_;
  const double dt_;
  const long samples_;
  const CheckpointPlan plan_;
  const std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  RunTotals totals_;
  // The step-resolved pocket statistics (solver/run/pocket_steps.hpp), on the run's thread; the row
  // of each sample goes to the output with it.
  PocketSteps pockets_;
  // The power balance over the steps (solver/run/power_balance.hpp), on the run's thread; its row
  // of each sample goes to the output after the pocket statistics' and the sensor's.
  PowerBalance power_;
  // The housing's sensor (solver/run/housing_sensor.hpp): its samples of each interval go to the
  // output with the pocket statistics' row.
  HousingSensor sensor_;
  std::vector<double> pocket_row_;
  std::optional<h5::H5SeriesWriter> file_;
  std::optional<OutputWriter> out_;
  std::unique_ptr<numerics::Integrator> integrator_;
  // [solver] automatic_order: BDF's largest order chosen during the run (solver/numerics/order_choice.hpp);
  // kept across the integrator's restarts and in the checkpoints.
  std::optional<numerics::OrderChoice> order_choice_;
  void log_order_switches();
  std::vector<double> z_, zdot_, restart_times_;
  double output_seconds_ = 0, last_checkpoint_wall_ = 0;
  double diagnostics_seconds_ = 0;  // of output_seconds_: the right-hand sides at output times
  // The output thread's own equations (the same tasks, evaluated there in full on a serial
  // executor: the same records bit for bit) and the thread. Without them (the parallel output, whose
  // workers keep the diagnostics of the right-hand side they evaluated) the run's thread writes.
  scheduler::SerialExecutor sample_executor_;
  std::unique_ptr<bearing::Equations> sample_eq_;
  std::vector<double> sample_zdot_;
  std::unique_ptr<OutputThread> output_thread_;  // after what its work uses: it ends first
};

double RunLoop::write_sample(bearing::Equations& eq, double t, long sample, const std::vector<double>& z,
                             std::vector<double>& zdot, const std::vector<double>& pocket_row) {
  // Each body's kinematics once for the sample: its right-hand side's, kept for its rows.
  const bearing::KinematicsMemo memo(eq.model(), t, z.data());
  const double before = wall();
  eq.rhs(t, z.data(), zdot.data());
  const double rhs_seconds = wall() - before;
  const double e = eq.energy(t, z.data());
  // The parallel output's workers keep their diagnostics only of the samples that store them.
  const std::vector<int>* segment_rank =
      options_.shared_output && out_->stores_segments(sample) ? &options_.shared_output->sample(sample) : nullptr;
  out_->append(t, z, zdot, eq, e, pocket_row, sample, segment_rank);
  totals_.record(t, z, eq, e);
  return rhs_seconds;
}

void RunLoop::record(double t, long sample) {
  const double before = wall();
  totals_.turn_to(t);
  pockets_.take_row(t, pocket_row_);
  sensor_.take_row(sample, pocket_row_);
  power_.take_row(t, pocket_row_);
  if (output_thread_) {
    output_thread_->submit(t, sample, z_, pocket_row_);
  } else {
    diagnostics_seconds_ += write_sample(eq_, t, sample, z_, zdot_, pocket_row_);
  }
  output_seconds_ += wall() - before;
}

void RunLoop::drain_output(bool rethrow) {
  if (!output_thread_) return;
  const double before = wall();
  output_thread_->drain(rethrow);
  output_seconds_ += wall() - before;
}

void RunLoop::checkpoint(CheckpointKind kind, long sample, double t) {
  drain_output();
  const double before = wall();
  file_->flush();  // first the rows, then the checkpoint that names them
  Checkpoint cp{kind, sample, t, z_, {}, restart_times_, file_->unwritten_rows(), fingerprint_, file_->row_checksums()};
  totals_.save(cp, integrator_->statistics(), eq_, executor_, wall());
  pockets_.save(cp);
  power_.save(cp);
  if (order_choice_) order_choice_->save(cp.values);
  write_checkpoint(checkpoint_path(options_.output_path), cp);
  if (kind == CheckpointKind::periodic) {  // every run restarts CVODE here: a resume repeats it bitwise
    totals_.add_finished_integrator(integrator_->statistics());
    pockets_.restart();  // the steps past t are integrated again
    power_.restart();
    start_integrator(t);
  }
  last_checkpoint_wall_ = wall();
  output_seconds_ += last_checkpoint_wall_ - before;
}

RunSummary RunLoop::finish(double t, bool rethrow) {
  drain_output(rethrow);
  RunSummary sum;
  sum.model_kind = model_.kind == scene::ModelKind::spatial ? "spatial" : "planar";
  sum.spatial_rollers = model_.kind == scene::ModelKind::spatial && !model_.params().bearing.is_ball_bearing();
  totals_.summarize(sum, t, integrator_->statistics(), eq_, executor_, wall());
  // The integrator since the last restart (a checkpoint restarts it): its method, the states that
  // limit its step and the split of its time.
  sum.method = integrator_->method_name();
  sum.order_choice = order_choice_ ? order_choice_->description()
                                   : fmt::format("fixed: max_order = {}", scene_.solver.max_order);
  sum.step_limiting = step_limiting_classes(model_, integrator_->step_limiting_states());
  sum.timing = integrator_->timing();
  sum.output_seconds = output_seconds_;
  sum.output_write_seconds = output_seconds_ - diagnostics_seconds_;
  sum.output_thread_seconds = output_thread_ ? output_thread_->busy_seconds() : 0.0;
  sum.pocket_step_totals = pockets_.totals_json();
  sum.power_balance = power_.summary_json(0.0, t, totals_.stored_energy_initial(), totals_.stored_energy_final());
  if (const bearing::ThermalNetwork* network = bearing::thermal_network_of(model_)) {
    json::JsonObject temperatures;
    for (int k = 0; k < bearing::ThermalNetwork::parts; ++k)
      temperatures.add(bearing::ThermalNetwork::part_names[k], z_[static_cast<std::size_t>(network->state(k))]);
    sum.thermal.add("final_temperature_k", std::move(temperatures));
  }
  sum.scene_overrides = scene_overrides_json(scene_);
  sum.scene_parameters = scene_parameters_json(scene_);
  sum.warnings = regime_warnings(sum);
  file_->set_attribute("/", "summary_json", sum.to_json().dump());
  // The scheduler's arrays get what [output] max_size leaves after the rest of the file's estimate.
  if (const auto* log = executor_.schedule_log(); log && (log->ranks > 1 || options_.scheduler_log))
    write_schedule_log(*file_, *log, scene_.output.max_size - estimate_output(model_, scene_).total());
  return sum;
}

void RunLoop::log_order_switches() {
  if (!order_choice_) return;
  for (const numerics::OrderSwitch& sw : order_choice_->take_switches())
    if (options_.on_info)
      options_.on_info(fmt::format("automatic order: BDF order at most {} from t = {:.6g} s (it advanced {:.3g} s per "
                                   "unit of work against {:.3g} s at the order left)",
                                   sw.to_order, sw.time, sw.probe_rate, sw.current_rate));
}

void RunLoop::start_integrator(double t) {
  integrator_ = std::make_unique<numerics::Integrator>(eq_, scene_.solver, t, z_);
  if (order_choice_) integrator_->set_order_choice(&*order_choice_);
  // The last right-hand side of an accepted step is the integrator's own: a sample's (write_sample
  // on eq_) comes after advance_to() returns, and every step evaluates the right-hand side again.
  sensor_.restart(t);
  integrator_->set_step_observer([this] {
    if (pockets_.active()) pockets_.observe(eq_.last_rhs_time(), eq_.segment_records());
    power_.observe(eq_);
    if (sensor_.active()) sensor_.observe(*integrator_);
  });
}

void RunLoop::start_output_thread() {
  output_thread_ = std::make_unique<OutputThread>(
      z_.size(),
      [this](double t, long sample, const std::vector<double>& z, const std::vector<double>& pocket_row) {
        write_sample(*sample_eq_, t, sample, z, sample_zdot_, pocket_row);
      },
      // Up to 1024 samples queued (the run's thread waits only when the output thread is that far
      // behind: on a loaded machine it is descheduled for tens of ms), at most 64 MiB of states.
      std::clamp<std::size_t>((std::size_t{64} << 20) / (sizeof(double) * z_.size()), 16, 1024));
  const int core = options_.output_thread_core;
  if (core < 0) return;
  const std::string bound = output_thread_->bind_to_core(core);
  if (!options_.on_info) return;
  options_.on_info(bound.empty()
                       ? fmt::format("output thread: binding it to core {} was refused; it runs where the process may", core)
                       : fmt::format("output thread bound to core {} (its affinity read back: {})", core, bound));
}

RunSummary RunLoop::run(const std::optional<Checkpoint>& resumed) {
  const double t0 = 0.0;
  long first = 1;  // the first sample integrated to
  if (!options_.shared_output && options_.output_thread) {
    sample_eq_ = std::make_unique<bearing::Equations>(model_, sample_executor_);
    sample_executor_.attach(sample_eq_->task_catalogue());
    sample_zdot_.resize(static_cast<std::size_t>(model_.state_size));
    totals_.count_also(*sample_eq_, sample_executor_);
  }
  if (scene_.solver.automatic_order) {
    order_choice_.emplace(t0, numerics::OrderChoiceSettings{.high_order = scene_.solver.max_order});
    if (resumed) order_choice_->restore(resumed->values);
    if (options_.on_info)
      options_.on_info(resumed ? "automatic order: continues from the checkpoint: " + order_choice_->description()
                               : fmt::format("automatic order: BDF order at most {}, probing order 2 after {} steps",
                                             scene_.solver.max_order, numerics::OrderChoiceSettings{}.first_probe));
  }
  if (resumed) {
    totals_.restore(*resumed, eq_, executor_);
    pockets_.restore(*resumed);
    power_.restore(*resumed);
    z_ = resumed->state, first = resumed->sample + 1, restart_times_ = resumed->restart_times;
    if (resumed->kind != CheckpointKind::periodic) restart_times_.push_back(resumed->time);
  } else {
    const bearing::StartupReport start = startup_naming_keys(model_, scene_, t0, options_.azimuth_offset, eq_);
    if (options_.on_info) options_.on_info(start.summary);
    z_ = start.state;
    // The power balance's first evaluation: the terms at the start (the steps' evaluations follow).
    std::vector<double> zdot(z_.size());
    eq_.rhs(t0, z_.data(), zdot.data());
    power_.observe(eq_);
  }
  zdot_.resize(z_.size());
  double t_last = resumed ? resumed->time : t0;
  try {
    file_.emplace(open_run_output(scene_, options_, eq_, resumed ? &*resumed : nullptr));
    out_.emplace(*file_, model_, scene_.output.segments, options_.shared_output != nullptr, scene_.output.segment_every);
  } catch (const std::runtime_error& e) {
    if (!resumed || dynamic_cast<const scene::SceneError*>(&e) || dynamic_cast<const numerics::OptionsError*>(&e)) throw;
    // The .partial file does not continue (missing rows, a damaged chunk, rows whose checksum is
    // not the checkpoint's): a refused resume, exit 2, nothing more written.
    throw ResumeRefused(fmt::format("cannot resume from {}: {}; run without --resume to start again",
                                    checkpoint_path(options_.output_path), e.what()));
  }
  file_->set_attribute("/", "restart_times", restart_times_);
  // The layout in the file: from here on the .partial file is readable after the process is
  // killed. A fresh run does not wait for the disk here: a power loss now loses nothing a resume
  // could use (there is no checkpoint yet); a resumed file holds the rows of the earlier runs.
  file_->flush(resumed.has_value());
  if (options_.on_info)
    options_.on_info(fmt::format("output {} {}: readable from here on, also after a kill", file_->partial_path(),
                                 resumed ? "reopened" : "laid out"));
  if (sample_eq_) start_output_thread();
  start_integrator(t_last);
  last_checkpoint_wall_ = wall();
  if (!resumed) record(t0, 0);
  for (long i = first; i <= samples_; ++i) {
    const double t = t0 + static_cast<double>(i) * dt_;
    try {
      integrator_->advance_to(t, z_);
    } catch (const numerics::IntegrationFailure&) {
      finish(t_last, false);
      file_->flush();
      throw;  // the .partial file stays, the previous output is untouched
    }
    log_order_switches();
    record(t, i);
    t_last = t;
    if (options_.on_progress)
      options_.on_progress({t, scene_.scene.end_time, totals_.revolutions(), wall(),
                            totals_.steps(integrator_->statistics())});
    const auto kind = plan_.due(i, samples_, wall() - last_checkpoint_wall_);
    if (!kind) continue;
    checkpoint(*kind, i, t);
    if (*kind != CheckpointKind::signal) continue;
    finish(t);
    file_->flush();
    throw RunInterrupted(fmt::format("stopped by signal {} at t = {:.9g} s (output sample {} of {}): checkpoint written; "
                                     "continue with raceway run ... -o {} --resume",
                                     options_.stop_signal->load(), t, i, samples_, options_.output_path));
  }
  drain_output();
  const double before_commit = wall();
  RunSummary sum = finish(t_last);
  std::error_code ec;
  std::filesystem::remove(checkpoint_path(options_.output_path), ec);  // first: never a checkpoint without its .partial
  file_->commit();
  sum.output_seconds = output_seconds_ + (wall() - before_commit);
  sum.output_write_seconds = sum.output_seconds - diagnostics_seconds_;
  return sum;
}

/// The start-up state; a start-up that fails names the scene keys that set it (file, lines).
bearing::StartupReport startup_naming_keys(const bearing::Model& model, const scene::Scene& scene, double t0, double azimuth_offset,
                                  bearing::Equations& eq) {
  try {
    return initial_state(model, t0, azimuth_offset, &eq);  // its contacts through the executor
  } catch (const std::runtime_error& e) {
    static constexpr std::string_view keys[] = {
        "bearing.radial_clearance", "inner_ring.motion", "outer_ring.motion", "inner_ring.translation",
        "outer_ring.translation", "inner_ring.axial", "outer_ring.axial", "inner_ring.tilt", "outer_ring.tilt",
        "inner_ring.load", "outer_ring.load", "inner_ring.support", "outer_ring.support", "inner_ring.speed",
        "outer_ring.speed", "scene.gravity"};
    const std::string named = scene::keys_with_lines(scene, keys);
    throw scene::SceneError(scene.source, 0, "",
                         fmt::format("{}; the keys that set the start-up: {}", e.what(),
                                     named.empty() ? "none given (the defaults of [bearing] and the rings)" : named));
  }
}

}  // namespace

RunSummary run_scene(const scene::Scene& scene, const RunOptions& options) {
  h5::check_output_path(options.output_path, "output file (-o)");
  const h5::OutputLock lock(options.output_path);  // before anything of the output is touched
  const bearing::Model model = bearing::build_model(scene);
  check_output_size(estimate_output(model, scene), scene);  // before any work or file
  scheduler::SerialExecutor serial;
  scheduler::Executor& executor = options.executor ? *options.executor : serial;
  bearing::Equations eq(model, executor);
  executor.attach(eq.task_catalogue());
  // The overrides are part of the scene: a resume with other ones is refused at their line.
  const RunFingerprint fingerprint{scene.text + scene::overrides_as_comments(scene.overrides), build_fingerprint(options.mpi_library), options.result_options};
  const std::optional<Checkpoint> resumed = checkpoint_to_resume(options, fingerprint);
  if (resumed)
    require_fits(*resumed, static_cast<std::size_t>(model.state_size), run_samples(scene),
                 scene.scene.output_interval, checkpoint_path(options.output_path));
  RunLoop loop(scene, options, model, eq, executor, fingerprint);
  return loop.run(resumed);
}

void serve_scene(const scene::Scene& scene,
                 const std::function<void(const scheduler::TaskCatalogue&, const std::map<std::string, SegmentSeries>&)>& serve) {
  // The equations need an executor, but a worker's never call run(): their tasks are called by
  // `serve` with the master's context.
  scheduler::SerialExecutor unused;
  const bearing::Model model = bearing::build_model(scene);
  const bearing::Equations eq(model, unused);
  auto series = segment_series(model);
  for (auto& [path, one] : series) one.stride = scene.output.segment_every;
  serve(eq.task_catalogue(), series);
}

}  // namespace raceway::run
