// One spatial (ball-bearing) simulation: model, start-up, CVODE, output at fixed times
// (docs/output_layout.md, "Spatial (ball-bearing) runs").
#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "io/h5/h5_series.hpp"
#include "solver/run/schedule_output.hpp"
#include "solver/run/run.hpp"
#include "solver/run/run_loop.hpp"
#include "solver/bearing/spatial_equations.hpp"
#include "solver/bearing/spatial_startup.hpp"

namespace raceway::solver {

using contact::Vec3;

namespace {


const char* diagnostic_names[contact::point_diagnostics_count] = {
    "approach",       "normal_force",   "contact_angle",         "max_pressure",   "film_thickness", "slip_velocity",
    "spin_velocity",  "traction_force", "circumferential_force", "elastic_energy", "power_loss"};
const char* diagnostic_units[contact::point_diagnostics_count] = {"m",     "N",     "rad", "Pa", "m", "m/s",
                                                                  "rad/s", "N",     "N",   "J",  "W"};
const char* diagnostic_docs[contact::point_diagnostics_count] = {
    "approach of the two surfaces (> 0 in contact)",
    "normal contact force (>= 0)",
    "ball-groove: angle of the contact normal to the radial plane; others 0",
    "maximum Hertz pressure",
    "central EHL film thickness (0 dry)",
    "sliding speed at the contact centre",
    "relative spin about the contact normal",
    "magnitude of the tangential (traction, friction) force",
    "force on the ball (land: on the ring) along the bearing's circumferential direction at its centre",
    "elastic energy stored in the contact",
    "power dissipated by traction, damping and rolling resistance"};

class SpatialOutput {
 public:
  SpatialOutput(io::H5SeriesWriter& file, const SpatialModel& m, bool segments) : file_(file), m_(m), segments_(segments) {
    file_.define_series("/time", {1}, "s", "output times (interpolated, not solver steps)");
    file_.define_series("/energy", {1}, "J", "kinetic + elastic + support + load potential energy");
    for (int b = 0; b < m.first_ball; ++b) {
      const std::string g = "/" + m.bodies[static_cast<std::size_t>(b)].name;
      file_.define_series(g + "/position", {3}, "m", "centre in the bearing frame");
      file_.define_series(g + "/velocity", {3}, "m/s", "centre velocity");
      file_.define_series(g + "/angles", {3}, "rad", "tilt about x, tilt about y, rotation about z (rings: 0 about z)");
      file_.define_series(g + "/angular_velocity", {3}, "rad/s", "angular velocity, bearing frame");
      file_.define_series(g + "/force", {6}, "N, N m", "net force and moment at the centre (contacts, loads, supports, gravity)");
    }
    file_.define_series("/cage/epicyclic_speed", {1}, "rad/s", "kinematic cage speed (seed 001 eq. 5, nominal contact angle)");
    file_.define_series("/cage/rolling_speed", {1}, "rad/s",
                        "kinematic cage speed at the load-weighted mean contact angle of the inner-groove contacts "
                        "(nominal angle when none is loaded)");
    const std::size_t n = static_cast<std::size_t>(m.ball_count);
    file_.define_series("/balls/position", {n, 3}, "m", "ball centres");
    file_.define_series("/balls/velocity", {n, 3}, "m/s", "ball centre velocities");
    file_.define_series("/balls/angular_velocity", {n, 3}, "rad/s", "ball angular velocities, bearing frame");
    if (segments_) {
      for (int k = 0; k < spatial_segment_kind_count; ++k) {
        std::vector<std::string> names;
        std::vector<double> balls;
        for (std::size_t s = 0; s < m.segments.size(); ++s)
          if (static_cast<int>(m.segments[s].kind) == k) {
            names.push_back(m.segments[s].name);
            balls.push_back(m.segments[s].ball);
            index_[k].push_back(static_cast<int>(s));
          }
        if (names.empty()) continue;
        const std::string g = std::string("/segments/") + spatial_segment_kind_name(static_cast<SpatialSegmentKind>(k));
        file_.write_array(g + "/names", names, "segment names, in column order of the datasets of this group");
        file_.write_array(g + "/ball", {balls.size()}, balls, "-", "ball index (0-based) of each column; -1 for cage-land");
        for (int d = 0; d < contact::point_diagnostics_count; ++d)
          file_.define_series(g + "/" + diagnostic_names[d], {names.size()}, diagnostic_units[d], diagnostic_docs[d]);
      }
    }
    file_.set_attribute("/", "state_names", m.state_name);
  }

