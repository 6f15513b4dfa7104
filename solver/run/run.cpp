// One simulation from a validated scene to an output file (docs/output_layout.md) and a summary:
// model, start-up state, CVODE, output at fixed times by interpolation. One loop for every bearing
// kind; what a sample writes comes from the output table (solver/run/output_writer.hpp).
#include "solver/run/run.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "io/h5/h5_series.hpp"
#include "io/scene/scene_parser.hpp"
#include "raceway/version.hpp"
#include "io/h5/output_lock.hpp"
#include "solver/run/build_info.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/run/output_writer.hpp"
#include "solver/run/schedule_output.hpp"

namespace raceway::solver {

using contact::Vec3;

io::JsonObject RunSummary::to_json() const {
  io::JsonObject j;
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
  j.add("cage_slip", cage_slip);
  j.add("driven_ring_revolutions", driven_ring_revolutions);
  j.add("inner_ring_contact_force_n", inner_ring_contact_force_n);
  j.add("inner_ring_load_n", inner_ring_load_n);
  if (model_kind == "spatial") j.add("max_ball_load_n", max_ball_load_n);
  j.add("model_kind", model_kind);
  j.add("energy_initial_j", energy_initial_j);
  j.add("energy_final_j", energy_final_j);
  j.add("energy_max_drift_j", energy_max_drift_j);
  j.add("output_samples", static_cast<long long>(output_samples));
  j.add("method", method);
  j.add("step_limiting_states", step_limiting_json(step_limiting));
  j.add("time_split_s", time_split_json(timing, output_seconds, wall_time_s));
  return j;
}

namespace {

/// Checks the Newton linear solver (and PETSc's options) before any output exists, then creates
/// the output (OUT.h5.partial) with the attributes every run has.
io::H5SeriesWriter open_run_output(const io::Scene& scene, const RunOptions& options, const Equations& eq) {
  const std::string solver_line =
      prepare_linear_solver(scene.solver, {eq.border_size(), eq.block_count(), eq.block_size()});
  if (options.on_info) options.on_info(solver_line);
  const Model& model = eq.model();
  auto file = io::H5SeriesWriter::create(options.output_path);
  file.set_attribute("/", "scene_text", scene.text);
  file.set_attribute("/", "scene_source", scene.source);
  file.set_attribute("/", "layout_version", kOutputLayoutVersion);
  for (const auto& [name, value] : build_info(options.mpi_library)) file.set_attribute("/", name, value);
  file.set_attribute("/", "model", model.describe());
  if (model.kind == io::ModelKind::spatial) {
    file.set_attribute("/", "model_kind", std::string("spatial"));
    file.set_attribute("/", "ball_count", static_cast<long long>(model.element_count));
    file.set_attribute("/", "pitch_radius", model.pitch_radius);
    file.set_attribute("/", "pocket_clearance", scene.cage.pocket_clearance);
    file.set_attribute("/", "land_clearance",
                       model.first_segment(SegmentKind::cage_land) ? scene.cage.land_clearance : 0.0);
  }
  return file;
}

/// The summary's figures of the run's second half, accumulated over the output samples.
class SecondHalf {
 public:
  explicit SecondHalf(const Model& m) : m_(m) {}

  void add(double t, const std::vector<double>& z, const Equations& eq) {
    force_sum_ += eq.contact_loads()[static_cast<std::size_t>(m_.inner_ring)].force;
    const auto& l = m_.scene->inner_ring.load;
    load_sum_ += Vec3(l.fx(t), l.fy(t), l.fz(t));
    constexpr int normal_force = contact::field_index(contact::point_diagnostic_fields, "normal_force");
    std::vector<double> element_load(static_cast<std::size_t>(m_.element_count), 0.0);
    for (std::size_t s = 0; s < m_.segments.size(); ++s)
      if (m_.segments[s].kind == SegmentKind::ball_inner_groove)
        element_load[static_cast<std::size_t>(m_.segments[s].element)] += eq.diagnostic(s, normal_force);
    for (double q : element_load) max_element_load_ = std::max(max_element_load_, q);
    const std::vector<double> none(z.size(), 0.0);
    cage_sum_ += sample_body(m_, m_.cage, t, z, none, Wrench{}).angular_velocity.z();
    epicyclic_sum_ += m_.epicyclic_cage_speed(t);
    ++count_;
  }

  void summarize(RunSummary& sum) const {
    if (count_ == 0) return;
    constexpr double rpm = 30.0 / std::numbers::pi;
    sum.cage_speed_rpm = cage_sum_ / count_ * rpm;
    sum.epicyclic_cage_speed_rpm = epicyclic_sum_ / count_ * rpm;
    sum.cage_slip = sum.epicyclic_cage_speed_rpm != 0 ? 1.0 - sum.cage_speed_rpm / sum.epicyclic_cage_speed_rpm : 0.0;
    sum.max_ball_load_n = max_element_load_;
    const int dims = m_.kind == io::ModelKind::spatial ? 3 : 2;
    for (int d = 0; d < dims; ++d) {
      sum.inner_ring_contact_force_n.push_back(force_sum_[d] / count_);
      sum.inner_ring_load_n.push_back(load_sum_[d] / count_);
    }
  }

