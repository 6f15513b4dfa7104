#include "solver/run/run.hpp"
#include "solver/run/run_loop.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "io/h5/h5_series.hpp"
#include "solver/run/schedule_output.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/spatial_equations.hpp"
#include "solver/bearing/startup.hpp"

namespace raceway::solver {

using contact::Component;

namespace {


const char* diagnostic_names[contact::diagnostics_count] = {
    "approach", "normal_force", "traction_force", "slip_velocity", "elastic_energy", "power_loss"};
const char* diagnostic_units[contact::diagnostics_count] = {"m", "N", "N", "m/s", "J", "W"};
const char* diagnostic_docs[contact::diagnostics_count] = {
    "approach of the two surfaces (> 0 in contact)", "normal contact force (>= 0)",
    "tangential force on body B along the segment tangent", "sliding velocity of B's surface relative to A's",
    "elastic energy stored in the contact", "power dissipated by traction and damping"};

/// Writes the model-dependent output layout (docs/output_layout.md) and appends samples.
class OutputWriter {
 public:
  OutputWriter(io::H5SeriesWriter& file, const Model& m, bool segments) : file_(file), m_(m), segments_(segments) {
    file_.define_series("/time", {1}, "s", "output times (interpolated, not solver steps)");
    file_.define_series("/energy", {1}, "J", "total mechanical energy (kinetic + elastic + load potential)");
    for (int b = 0; b < m.first_roller; ++b) {
      const std::string g = "/" + m.bodies[b].name;
      file_.define_series(g + "/position", {2}, "m", "centre x, y in the bearing frame");
      file_.define_series(g + "/velocity", {2}, "m/s", "centre velocity");
      file_.define_series(g + "/angle", {1}, "rad", "rotation about z (0 where not a state)");
      file_.define_series(g + "/angular_velocity", {1}, "rad/s", "rotation rate about z (drive speed if driven)");
      file_.define_series(g + "/acceleration", {3}, "m/s^2, m/s^2, rad/s^2",
                          "ax, ay, angular acceleration (0 where not a state)");
      file_.define_series(g + "/force", {3}, "N, N, N m", "net force and moment (contacts, loads, supports)");
    }
    const std::size_t n = static_cast<std::size_t>(m.roller_count);
    file_.define_series("/rollers/position", {n, 2}, "m", "roller centres x, y");
    file_.define_series("/rollers/velocity", {n, 2}, "m/s", "roller centre velocities");
    file_.define_series("/rollers/spin", {n}, "rad/s", "roller rotation rate about its axis");
    file_.define_series("/rollers/acceleration", {n, 3}, "m/s^2, m/s^2, rad/s^2", "ax, ay, spin acceleration");
    if (segments_) {
      for (int k = 0; k < segment_kind_count; ++k) {
        std::vector<std::string> names;
        for (std::size_t s = 0; s < m.segments.size(); ++s)
          if (static_cast<int>(m.segments[s].kind) == k) {
            names.push_back(m.segments[s].name);
            index_[k].push_back(static_cast<int>(s));
          }
        if (names.empty()) continue;
        const std::string g = std::string("/segments/") + segment_kind_name(static_cast<SegmentKind>(k));
        file_.write_array(g + "/names", names, "segment names, in column order of the datasets of this group");
        for (int d = 0; d < contact::diagnostics_count; ++d)
          file_.define_series(g + "/" + diagnostic_names[d], {names.size()}, diagnostic_units[d], diagnostic_docs[d]);
      }
    }
    file_.set_attribute("/", "state_names", m.state_name);
  }

