// Angular contact ball bearings (bearing.type = "angular_contact_ball", solver/bearing/ball_model.cpp)
// against the quasi-static solution this test computes itself (quasi_static_bearing.hpp: each ball
// on the line between its grooves' curvature centres, series Hertz stiffness, Newton on the inner
// ring's displacement):
//  - under a combined load (F_a 1500 N along +z, F_r 1000 N) at 120 rpm: the start-up state and a
//    run, ball by ball: loads and contact angles, and the inner ring's displacement;
//  - preloaded by displacement (the inner ring held 15 um along +z, no load): every ball carries
//    the same load at the same angle, from the geometry alone;
//  - loaded the wrong way: no equilibrium, and the start-up names the keys.
// The bearing: 7206 B size (jobs/scenes/7206B_angular_contact.toml): 12 balls of 9.525 mm on a
// 46 mm pitch circle, f_i 0.52, f_o 0.53, 40 deg free contact angle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/run/run.hpp"
#include "tests/support/quasi_static_bearing.hpp"
#include "tests/support/solver_test_support.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::bearing {
namespace {

using contact::Vec3;
using test::pi;

constexpr double deg = pi / 180;

scene::Scene angular_scene(double fy, double fz, double end_time) {
  test::BallSceneOptions o;
  o.speed_rpm = 120;
  o.fy = fy;
  o.fz = fz;
  o.end_time = end_time;
  o.output_interval = 1e-3;
  scene::Scene s = test::ball_scene(
      o, {.type = scene::BearingType::angular_contact_ball, .balls = 12,
          .ball = {.ball_diameter = 9.525e-3, .inner_conformity = 0.52, .outer_conformity = 0.53,
                   .free_contact_angle = 40 * deg},
          .pitch_diameter = 46e-3, .inner_bore_diameter = 30e-3, .outer_outside_diameter = 62e-3,
          .ring_width = 16e-3});
  s.cage.pocket_shape = scene::PocketShape::spherical;
  s.cage.pocket_clearance = 0.2e-3;
  return s;
}

/// Each ball's inner-groove load and contact angle (its magnitude) at the state z.
struct BallContacts {
  std::vector<double> load, angle;
};
BallContacts inner_contacts(const Model& m, const std::vector<double>& z) {
  BallContacts out;
  for (const Segment& seg : m.segments) {
    if (seg.kind != SegmentKind::ball_inner_groove) continue;
    auto ring = m.kinematics(seg.body_a, 0.0, z.data());
    auto ball = m.kinematics(seg.body_b, 0.0, z.data());
    ring.velocity.setZero(), ring.angular_velocity.setZero();
    ball.velocity.setZero(), ball.angular_velocity.setZero();
    const auto r = contact::evaluate(m.law<contact::BallGrooveSegment>(seg), ring, ball);
    out.load.push_back(r.diagnostics.normal_force);
    out.angle.push_back(std::abs(r.diagnostics.contact_angle));
  }
  return out;
}

double angle_of(const test::QuasiStaticBearing::Ball& b) { return std::atan2(std::abs(b.sin_alpha), b.cos_alpha); }

// The start-up (Levenberg-Marquardt with the model's contact functions) against the quasi-static
// solution: what separates them is the start-up's regularization springs (1e3 N/m), the balls'
// centrifugal force at 120 rpm (~2e-3 N) and the solvers' tolerances: 1e-3 of Q_max per ball,
// 0.01 deg per contact angle of the balls above 0.1 Q_max (0.1 deg for all), 1e-3 of the ring's
// displacement.
TEST(AngularContact, CombinedLoadStartupMatchesQuasiStatic) {
  const scene::Scene scene = angular_scene(-1000, 1500, 0.01);
  const test::QuasiStaticBearing qs(scene);
  const Model model = build_model(scene);
  const StartupReport start = initial_state(model, 0.0);
  std::vector<double> psi;
  for (int k = 0; k < qs.z; ++k) psi.push_back(2 * pi * k / qs.z);
  const Vec3 c = qs.solve(psi, Vec3(0, -1000, 1500), Vec3(0, -1e-6, 5e-6), {0, 1, 2});
  const BallContacts sim = inner_contacts(model, start.state);
  double q_max = 0, worst_load = 0, worst_angle = 0, a_min = 1e300, a_max = 0;
  for (int k = 0; k < qs.z; ++k) q_max = std::max(q_max, qs.ball(psi[static_cast<std::size_t>(k)], c).load);
  for (std::size_t k = 0; k < psi.size(); ++k) {
    const auto b = qs.ball(psi[k], c);
    worst_load = std::max(worst_load, std::abs(sim.load[k] - b.load) / q_max);
    // The balls' centrifugal force (2.3e-3 N at 120 rpm) turns a lightly loaded ball's contact line:
    // 0.07 deg on the 4.6 N ball opposite the radial load. The loaded balls are compared closely.
    if (b.load > 0.1 * q_max) worst_angle = std::max(worst_angle, std::abs(sim.angle[k] - angle_of(b)));
    EXPECT_NEAR(sim.angle[k], angle_of(b), 0.1 * deg) << "ball " << k;
    a_min = std::min(a_min, angle_of(b)), a_max = std::max(a_max, angle_of(b));
    EXPECT_NEAR(start.outer_contact_force[k], b.load, 1e-3 * q_max) << "ball " << k << " (outer contact)";
  }
  const Body& ring = model.bodies[static_cast<std::size_t>(model.inner_ring)];
  const auto at = [&](Coordinate q) { return start.state[static_cast<std::size_t>(ring.slot[q])]; };
  const Vec3 c_start(at(sx), at(sy), at(sz));
  std::printf("[ angular contact ] Fa 1500 N, Fr 1000 N: quasi-static ring (%.4f, %.4f, %.4f) um, Q %.1f..%.1f N at "
              "%.2f..%.2f deg; start-up ring (%.4f, %.4f, %.4f) um; worst ball load difference / Q_max %.2g, "
              "worst contact angle difference (balls above 0.1 Q_max) %.2g deg\n",
              1e6 * c.x(), 1e6 * c.y(), 1e6 * c.z(), *std::min_element(sim.load.begin(), sim.load.end()), q_max,
              a_min / deg, a_max / deg, 1e6 * c_start.x(), 1e6 * c_start.y(), 1e6 * c_start.z(), worst_load,
              worst_angle / deg);
  EXPECT_LT(worst_load, 1e-3);
  EXPECT_LT(worst_angle, 0.01 * deg);
  EXPECT_LT((c_start - c).norm(), 1e-3 * c.norm());
  // Every ball loaded (F_a / F_r = 1.5 > 1.14 tan 40 deg); the axial displacement opens every
  // contact line beyond 40 deg, the most loaded ball (under the radial load) the least.
  EXPECT_GT(*std::min_element(sim.load.begin(), sim.load.end()), 0.0);
  EXPECT_GT(a_min, 40 * deg);
  EXPECT_NEAR(sim.angle[9], a_min, 1e-3 * deg) << "ball 9, at 270 deg, under the radial load";
}

// The run at every output time: each ball's azimuth from /balls/position, the quasi-static solution
// for those azimuths, and the simulated inner-groove loads and contact angles against it (loads
// within 1 % of Q_max, angles within 0.1 deg), the ring within 1 % of its displacement. 0.15 s at
// 120 rpm: the cage turns 38 deg, more than the 30 deg ball spacing.
TEST(AngularContact, CombinedLoadRunMatchesQuasiStatic) {
  const scene::Scene scene = angular_scene(-1000, 1500, 0.15);
  const test::QuasiStaticBearing qs(scene);
  test::TempDir dir;
  run::RunOptions options;
  options.output_path = dir.file("angular.h5");
  const run::RunSummary sum = run_scene(scene, options);
  const auto balls = test::read_dataset(options.output_path, "/balls/position");
  const auto ring = test::read_dataset(options.output_path, "/inner_ring/position");
  const auto q = test::read_dataset(options.output_path, "/segments/ball_inner_groove/normal_force");
  const auto angle = test::read_dataset(options.output_path, "/segments/ball_inner_groove/contact_angle");
  const std::size_t samples = q.shape[0], z = q.shape[1];
  ASSERT_EQ(z, static_cast<std::size_t>(qs.z));
  Vec3 c(0, -1e-6, 5e-6);
  double worst_load = 0, worst_angle = 0, worst_ring = 0;
  for (std::size_t i = 0; i < samples; ++i) {
    std::vector<double> psi;
    for (std::size_t k = 0; k < z; ++k) psi.push_back(std::atan2(balls.at(i, k, 1), balls.at(i, k, 0)));
    c = qs.solve(psi, Vec3(0, -1000, 1500), c, {0, 1, 2});
    double q_max = 0;
    for (double p : psi) q_max = std::max(q_max, qs.ball(p, c).load);
    for (std::size_t k = 0; k < z; ++k) {
      const auto b = qs.ball(psi[k], c);
      worst_load = std::max(worst_load, std::abs(q.at(i, k) - b.load) / q_max);
      worst_angle = std::max(worst_angle, std::abs(std::abs(angle.at(i, k)) - angle_of(b)));
    }
    worst_ring = std::max(worst_ring, (Vec3(ring.at(i, 0), ring.at(i, 1), ring.at(i, 2)) - c).norm() / c.norm());
  }
  std::printf("[ angular contact ] run at 120 rpm, %.2f s (%zu outputs, %ld steps): worst ball load difference / "
              "Q_max %.2g, worst contact angle difference %.2g deg, worst ring |c - c_qs| / |c_qs| %.2g\n",
              sum.simulated_time_s, samples, sum.stats.steps, worst_load, worst_angle / deg, worst_ring);
  EXPECT_LT(worst_load, 1e-2);
  EXPECT_LT(worst_angle, 0.1 * deg);
  EXPECT_LT(worst_ring, 1e-2);
}

// Preload by displacement: the inner ring held 15 um along +z (axial = "fixed", axial_position),
// no load. Every ball: L = |(A cos a0, A sin a0 + 15 um)|, approach L - A shared by its two
// contacts, the angle atan((A sin a0 + 15 um) / (A cos a0)).
TEST(AngularContact, PreloadByAxialDisplacement) {
  scene::Scene scene = angular_scene(0, 0, 0.02);
  scene.inner_ring.axial_free = false;
  scene.inner_ring.axial_position = 15e-6;
  const test::QuasiStaticBearing qs(scene);
  const Model model = build_model(scene);
  const StartupReport start = initial_state(model, 0.0);
  const double a = qs.rgi + qs.rgo - 2 * qs.rb, a0 = 40 * deg;
  const double expected_angle = std::atan((a * std::sin(a0) + 15e-6) / (a * std::cos(a0)));
  const auto b = qs.ball(0.0, Vec3(0, 0, 15e-6));
  EXPECT_NEAR(angle_of(b), expected_angle, 1e-9);
  const BallContacts sim = inner_contacts(model, start.state);
  for (std::size_t k = 0; k < sim.load.size(); ++k) {
    EXPECT_NEAR(sim.load[k], b.load, 1e-4 * b.load) << "ball " << k;
    EXPECT_NEAR(sim.angle[k], expected_angle, 1e-3 * deg) << "ball " << k;
  }
  test::TempDir dir;
  run::RunOptions options;
  options.output_path = dir.file("preload.h5");
  const run::RunSummary sum = run_scene(scene, options);
  const auto q = test::read_dataset(options.output_path, "/segments/ball_inner_groove/normal_force");
  double worst = 0;
  for (double v : q.values) worst = std::max(worst, std::abs(v - b.load) / b.load);
  std::printf("[ angular contact ] preload 15 um: ball load %.2f N at %.3f deg (axial force %.1f N); start-up "
              "ball loads within %.2g; run (%ld steps) within %.2g\n",
              b.load, expected_angle / deg, qs.z * b.load * std::sin(expected_angle),
              std::abs(sim.load[0] - b.load) / b.load, sum.stats.steps, worst);
  EXPECT_LT(worst, 1e-2);
}

// An axial load the wrong way (-z on the inner ring) pushes the balls past the grooves' bottoms
// towards the low shoulders: they leave the grooves (a full torus would instead give a mirrored
// contact 0.6 mm further on). There is no equilibrium, and the start-up says so naming the keys.
TEST(AngularContact, LoadTheWrongWayHasNoEquilibrium) {
  const scene::Scene scene = angular_scene(-1000, -1500, 0.01);
  const Model model = build_model(scene);
  std::string what = "(no error)";
  EXPECT_THROW(
      {
        try {
          (void)initial_state(model, 0.0);
        } catch (const std::runtime_error& e) {
          what = e.what();
          throw;
        }
      },
      std::runtime_error);
  for (const char* part : {"no quasi-static equilibrium", "inner_ring.load", "bearing.contact_angle"})
    EXPECT_NE(what.find(part), std::string::npos) << what;
}

}  // namespace
}  // namespace raceway::bearing
