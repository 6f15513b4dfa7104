// The output loop shared by the planar and the spatial run (solver/run.cpp, solver/spatial_run.cpp):
// integrate to each output time, record it, keep the summary's running figures, and on an
// integration failure write what is known and keep the .partial file. What differs between the
// models (what an output sample writes, what the summary averages) comes in as a RunRecorder.
#pragma once

#include <chrono>
#include <cmath>
#include <functional>
#include <numbers>
#include <utility>
#include <vector>

#include "io/h5/h5_series.hpp"
#include "raceway/version.hpp"
#include "io/scene/scene.hpp"
#include "scheduler/executor.hpp"
#include "solver/numerics/integrator.hpp"
#include "solver/numerics/newton_backends.hpp"
#include "solver/run/run.hpp"
#include "solver/run/schedule_output.hpp"

namespace raceway::solver {

struct RunRecorder {
  /// Writes output time t; rhs at (t, z) has just filled zdot and the segment records.
  std::function<void(double t, const std::vector<double>& z, const std::vector<double>& zdot, double energy)> append;
  /// A sample of the run's second half: accumulates the model's own figures and returns the cage
  /// speed and the epicyclic cage speed [rad/s].
  std::function<std::pair<double, double>(double t, const std::vector<double>& z)> second_half;
  /// Writes the means of the model's own figures over `count` second-half samples into the summary.
  std::function<void(RunSummary& sum, int count)> summarize;
};

/// Checks the Newton linear solver (and PETSc's options) before any output exists, then creates
/// the output (OUT.h5.partial) with the attributes every run has.
template <class Equations>
io::H5SeriesWriter open_run_output(const io::Scene& scene, const RunOptions& options, const Equations& eq,
                                   const std::string& model_description) {
  const std::string solver_line =
      prepare_linear_solver(scene.solver, {eq.border_size(), eq.block_count(), eq.block_size()});
  if (options.on_info) options.on_info(solver_line);
  auto file = io::H5SeriesWriter::create(options.output_path);
  file.set_attribute("/", "scene_text", scene.text);
  file.set_attribute("/", "scene_source", scene.source);
  file.set_attribute("/", "raceway_version", std::string(kVersion));
  file.set_attribute("/", "raceway_commit", std::string(kGitCommit));
  file.set_attribute("/", "model", model_description);
  return file;
}

/// Integrates from z to the scene's end time with output every output_interval and returns the
/// summary (started as `sum`). `wall_start` is when the run began (model building included).
template <class Equations>
RunSummary record_run(const io::Scene& scene, const RunOptions& options, Equations& eq, scheduler::Executor& executor,
                      Integrator& integrator, io::H5SeriesWriter& file, std::vector<double> z, RunSummary sum,
                      std::chrono::steady_clock::time_point wall_start, const RunRecorder& recorder) {
  constexpr double rpm = 30.0 / std::numbers::pi;
  auto wall = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count(); };
  const double t0 = 0.0, end = scene.scene.end_time, dt = scene.scene.output_interval;
  const long samples = std::lround(std::floor(end / dt + 1e-9));
  const io::RingSpec& drive = scene.inner_ring.motion == io::RingMotion::driven ? scene.inner_ring : scene.outer_ring;
  std::vector<double> zdot(z.size());
  double cage_sum = 0, epi_sum = 0, revolutions = 0, last_t = t0;
  int half_count = 0;

  auto record = [&](double t) {
    eq.rhs(t, z.data(), zdot.data());
    const double e = eq.energy(t, z.data());
    if (sum.output_samples == 0) sum.energy_initial_j = e;
    sum.energy_final_j = e;
    sum.energy_max_drift_j = std::max(sum.energy_max_drift_j, std::abs(e - sum.energy_initial_j));
    recorder.append(t, z, zdot, e);
    ++sum.output_samples;
    if (drive.motion == io::RingMotion::driven)
      revolutions += 0.5 * (drive.speed(last_t) + drive.speed(t)) * (t - last_t) / (2 * std::numbers::pi);
    last_t = t;
    if (t >= 0.5 * end - 1e-12) {
      const auto [cage, epicyclic] = recorder.second_half(t, z);
      cage_sum += cage, epi_sum += epicyclic;
      ++half_count;
    }
  };
  auto finish = [&](double t) {
    sum.stats = integrator.statistics();
    sum.simulated_time_s = t;
    sum.wall_time_s = wall();
    sum.model_rhs_evaluations = eq.rhs_evaluations();
    sum.model_jacobian_evaluations = eq.jacobian_evaluations();
    sum.segment_evaluations = eq.segment_evaluations();
    sum.rhs_seconds = executor.total_seconds(scheduler::Phase::rhs);
    sum.jacobian_seconds = executor.total_seconds(scheduler::Phase::jacobian);
    sum.driven_ring_revolutions = revolutions;
    if (half_count > 0) {
      sum.cage_speed_rpm = cage_sum / half_count * rpm;
      sum.epicyclic_cage_speed_rpm = epi_sum / half_count * rpm;
      sum.cage_slip = sum.epicyclic_cage_speed_rpm != 0 ? 1.0 - sum.cage_speed_rpm / sum.epicyclic_cage_speed_rpm : 0.0;
      recorder.summarize(sum, half_count);
    }
    file.set_attribute("/", "summary_json", sum.to_json().dump());
    if (const auto* log = executor.schedule_log()) write_schedule_log(file, *log);
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

}  // namespace raceway::solver