  void append(double t, const std::vector<double>& z, const std::vector<double>& zdot, const Equations& eq, double energy) {
    file_.append("/time", std::span<const double>(&t, 1));
    file_.append("/energy", std::span<const double>(&energy, 1));
    const auto& loads = eq.body_loads();
    auto val = [&](const Body& b, int c, const std::vector<double>& v) { return b.slot[c] >= 0 ? v[b.slot[c]] : 0.0; };
    for (int bi = 0; bi < m_.first_roller; ++bi) {
      const Body& b = m_.bodies[bi];
      const auto k = m_.kinematics(bi, t, z.data());
      const std::string g = "/" + b.name;
      const double pos[2] = {k.x, k.y}, vel[2] = {k.vx, k.vy}, ang = k.theta, w = k.omega;
      const double acc[3] = {val(b, Component::vx, zdot), val(b, Component::vy, zdot), val(b, Component::omega, zdot)};
      const double f[3] = {loads[bi].fx, loads[bi].fy, loads[bi].mz};
      file_.append(g + "/position", pos);
      file_.append(g + "/velocity", vel);
      file_.append(g + "/angle", std::span<const double>(&ang, 1));
      file_.append(g + "/angular_velocity", std::span<const double>(&w, 1));
      file_.append(g + "/acceleration", acc);
      file_.append(g + "/force", f);
    }
    const std::size_t n = static_cast<std::size_t>(m_.roller_count);
    std::vector<double> pos(2 * n), vel(2 * n), spin(n), acc(3 * n);
    for (std::size_t k = 0; k < n; ++k) {
      const Body& b = m_.bodies[m_.first_roller + k];
      pos[2 * k] = z[b.slot[Component::px]], pos[2 * k + 1] = z[b.slot[Component::py]];
      vel[2 * k] = z[b.slot[Component::vx]], vel[2 * k + 1] = z[b.slot[Component::vy]];
      spin[k] = z[b.slot[Component::omega]];
      acc[3 * k] = zdot[b.slot[Component::vx]], acc[3 * k + 1] = zdot[b.slot[Component::vy]];
      acc[3 * k + 2] = zdot[b.slot[Component::omega]];
    }
    file_.append("/rollers/position", pos);
    file_.append("/rollers/velocity", vel);
    file_.append("/rollers/spin", spin);
    file_.append("/rollers/acceleration", acc);
    if (!segments_) return;
    const auto& rec = eq.segment_records();
    for (int k = 0; k < segment_kind_count; ++k) {
      if (index_[k].empty()) continue;
      const std::string g = std::string("/segments/") + segment_kind_name(static_cast<SegmentKind>(k));
      std::vector<double> row(index_[k].size());
      for (int d = 0; d < contact::diagnostics_count; ++d) {
        for (std::size_t i = 0; i < row.size(); ++i)
          row[i] = rec[static_cast<std::size_t>(index_[k][i]) * SegmentRecord::size + SegmentRecord::diagnostics + d];
        file_.append(g + "/" + diagnostic_names[d], row);
      }
    }
  }

 private:
  io::H5SeriesWriter& file_;
  const Model& m_;
  bool segments_;
  std::vector<int> index_[segment_kind_count];
};

}  // namespace

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
  return j;
}

RunSummary run_scene(const io::Scene& scene, const RunOptions& options) {
  if (scene.scene.model == io::ModelKind::spatial) return run_spatial_scene(scene, options);
  const auto wall_start = std::chrono::steady_clock::now();
  const Model model = build_model(scene);
  scheduler::SerialExecutor serial;
  scheduler::Executor& executor = options.executor ? *options.executor : serial;
  Equations eq(model, executor);
  executor.attach(eq.task_catalogue());
  const double t0 = 0.0;
  const StartupReport start = consistent_initial_state(model, t0);
  if (options.on_info) options.on_info(start.summary);

  auto file = open_run_output(scene, options, eq, model.describe());
  OutputWriter out(file, model, scene.output.segments);

  Integrator integrator(eq, scene.solver, t0, start.state);
  double force_sum[2] = {0, 0}, load_sum[2] = {0, 0};
  RunRecorder recorder;
  recorder.append = [&](double t, const std::vector<double>& z, const std::vector<double>& zdot, double e) {
    out.append(t, z, zdot, eq, e);
  };
  recorder.second_half = [&](double t, const std::vector<double>& z) {
    // Contact force of the rollers on the inner ring (without its load).
    const Body& in = model.bodies[model.inner_ring];
    const auto& rec = eq.segment_records();
    for (std::size_t s = 0; s < model.segments.size(); ++s) {
      const auto& seg = model.segments[s];
      const double* r = rec.data() + s * SegmentRecord::size;
      if (seg.body_a == model.inner_ring) force_sum[0] += r[0], force_sum[1] += r[1];
      else if (seg.body_b == model.inner_ring) force_sum[0] += r[3], force_sum[1] += r[4];
    }
    load_sum[0] += in.ring->load.fx(t);
    load_sum[1] += in.ring->load.fy(t);
    return std::pair(z[model.bodies[model.cage].slot[Component::omega]], model.epicyclic_cage_speed(t));
  };
  recorder.summarize = [&](RunSummary& sum, int count) {
    for (int d = 0; d < 2; ++d) {
      sum.inner_ring_contact_force_n.push_back(force_sum[d] / count);
      sum.inner_ring_load_n.push_back(load_sum[d] / count);
    }
  };
  return record_run(scene, options, eq, executor, integrator, file, start.state, RunSummary{}, wall_start, recorder);
}

void serve_scene(const io::Scene& scene, const std::function<void(const scheduler::TaskCatalogue&)>& serve) {
  // The equations need an executor, but a worker's never call run(): their tasks are called by
  // `serve` with the master's context.
  scheduler::SerialExecutor unused;
  if (scene.scene.model == io::ModelKind::spatial) {
    const SpatialModel model = build_spatial_model(scene);
    const SpatialEquations eq(model, unused);
    serve(eq.task_catalogue());
  } else {
    const Model model = build_model(scene);
    const Equations eq(model, unused);
    serve(eq.task_catalogue());
  }
}

}  // namespace raceway::solver
