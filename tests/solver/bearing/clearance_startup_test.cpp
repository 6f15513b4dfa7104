// Start-up from any clearance (solver/bearing/roller_startup.cpp, ball_startup.cpp): bearings with
// the radial clearances real bearings have seat in quasi-static equilibrium and then run.
//  - cylindrical roller bearing (seed 002's 13-roller bearing): 0, 2, 10, 25, 50 um diametral
//    clearance under its 1 kN load and under a light 30 N load at 30 deg (where one or two rollers
//    carry it);
//  - deep groove ball bearing (6309 size, 45 mm bore): 0 to 51 um, the top of ISO 5753's C4 class
//    for that bore (C2 1-11, CN 6-23, C3 18-36, C4 30-51 um), under radial and combined loads;
//  - four-point contact ball bearing (QJ215 size): 0 to 90 um under a combined load.
// Each start is checked against what a quasi-static start must be (the free ring's net force
// vanishes while the rolling elements carry the load; every roller's radial force is the
// centripetal force of its orbit) and then run for a few milliseconds, which must end normally.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::bearing {
namespace {

using test::pi;

constexpr double um = 1e-6;

/// Runs the scene for its end time into a temporary file; the run must end normally.
run::RunSummary run_briefly(const scene::Scene& scene) {
  test::TempDir dir;
  run::RunOptions options;
  options.output_path = dir.file("clearance.h5");
  return run_scene(scene, options);
}

// ---- cylindrical roller bearing ---------------------------------------------------------------

scene::Scene roller_scene(double clearance, double load, double load_angle, double shaft_hz) {
  scene::Scene s = test::load_seed002_former_solver();
  s.inner_ring.speed = scene::TimeFunction::constant(2 * pi * shaft_hz);
  s.bearing.radial_clearance = clearance;
  s.inner_ring.load.fx = scene::TimeFunction::constant(load * std::cos(load_angle));
  s.inner_ring.load.fy = scene::TimeFunction::constant(load * std::sin(load_angle));
  s.scene.end_time = 5e-3;  // a fifth of a shaft revolution at 40 Hz
  s.scene.output_interval = 1e-4;
  return s;
}

void check_roller_start(double clearance, double load, double load_angle, double shaft_hz = 40) {
  const scene::Scene scene = roller_scene(clearance, load, load_angle, shaft_hz);
  const Model m = build_model(scene);
  StartupReport start;
  ASSERT_NO_THROW(start = initial_state(m, 0.0)) << clearance / um << " um";
  scheduler::SerialExecutor executor;
  Equations eq(m, executor);
  std::vector<double> zdot(start.state.size());
  ASSERT_EQ(eq.rhs(0.0, start.state.data(), zdot.data()), 0);
  const auto& ring = eq.body_loads()[static_cast<std::size_t>(m.inner_ring)];
  EXPECT_LT(std::hypot(ring.force.x(), ring.force.y()), 1e-6 * load) << clearance / um << " um";
  // The rollers carry the load: the ring moved along it by at least the radial play P_d / 2.
  const Body& inner = m.bodies[static_cast<std::size_t>(m.inner_ring)];
  const double along = start.state[static_cast<std::size_t>(inner.slot[sx])] * std::cos(load_angle) +
                       start.state[static_cast<std::size_t>(inner.slot[sy])] * std::sin(load_angle);
  EXPECT_GT(along, 0.5 * clearance);
  // Every roller seated: its radial force is the centripetal force of the epicyclic orbit.
  const double wc = m.epicyclic_cage_speed(0.0);
  for (int k = 0; k < m.element_count; ++k) {
    const Body& b = m.bodies[static_cast<std::size_t>(m.first_element + k)];
    const double x = start.state[static_cast<std::size_t>(b.slot[sx])];
    const double y = start.state[static_cast<std::size_t>(b.slot[sy])];
    const double r = std::hypot(x, y);
    const double radial = (zdot[static_cast<std::size_t>(b.slot[svx])] * x + zdot[static_cast<std::size_t>(b.slot[svy])] * y) / r;
    EXPECT_NEAR(radial, -wc * wc * r, 1e-3 * wc * wc * r) << "roller " << k << ", " << clearance / um << " um";
  }
  const run::RunSummary sum = run_briefly(scene);
  EXPECT_NEAR(sum.simulated_time_s, scene.scene.end_time, 1e-12);
  std::printf("[ clearance ] roller bearing at %3.0f Hz, P_d %4.0f um, %6.0f N at %3.0f deg: seated in %d iterations (%.2g N), "
              "ring %.2f um along the load; %.0f ms run in %ld steps\n",
              shaft_hz, clearance / um, load, load_angle * 180 / pi, start.iterations, start.residual, along / um,
              1e3 * sum.simulated_time_s, sum.stats.steps);
}

TEST(ClearanceStartup, RollerBearingUnderItsLoad) {
  for (double clearance : {0.0, 2 * um, 10 * um, 25 * um, 50 * um}) check_roller_start(clearance, 1000, -pi / 2);
}

TEST(ClearanceStartup, RollerBearingUnderALightObliqueLoad) {
  for (double clearance : {0.0, 2 * um, 10 * um, 25 * um, 50 * um}) check_roller_start(clearance, 30, -pi / 3);
}

// A preload (negative clearance): the rollers are pressed in before any load is applied. Under its
// load the bearing seats and runs as with clearance; without load the ring stays centred and every
// roller carries the same load, its two contacts sharing the interference -P_d / 2 (equal line
// contacts: each takes -P_d / 4; gravity off, at 1 Hz the centrifugal force is 1e-6 of the load).
TEST(ClearanceStartup, RollerBearingWithPreload) {
  for (double clearance : {-2 * um, -10 * um}) check_roller_start(clearance, 1000, -pi / 2);
  for (double clearance : {-2 * um, -10 * um}) {
    scene::Scene scene = roller_scene(clearance, 0.0, 0.0, 1.0);
    scene.gravity = false;  // the rollers' weights would load the lower ones more
    const Model m = build_model(scene);
    const StartupReport start = initial_state(m, 0.0);
    scheduler::SerialExecutor executor;
    Equations eq(m, executor);
    std::vector<double> zdot(start.state.size());
    ASSERT_EQ(eq.rhs(0.0, start.state.data(), zdot.data()), 0);
    const Body& inner = m.bodies[static_cast<std::size_t>(m.inner_ring)];
    EXPECT_LT(std::hypot(start.state[static_cast<std::size_t>(inner.slot[sx])],
                         start.state[static_cast<std::size_t>(inner.slot[sy])]), 1e-3 * um);
    std::vector<double> approach(2 * static_cast<std::size_t>(m.element_count)), load(approach.size());
    for (std::size_t s = 0; s < m.segments.size(); ++s) {
      const Segment& seg = m.segments[s];
      if (seg.kind != SegmentKind::roller_inner_race && seg.kind != SegmentKind::roller_outer_race) continue;
      const std::size_t at = 2 * static_cast<std::size_t>(seg.element) + (seg.kind == SegmentKind::roller_outer_race);
      approach[at] = eq.diagnostic(s, approach_field);
      load[at] = eq.diagnostic(s, normal_force_field);
    }
    for (int k = 0; k < m.element_count; ++k) {
      const std::size_t i = 2 * static_cast<std::size_t>(k);
      EXPECT_NEAR(approach[i] + approach[i + 1], -0.5 * clearance, 1e-4 * -clearance) << "roller " << k;
      EXPECT_NEAR(approach[i], -0.25 * clearance, 1e-3 * -clearance) << "roller " << k;
      EXPECT_NEAR(load[i], load[0], 1e-6 * load[0]) << "roller " << k;
    }
    std::printf("[ clearance ] preload %.0f um, no load: every roller %.1f N, approaches %.4f + %.4f um\n",
                -clearance / um, load[0], approach[0] / um, approach[1] / um);
  }
}

// At high speed the rollers' centrifugal force presses them into the outer race and opens a play
// of its own even at zero clearance (seed 002's bearing at 160 and 400 Hz once could not start).
TEST(ClearanceStartup, RollerBearingAtHighSpeed) {
  for (double shaft_hz : {100.0, 160.0, 250.0, 400.0})
    for (double clearance : {0.0, 25 * um}) check_roller_start(clearance, 1000, -pi / 2, shaft_hz);
}

// ---- deep groove ball bearing -----------------------------------------------------------------

void check_ball_start(double clearance, double fy, double fz, scene::Scene (*bearing)(const test::BallSceneOptions&) =
                                                                      test::deep_groove_scene) {
  test::BallSceneOptions o;
  o.fy = fy;
  o.fz = fz;
  o.speed_rpm = 3000;
  o.end_time = 2e-3;
  scene::Scene scene = bearing(o);
  scene.bearing.radial_clearance = clearance;
  const Model m = build_model(scene);
  StartupReport start;
  ASSERT_NO_THROW(start = initial_state(m, 0.0)) << clearance / um << " um";
  const double load = std::hypot(fy, fz);
  EXPECT_LT(start.residual, 1e-6 * load) << clearance / um << " um";
  // The balls carry the load: the inner-groove forces along it add up to at least the load.
  double carried_y = 0, carried_z = 0;
  for (const auto& seg : m.segments) {
    if (seg.kind != SegmentKind::ball_inner_groove) continue;
    const auto& g = m.law<contact::BallGrooveSegment>(seg);
    const auto ring = m.kinematics(seg.body_a, 0.0, start.state.data());
    auto ball = m.kinematics(seg.body_b, 0.0, start.state.data());
    ball.velocity.setZero();
    ball.angular_velocity.setZero();
    auto at_rest = ring;
    at_rest.velocity.setZero();
    at_rest.angular_velocity.setZero();
    const auto r = contact::evaluate(g, at_rest, ball);
    carried_y -= r.on_a.force.y();
    carried_z -= r.on_a.force.z();
  }
  // The seating's regularization spring (1e3 N/m on every unknown, ball_startup.cpp) carries the
  // rest: 1e3 N/m times the ring's displacement.
  const Body& inner = m.bodies[static_cast<std::size_t>(m.inner_ring)];
  const auto position = [&](Coordinate c) { return start.state[static_cast<std::size_t>(inner.slot[c])]; };
  const double spring = 1e3 * std::hypot(position(sx), position(sy), position(sz));
  EXPECT_NEAR(carried_y, fy, spring + 1e-6 * load) << clearance / um << " um";
  EXPECT_NEAR(carried_z, fz, spring + 1e-6 * load) << clearance / um << " um";
  const run::RunSummary sum = run_briefly(scene);
  EXPECT_NEAR(sum.simulated_time_s, scene.scene.end_time, 1e-12);
  std::printf("[ clearance ] %s, P_d %4.0f um, Fr %5.0f N, Fa %5.0f N: seated in %d iterations "
              "(%.2g N), largest ball load %.0f N; %.0f ms run in %ld steps\n",
              m.arcs_per_ring == 2 ? "QJ215 four-point" : "6309 deep groove", clearance / um, -fy, fz, start.iterations, start.residual, sum.max_ball_load_n,
              1e3 * sum.simulated_time_s, sum.stats.steps);
}

const double ball_clearances[] = {0.0, 6 * um, 15 * um, 23 * um, 36 * um, 51 * um};

TEST(ClearanceStartup, BallBearingUnderRadialLoad) {
  for (double clearance : ball_clearances) check_ball_start(clearance, -1000, 0);
}

TEST(ClearanceStartup, BallBearingUnderCombinedLoad) {
  for (double clearance : ball_clearances) check_ball_start(clearance, -1000, 1000);
}

TEST(ClearanceStartup, BallBearingUnderALightLoad) {
  for (double clearance : ball_clearances) check_ball_start(clearance, -20, 0);
}

// The QJ215-size four-point bearing (seed 001 gives it 27 um) from 0 to 90 um, under the combined
// load of jobs/scenes/qj215_validation.toml.
TEST(ClearanceStartup, FourPointBearingUnderCombinedLoad) {
  for (double clearance : {0.0, 10 * um, 27 * um, 50 * um, 90 * um})
    check_ball_start(clearance, -500, 2000, test::four_point_scene);
}

}  // namespace
}  // namespace raceway::bearing