  /// Load-weighted mean |contact angle| of the inner-groove contacts in the last rhs (the angle the
  /// balls roll at); the nominal angle when none is loaded.
  double loaded_contact_angle(const SpatialEquations& eq) const {
    const auto& rec = eq.segment_records();
    double load = 0, weighted = 0;
    for (std::size_t s = 0; s < m_.segments.size(); ++s) {
      if (m_.segments[s].kind != SpatialSegmentKind::ball_inner_groove) continue;
      const double* d = rec.data() + s * SpatialRecord::size + SpatialRecord::diagnostics;
      load += d[1], weighted += d[1] * std::abs(d[2]);  // normal_force, contact_angle
    }
    return load > 0 ? weighted / load : m_.nominal_contact_angle;
  }

  void append(double t, const std::vector<double>& z, const SpatialEquations& eq, double energy) {
    file_.append("/time", std::span<const double>(&t, 1));
    file_.append("/energy", std::span<const double>(&energy, 1));
    const auto& loads = eq.body_loads();
    for (int bi = 0; bi < m_.first_ball; ++bi) {
      const auto& b = m_.bodies[static_cast<std::size_t>(bi)];
      const auto k = m_.kinematics(bi, t, z.data());
      const std::string g = "/" + b.name;
      auto state = [&](int c) { return b.slot[c] >= 0 ? z[static_cast<std::size_t>(b.slot[c])] : 0.0; };
      double angles[3] = {state(sax), state(say), state(saz)};
      if (b.ring && b.ring->tilt == io::RingTilt::prescribed)
        angles[0] = b.ring->misalignment_x(t), angles[1] = b.ring->misalignment_y(t);
      const auto& w = loads[static_cast<std::size_t>(bi)];
      const double pos[3] = {k.position.x(), k.position.y(), k.position.z()};
      const double vel[3] = {k.velocity.x(), k.velocity.y(), k.velocity.z()};
      const double om[3] = {k.angular_velocity.x(), k.angular_velocity.y(), k.angular_velocity.z()};
      const double f[6] = {w.force.x(), w.force.y(), w.force.z(), w.moment.x(), w.moment.y(), w.moment.z()};
      file_.append(g + "/position", pos);
      file_.append(g + "/velocity", vel);
      file_.append(g + "/angles", angles);
      file_.append(g + "/angular_velocity", om);
      file_.append(g + "/force", f);
    }
    const double epi = m_.epicyclic_cage_speed(t);
    file_.append("/cage/epicyclic_speed", std::span<const double>(&epi, 1));
    const double rolling = m_.epicyclic_cage_speed(t, loaded_contact_angle(eq));
    file_.append("/cage/rolling_speed", std::span<const double>(&rolling, 1));
    const std::size_t n = static_cast<std::size_t>(m_.ball_count);
    std::vector<double> pos(3 * n), vel(3 * n), om(3 * n);
    for (std::size_t k = 0; k < n; ++k) {
      const auto& b = m_.bodies[static_cast<std::size_t>(m_.first_ball) + k];
      for (int d = 0; d < 3; ++d) {
        pos[3 * k + static_cast<std::size_t>(d)] = z[static_cast<std::size_t>(b.slot[sx + d])];
        vel[3 * k + static_cast<std::size_t>(d)] = z[static_cast<std::size_t>(b.slot[svx + d])];
        om[3 * k + static_cast<std::size_t>(d)] = z[static_cast<std::size_t>(b.slot[swx + d])];
      }
    }
    file_.append("/balls/position", pos);
    file_.append("/balls/velocity", vel);
    file_.append("/balls/angular_velocity", om);
    if (!segments_) return;
    const auto& rec = eq.segment_records();
    for (int k = 0; k < spatial_segment_kind_count; ++k) {
      if (index_[k].empty()) continue;
      const std::string g = std::string("/segments/") + spatial_segment_kind_name(static_cast<SpatialSegmentKind>(k));
      std::vector<double> row(index_[k].size());
      for (int d = 0; d < contact::point_diagnostics_count; ++d) {
        for (std::size_t i = 0; i < row.size(); ++i)
          row[i] = rec[static_cast<std::size_t>(index_[k][i]) * SpatialRecord::size + SpatialRecord::diagnostics +
                       static_cast<std::size_t>(d)];
        file_.append(g + "/" + diagnostic_names[d], row);
      }
    }
  }