 private:
  const Model& m_;
  Vec3 force_sum_ = Vec3::Zero(), load_sum_ = Vec3::Zero();
  double cage_sum_ = 0, epicyclic_sum_ = 0, max_element_load_ = 0;
  int count_ = 0;
};

/// Counters and times of the run into the summary, which is stored as the file's summary_json.
void finish_summary(RunSummary& sum, double t, const Integrator& integrator, const Equations& eq,
                    scheduler::Executor& executor, double wall_seconds) {
  sum.stats = integrator.statistics();
  sum.method = integrator.method_name();
  sum.step_limiting = step_limiting_classes(eq.model(), integrator.step_limiting_states());
  sum.timing = integrator.timing();
  sum.simulated_time_s = t;
  sum.wall_time_s = wall_seconds;
  sum.model_rhs_evaluations = eq.rhs_evaluations();
  sum.model_jacobian_evaluations = eq.jacobian_evaluations();
  sum.segment_evaluations = eq.segment_evaluations();
  sum.rhs_seconds = executor.total_seconds(scheduler::Phase::rhs);
  sum.jacobian_seconds = executor.total_seconds(scheduler::Phase::jacobian);
}

/// The start-up state; a start-up that fails names the scene keys that set it (file, lines).
StartupReport startup_naming_keys(const Model& model, const io::Scene& scene, double t0, double azimuth_offset) {
  try {
    return initial_state(model, t0, azimuth_offset);
  } catch (const std::runtime_error& e) {
    static constexpr std::string_view keys[] = {
        "bearing.radial_clearance", "inner_ring.motion", "outer_ring.motion", "inner_ring.translation",
        "outer_ring.translation", "inner_ring.axial", "outer_ring.axial", "inner_ring.tilt", "outer_ring.tilt",
        "inner_ring.load", "outer_ring.load", "inner_ring.support", "outer_ring.support", "inner_ring.speed",
        "outer_ring.speed", "scene.gravity"};
    const std::string named = io::keys_with_lines(scene, keys);
    throw io::SceneError(scene.source, 0, "",
                         fmt::format("{}; the keys that set the start-up: {}", e.what(),
                                     named.empty() ? "none given (the defaults of [bearing] and the rings)" : named));
  }
}

}  // namespace

RunSummary run_scene(const io::Scene& scene, const RunOptions& options) {
  io::check_output_path(options.output_path, "output file (-o)");
  const io::OutputLock lock(options.output_path);  // before anything of the output is touched
  const auto wall_start = std::chrono::steady_clock::now();
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(); };
  const Model model = build_model(scene);
  check_output_size(estimate_output(model, scene), scene);  // before any work or file
  scheduler::SerialExecutor serial;
  scheduler::Executor& executor = options.executor ? *options.executor : serial;
  Equations eq(model, executor);
  executor.attach(eq.task_catalogue());
  const double t0 = 0.0, end = scene.scene.end_time, dt = scene.scene.output_interval;
  const StartupReport start = startup_naming_keys(model, scene, t0, options.azimuth_offset);
  if (options.on_info) options.on_info(start.summary);

  auto file = open_run_output(scene, options, eq);
  OutputWriter out(file, model, scene.output.segments);
  file.flush();  // the layout on disk: from here on the .partial file is readable after any kill
  Integrator integrator(eq, scene.solver, t0, start.state);
  RunSummary sum;
  sum.model_kind = model.kind == io::ModelKind::spatial ? "spatial" : "planar";
  SecondHalf second_half(model);
  const long samples = std::lround(std::floor(end / dt + 1e-9));
  const io::RingSpec& drive = scene.inner_ring.motion == io::RingMotion::driven ? scene.inner_ring : scene.outer_ring;
  std::vector<double> z = start.state, zdot(z.size());
  double revolutions = 0, last_t = t0;

  auto record = [&](double t) {
    const auto record_start = std::chrono::steady_clock::now();
    eq.rhs(t, z.data(), zdot.data());
    const double e = eq.energy(t, z.data());
    if (sum.output_samples == 0) sum.energy_initial_j = e;
    sum.energy_final_j = e;
    sum.energy_max_drift_j = std::max(sum.energy_max_drift_j, std::abs(e - sum.energy_initial_j));
    out.append(t, z, zdot, eq, e);
    ++sum.output_samples;
    if (drive.motion == io::RingMotion::driven)
      revolutions += 0.5 * (drive.speed(last_t) + drive.speed(t)) * (t - last_t) / (2 * std::numbers::pi);
    last_t = t;
    if (t >= 0.5 * end - 1e-12) second_half.add(t, z, eq);
    sum.output_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - record_start).count();
  };
  auto finish = [&](double t) {
    finish_summary(sum, t, integrator, eq, executor, wall());
    sum.driven_ring_revolutions = revolutions;
    second_half.summarize(sum);
    file.set_attribute("/", "summary_json", sum.to_json().dump());
    if (const auto* log = executor.schedule_log(); log && (log->ranks > 1 || options.scheduler_log))
      write_schedule_log(file, *log);
  };

  record(t0);
  for (long i = 1; i <= samples; ++i) {
    const double t = t0 + static_cast<double>(i) * dt;
    try {
      integrator.advance_to(t, z);
    } catch (const IntegrationFailure&) {
      finish(last_t);
      file.flush();
      throw;  // the .partial file stays, the previous output is untouched
    }
    record(t);
    if (options.on_progress) options.on_progress({t, end, revolutions, wall(), integrator.statistics().steps});
  }
  finish(last_t);
  file.commit();
  return sum;
}

void serve_scene(const io::Scene& scene, const std::function<void(const scheduler::TaskCatalogue&)>& serve) {
  // The equations need an executor, but a worker's never call run(): their tasks are called by
  // `serve` with the master's context.
  scheduler::SerialExecutor unused;
  const Model model = build_model(scene);
  const Equations eq(model, unused);
  serve(eq.task_catalogue());
}

}  // namespace raceway::solver
