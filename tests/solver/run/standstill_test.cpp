// Standstill and start-stop: traction at zero speed (contact/laws/point_contact.hpp: the film's
// shear hands over to the friction curve as the film vanishes). Whole runs of a lubricated 6309-size
// ball bearing (limiting-shear traction, EHL rolling resistance) and of seed 002's roller bearing:
//  - held at 0 rpm under load: nothing drives the bearing, so the run must end normally with the
//    energy not rising and the cage at rest;
//  - a start-stop cycle (ramp up from rest, hold, ramp down to 0, hold): the cage follows the
//    epicyclic speed while running and comes to rest after the stop.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::run {
namespace {

using test::pi;

struct Outcome {
  RunSummary summary;
  std::vector<double> cage_speed;  ///< per sample: about the axis [rad/s]
  test::Dataset epicyclic;         ///< [T] (spatial runs)
};

Outcome run(const scene::Scene& scene) {
  test::TempDir dir;
  RunOptions options;
  options.output_path = dir.file("standstill.h5");
  Outcome out;
  out.summary = run_scene(scene, options);
  // Planar: the rate about z; spatial: the body-frame angular velocity, whose z is along the cage axis.
  const test::Dataset w = test::read_dataset(options.output_path, "/cage/angular_velocity");
  const std::size_t columns = w.shape.size() > 1 ? w.shape[1] : 1;
  for (std::size_t i = 0; i < w.shape[0]; ++i) out.cage_speed.push_back(w.values[i * columns + columns - 1]);
  if (scene.scene.model == scene::ModelKind::spatial)
    out.epicyclic = test::read_dataset(options.output_path, "/cage/epicyclic_speed");
  return out;
}

/// Nothing drives the bearing: the energy may only fall (to the integrator's error), and the cage
/// turns no faster than `cage_bound` [rad/s].
void expect_at_rest(const Outcome& o, const scene::Scene& scene, double cage_bound) {
  const RunSummary& s = o.summary;
  EXPECT_NEAR(s.simulated_time_s, scene.scene.end_time, 1e-12);
  EXPECT_LE(s.energy_final_j, s.energy_initial_j + 1e-9 * std::abs(s.energy_initial_j));
  double fastest = 0;
  for (const double w : o.cage_speed) fastest = std::max(fastest, std::abs(w));
  EXPECT_LT(fastest, cage_bound);
  std::printf("[ standstill ] %s: %.0f ms at 0 rpm in %ld steps; energy %.6g -> %.6g J; fastest cage %.3g rad/s\n",
              s.model_kind.c_str(), 1e3 * s.simulated_time_s, s.stats.steps, s.energy_initial_j, s.energy_final_j,
              fastest);
}

scene::Scene lubricated_ball_bearing(const scene::TimeFunction& speed, double end_time) {
  test::BallSceneOptions o;
  o.lubricated = true;
  o.fy = -1000;
  o.end_time = end_time;
  scene::Scene s = test::deep_groove_scene(o);
  s.inner_ring.speed = speed;
  s.cage.pocket_shape = scene::PocketShape::spherical;  // a ball-guided cage the balls hold (scene_rules.cpp)
  return s;
}

// Limiting-shear traction at exactly 0 rpm: the film is zero at zero entrainment. Before the
// hand-over this ended with "too much work" after 2.6e-7 s.
TEST(Standstill, LubricatedBallBearingHeldAtRest) {
  const scene::Scene scene = lubricated_ball_bearing(scene::TimeFunction::constant(0.0), 0.02);
  expect_at_rest(run(scene), scene, 1e-9);  // no gravity: nothing moves the cage
}

TEST(Standstill, RollerBearingWithClearanceHeldAtRest) {
  scene::Scene scene = test::load_seed002_former_solver();
  scene.inner_ring.speed = scene::TimeFunction::constant(0.0);
  scene.bearing.radial_clearance = 20e-6;
  scene.scene.end_time = 0.01;
  // Gravity settles the rollers in their pockets; the cage turns at most as fast as a roller's
  // free fall through the pocket clearance would turn it, sqrt(2 g c) / r_p.
  expect_at_rest(run(scene), scene,
                 std::sqrt(2 * 9.80665 * scene.cage.pocket_clearance) / (0.5 * scene.bearing.pitch_diameter));
}

// 0 -> 3000 rpm in 20 ms, held 20 ms, down to 0 in 20 ms, held 20 ms.
TEST(Standstill, LubricatedBallBearingStartStopCycle) {
  const double w = 3000 * pi / 30;
  const scene::TimeFunction cycle{{0.0, 0.02, 0.04, 0.06}, {0.0, w, w, 0.0}};
  const scene::Scene scene = lubricated_ball_bearing(cycle, 0.08);
  const Outcome o = run(scene);
  EXPECT_NEAR(o.summary.simulated_time_s, 0.08, 1e-12);
  const std::size_t samples = o.cage_speed.size();
  ASSERT_EQ(samples, 801u);  // every 0.1 ms
  // Running (the last 5 ms of the hold): the cage within 3 % of the epicyclic speed.
  double worst_running = 0;
  for (std::size_t i = 350; i <= 400; ++i)
    worst_running = std::max(worst_running, std::abs(o.cage_speed[i] / o.epicyclic.values.at(i) - 1));
  EXPECT_LT(worst_running, 0.03);
  // Stopped (the last 5 ms): the cage at rest, below 1 % of its running speed.
  const double running = o.epicyclic.values.at(400);
  double fastest_stopped = 0;
  for (std::size_t i = 750; i < samples; ++i) fastest_stopped = std::max(fastest_stopped, std::abs(o.cage_speed[i]));
  EXPECT_LT(fastest_stopped, 0.01 * running);
  std::printf("[ standstill ] start-stop cycle: %ld steps; cage within %.2f %% of epicyclic while running, "
              "at most %.3g rad/s (%.2f %% of %.1f rad/s) after the stop\n",
              o.summary.stats.steps, 100 * worst_running, fastest_stopped, 100 * fastest_stopped / running, running);
}

}  // namespace
}  // namespace raceway::run