 private:
  io::H5SeriesWriter& file_;
  const SpatialModel& m_;
  bool segments_;
  std::vector<int> index_[spatial_segment_kind_count];
};

}  // namespace

RunSummary run_spatial_scene(const io::Scene& scene, const RunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  const SpatialModel model = build_spatial_model(scene);
  scheduler::SerialExecutor serial;
  scheduler::Executor& executor = options.executor ? *options.executor : serial;
  SpatialEquations eq(model, executor);
  executor.attach(eq.task_catalogue());
  const double t0 = 0.0;
  const SpatialStartupReport start = spatial_initial_state(model, t0, options.azimuth_offset);
  if (options.on_info) options.on_info(start.summary);

  auto file = open_run_output(scene, options, eq, model.describe());
  file.set_attribute("/", "model_kind", std::string("spatial"));
  file.set_attribute("/", "ball_count", static_cast<long long>(model.ball_count));
  file.set_attribute("/", "pitch_radius", model.pitch_radius);
  file.set_attribute("/", "pocket_clearance", scene.cage.pocket_clearance);
  file.set_attribute("/", "land_clearance", model.land_segments.empty() ? 0.0 : scene.cage.land_clearance);
  SpatialOutput out(file, model, scene.output.segments);

  Integrator integrator(eq, scene.solver, t0, start.state);
  RunSummary sum;
  sum.model_kind = "spatial";
  Vec3 force_sum = Vec3::Zero(), load_sum = Vec3::Zero();
  double max_ball_load = 0;
  RunRecorder recorder;
  recorder.append = [&](double t, const std::vector<double>& z, const std::vector<double>&, double e) {
    out.append(t, z, eq, e);
  };
  recorder.second_half = [&](double t, const std::vector<double>& z) {
    force_sum += eq.contact_loads()[static_cast<std::size_t>(model.inner_ring)].force;
    const auto& l = scene.inner_ring.load;
    load_sum += Vec3(l.fx(t), l.fy(t), l.fz(t));
    const auto& rec = eq.segment_records();
    std::vector<double> ball_load(static_cast<std::size_t>(model.ball_count), 0.0);
    for (std::size_t s = 0; s < model.segments.size(); ++s)
      if (model.segments[s].kind == SpatialSegmentKind::ball_inner_groove)
        ball_load[static_cast<std::size_t>(model.segments[s].ball)] +=
            rec[s * SpatialRecord::size + SpatialRecord::diagnostics + 1];
    for (double q : ball_load) max_ball_load = std::max(max_ball_load, q);
    return std::pair(model.kinematics(model.cage, t, z.data()).angular_velocity.z(), model.epicyclic_cage_speed(t));
  };
  recorder.summarize = [&](RunSummary& s, int count) {
    s.max_ball_load_n = max_ball_load;
    for (int d = 0; d < 3; ++d) {
      s.inner_ring_contact_force_n.push_back(force_sum[d] / count);
      s.inner_ring_load_n.push_back(load_sum[d] / count);
    }
  };
  return record_run(scene, options, eq, executor, integrator, file, start.state, std::move(sum), wall_start, recorder);
}

}  // namespace raceway::solver
