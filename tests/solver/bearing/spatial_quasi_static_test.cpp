// The spatial ball-bearing model (solver/bearing/ball_model.cpp, spatial_dynamics.cpp,
// ball_startup.cpp) in whole runs against quasi-static results derived here, independently of the
// solver's own start-up:
//  1. pure axial load: every ball carries the same load at the same contact angle, and the balls
//     balance the axial load (Z Q sin(alpha) = F_a), deep groove and four-point;
//  2. radial load at low speed: ball loads and ring displacement, of the start-up state and along a
//     run, against a quasi-static equilibrium solved in this file (Hertz per ball, Newton on the
//     ring displacement).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "contact/laws/point_contact.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/run/run.hpp"
#include "tests/support/solver_test_support.hpp"
#include "tests/support/quasi_static_bearing.hpp"
#include "tests/support/spatial_scene_builder.hpp"

namespace raceway::bearing {
namespace {

using contact::Vec3;
using test::BallSceneOptions;
using test::pi;
using test::seconds_since;

/// Per-segment diagnostic of one kind, with the ball index of each column.
struct SegmentSeries {
  test::Dataset values;       ///< [T x s]
  std::vector<int> ball;      ///< column -> ball
  std::vector<std::string> names;
};

SegmentSeries read_segments(const std::string& file, const std::string& kind, const std::string& diagnostic) {
  SegmentSeries s;
  s.values = test::read_dataset(file, "/segments/" + kind + "/" + diagnostic);
  const auto b = test::read_dataset(file, "/segments/" + kind + "/element");
  for (double v : b.values) s.ball.push_back(static_cast<int>(std::lround(v)));
  s.names = test::read_strings(file, "/segments/" + kind + "/names");
  return s;
}

// ---------------------------------------------------------------------------------------------
// 1. Pure axial load
// ---------------------------------------------------------------------------------------------

struct AxialOutcome {
  double worst_load_spread = 0;   ///< max over times and balls of |Q_k - mean| / mean (loaded arcs)
  double worst_angle_spread = 0;  ///< the same for |alpha_k|
  double mean_balance = 0;        ///< time mean of sum_k Q_k sin(alpha_k), N
  double worst_balance = 0;       ///< max over times of |sum_k Q_k sin(alpha_k) - F_a| / F_a
  double worst_inertia = 0;       ///< max over times of |F_net,z| / F_a (the ring's own m a_z)
  double worst_unloaded = 0;      ///< four-point: largest load on an arc that should be open [N]
  double mean_load = 0, mean_angle = 0;
  double mean_cage_speed = 0;     ///< rad/s, second half
  double mean_rolling_speed = 0;  ///< rad/s, /cage/rolling_speed (kinematic at the loaded angle)
  double mean_epicyclic_speed = 0;  ///< rad/s, /cage/epicyclic_speed (nominal angle)
  run::RunSummary summary;
};

/// Runs `scene` with a pure axial load F_a (+z) on the inner ring and measures, over the output
/// times of the second half, how equal the balls' loaded inner contacts are and how well they
/// balance F_a. For a four-point bearing each ball touches one inner arc (and the opposite outer arc).
AxialOutcome run_axial(const scene::Scene& scene, double fa, const char* label) {
  test::TempDir dir;
  run::RunOptions options;
  options.output_path = dir.file("axial.h5");
  const auto wall = std::chrono::steady_clock::now();
  AxialOutcome o;
  o.summary = run_scene(scene, options);
  const auto time = test::read_dataset(options.output_path, "/time");
  const auto q = read_segments(options.output_path, "ball_inner_groove", "normal_force");
  const auto angle = read_segments(options.output_path, "ball_inner_groove", "contact_angle");
  const auto ring_force = test::read_dataset(options.output_path, "/inner_ring/force");
  const auto cage_rate = test::read_dataset(options.output_path, "/cage/angular_velocity");
  const auto rolling_speed = test::read_dataset(options.output_path, "/cage/rolling_speed");
  const auto epicyclic_speed = test::read_dataset(options.output_path, "/cage/epicyclic_speed");
  const int z = scene.bearing.rolling_elements;
  const std::size_t columns = q.ball.size();
  int samples = 0;
  for (std::size_t i = 0; i < time.values.size(); ++i) {
    if (time.values[i] < 0.5 * scene.scene.end_time - 1e-12) continue;
    // Loaded column of each ball: its inner arc with the larger load (the only one for deep groove).
    std::vector<std::size_t> loaded(static_cast<std::size_t>(z), columns);
    for (std::size_t c = 0; c < columns; ++c) {
      const auto k = static_cast<std::size_t>(q.ball[c]);
      if (loaded[k] == columns || q.values.at(i, c) > q.values.at(i, loaded[k])) loaded[k] = c;
    }
    for (std::size_t c = 0; c < columns; ++c)
      if (c != loaded[static_cast<std::size_t>(q.ball[c])]) o.worst_unloaded = std::max(o.worst_unloaded, q.values.at(i, c));
    std::vector<double> load(static_cast<std::size_t>(z)), alpha(static_cast<std::size_t>(z));
    double mean_q = 0, mean_a = 0, axial = 0;
    for (std::size_t k = 0; k < load.size(); ++k) {
      load[k] = q.values.at(i, loaded[k]);
      alpha[k] = std::abs(angle.values.at(i, loaded[k]));
      mean_q += load[k] / z, mean_a += alpha[k] / z;
      axial += load[k] * std::sin(alpha[k]);
    }
    for (std::size_t k = 0; k < load.size(); ++k) {
      o.worst_load_spread = std::max(o.worst_load_spread, std::abs(load[k] - mean_q) / mean_q);
      o.worst_angle_spread = std::max(o.worst_angle_spread, std::abs(alpha[k] - mean_a) / mean_a);
    }
    const double net_z = ring_force.at(i, 2);  // m a_z of the inner ring
    o.worst_balance = std::max(o.worst_balance, std::abs(axial - fa) / fa);
    o.worst_inertia = std::max(o.worst_inertia, std::abs(net_z) / fa);
    o.mean_balance += axial, o.mean_load += mean_q, o.mean_angle += mean_a, ++samples;
    o.mean_cage_speed += cage_rate.at(i, 2), o.mean_rolling_speed += rolling_speed.values[i];
    o.mean_epicyclic_speed += epicyclic_speed.values[i];
  }
  o.mean_balance /= samples, o.mean_load /= samples, o.mean_angle /= samples;
  o.mean_cage_speed /= samples, o.mean_rolling_speed /= samples, o.mean_epicyclic_speed /= samples;
  std::printf("[ axial ] %s, F_a %g N: %d samples (second half); mean ball load %.4f N at %.4f deg; largest "
              "spread between balls: loads %.3g, angles %.3g; mean Z Q sin(a) / F_a - 1 = %.3g; worst "
              "|Z Q sin(a) - F_a| / F_a %.3g; worst |m a_z| / F_a %.3g; open arcs <= %.3g N; summary "
              "inner-ring contact force z %.4f N; %ld steps, %.2f s wall\n",
              label, fa, samples, o.mean_load, o.mean_angle * 180 / pi, o.worst_load_spread, o.worst_angle_spread,
              o.mean_balance / fa - 1, o.worst_balance, o.worst_inertia, o.worst_unloaded,
              o.summary.inner_ring_contact_force_n.at(2), o.summary.stats.steps, seconds_since(wall));
  EXPECT_GT(samples, 10);
  return o;
}

/// The pure axial load runs: F_a (+z) on the inner ring at 1000 rpm, 20 ms, outputs every 0.1 ms.
BallSceneOptions axial_options(double fa) {
  BallSceneOptions o;
  o.fz = fa;
  o.speed_rpm = 1000;
  o.end_time = 0.02;
  o.output_interval = 1e-4;
  return o;
}

// ---------------------------------------------------------------------------------------------
// Quasi-static deep-groove equilibrium, solved here independently of solver/bearing/ball_startup.cpp
// ---------------------------------------------------------------------------------------------

// (QuasiStaticBearing: quasi_static_bearing.hpp)

// What the dynamics add to the quasi-static picture, and the tolerances:
//  - the problem is symmetric about the axis, so the balls stay equal: 0.5 % of the mean for the
//    spread of loads and contact angles between balls at every output time (measured: 4e-8 and
//    below). An asymmetry anywhere (ball indexing, pocket angles, a term in one coordinate only)
//    shows up here.
//  - Z Q sin(alpha) = F_a (the balls carry the axial load): the mean over the second half within
//    1 % (measured: -0.06 % deep groove, -0.26 % four-point, the rest being the axial component of
//    traction in the tilted contact planes), and at every output time within 1.5 %: the inner ring
//    vibrates axially (about 1.1 kHz, ~2 % of critical damping from Hunt-Crossley) after the start
//    and, in the deep-groove run, after all balls reach their pockets at once at 15.5 ms (the
//    start-up turns the cage at the epicyclic speed of the NOMINAL contact angle, 0, while the balls
//    roll at the operating angle, 12 deg: the cage lags by 0.8 %; traction then slips briefly).
//    Measured: 0.75 % deep groove (ring inertia force m a_z up to 0.65 % of F_a), 0.52 % four-point.
//  - the summary's mean inner-ring contact force balances F_a along z within 1 %.
void expect_axial_balance(const AxialOutcome& r, double fa) {
  EXPECT_LT(r.worst_load_spread, 5e-3);
  EXPECT_LT(r.worst_angle_spread, 5e-3);
  EXPECT_NEAR(r.mean_balance, fa, 1e-2 * fa);
  EXPECT_LT(r.worst_balance, 1.5e-2);
  EXPECT_NEAR(-r.summary.inner_ring_contact_force_n.at(2), fa, 1e-2 * fa);
}

TEST(SpatialPhysics, PureAxialLoadEqualBallsDeepGroove) {
  const BallSceneOptions o = axial_options(1000);
  const scene::Scene scene = test::deep_groove_scene(o);
  const AxialOutcome r = run_axial(scene, o.fz, "deep groove");
  EXPECT_GT(r.mean_angle, 5 * test::deg) << "an axially loaded deep-groove ball must run at a contact angle";
  expect_axial_balance(r, o.fz);

  // Against this file's quasi-static solution (inner ring displaced axially until Z Q sin(alpha) =
  // F_a). It leaves out the centrifugal force (m w_c^2 r_p = 1.4 N at 1000 rpm, which unloads the
  // inner contacts by about 1 N and turns their angle by ~0.1 %) and gyroscopic moments: 1 % on load
  // and angle (measured: see the printout).
  const test::QuasiStaticBearing qs(scene);
  std::vector<double> psi;
  for (int k = 0; k < qs.z; ++k) psi.push_back(2 * pi * k / qs.z);
  // Start beyond the axial play sqrt(A P_d) (A = r_gi + r_go - D) so that every contact is closed.
  const double play = std::sqrt((qs.rgi + qs.rgo - 2 * qs.rb) * qs.pd);
  const Vec3 c = qs.solve(psi, Vec3(0, 0, o.fz), Vec3(0, 0, 1.05 * play), {2});
  const auto ball = qs.ball(psi[0], c);
  const double alpha = std::acos(std::min(ball.cos_alpha, 1.0));
  std::printf("[ axial ] quasi-static: ring z %.4f um, ball load %.4f N at %.4f deg; dynamics / quasi-static - 1: "
              "load %.3g, angle %.3g\n",
              1e6 * c.z(), ball.load, alpha * 180 / pi, r.mean_load / ball.load - 1, r.mean_angle / alpha - 1);
  EXPECT_NEAR(r.mean_load, ball.load, 1e-2 * ball.load);
  EXPECT_NEAR(r.mean_angle, alpha, 1e-2 * alpha);

  // Cage speed: all balls roll at the same angle, so the cage turns at the kinematic speed of that
  // angle, omega_i / 2 (1 - D cos(alpha) / d_m), which /cage/rolling_speed reports; the nominal
  // (0 deg) epicyclic speed is off by D (1 - cos alpha) / d_m (0.4 % at 12 deg here).
  const double rolling = 0.5 * o.speed_rpm * pi / 30 * (1 - 2 * qs.rb * std::cos(r.mean_angle) / (2 * qs.rp));
  std::printf("[ axial ] cage %.6f rad/s; rolling speed %.6f rad/s (analytic at the mean angle %.6f); nominal "
              "epicyclic %.6f rad/s\n",
              r.mean_cage_speed, r.mean_rolling_speed, rolling, r.mean_epicyclic_speed);
  EXPECT_NEAR(r.mean_rolling_speed, rolling, 1e-6 * rolling);
  EXPECT_NEAR(r.mean_cage_speed, r.mean_rolling_speed, 1e-3 * rolling);
  EXPECT_GT(std::abs(r.mean_cage_speed - r.mean_epicyclic_speed), 2e-3 * rolling);
}

// Four-point bearing: each ball carries the load on one inner arc and the opposite outer arc; the
// other two arcs are open (two-point contact under a pure axial load).
TEST(SpatialPhysics, PureAxialLoadEqualBallsFourPoint) {
  const BallSceneOptions o = axial_options(2000);
  const AxialOutcome r = run_axial(test::four_point_scene(o), o.fz, "four-point");
  EXPECT_GT(r.mean_angle, 30 * test::deg) << "the loaded arcs of a four-point bearing run near 35 deg";
  EXPECT_EQ(r.worst_unloaded, 0.0) << "the second inner arc of a ball must stay open";
  expect_axial_balance(r, o.fz);
}

// ---------------------------------------------------------------------------------------------
// 2. Radial load at low speed against the quasi-static solution
// ---------------------------------------------------------------------------------------------

/// The radial scene: fy = -1000 N on the inner ring at 120 rpm. Centrifugal force m w_c^2 r_p =
/// 0.018 N and the gyroscopic moment are 3e-5 of the ball loads; the loads change with the ball
/// pass at the cage speed (4.8 rad/s), slowly against the ring's and balls' contact resonances
/// (kHz), so the dynamics follow the quasi-static solution.
scene::Scene radial_scene(double end_time) {
  BallSceneOptions o;
  o.fy = -1000;
  o.speed_rpm = 120;
  o.end_time = end_time;
  o.output_interval = 1e-3;
  return test::deep_groove_scene(o);
}

// The start-up state (Levenberg-Marquardt on ring and ball positions with the model's own contact
// functions, balls at 2 pi k / Z) against this file's solution (Newton on the ring displacement
// alone, each ball on its line of centres with the series stiffness K_eff): the same physics solved
// two ways. What separates them: the start-up's regularization springs (1e3 N/m on every unknown,
// ~1e-5 N), its centrifugal force at 120 rpm (0.018 N), the tabulated Hertz constants (1e-12), and
// the solvers' tolerances. 0.1 % of the largest ball load per ball and of the displacement
// (measured: 2e-5 and 5e-7).
TEST(SpatialPhysics, RadialLoadStartupMatchesQuasiStatic) {
  const scene::Scene scene = radial_scene(0.01);
  const test::QuasiStaticBearing qs(scene);
  const Model model = build_model(scene);
  const StartupReport start = initial_state(model, 0.0);
  std::vector<double> psi;
  for (int k = 0; k < qs.z; ++k) psi.push_back(2 * pi * k / qs.z);
  const Vec3 load(0, -1000, 0);
  const Vec3 c = qs.solve(psi, load, Vec3(0, -(0.5 * qs.pd + 1e-6), 0), {0, 1});
  const auto& ring = model.bodies[static_cast<std::size_t>(model.inner_ring)];
  const Vec3 c_start(start.state[static_cast<std::size_t>(ring.slot[sx])],
                     start.state[static_cast<std::size_t>(ring.slot[sy])], 0.0);
  double q_max = 0, worst = 0;
  for (int k = 0; k < qs.z; ++k) q_max = std::max(q_max, qs.ball(psi[static_cast<std::size_t>(k)], c).load);
  for (int k = 0; k < qs.z; ++k) {
    const double q = qs.ball(psi[static_cast<std::size_t>(k)], c).load;
    const auto kk = static_cast<std::size_t>(k);
    worst = std::max(worst, std::abs(start.inner_contact_force[kk] - q) / q_max);
    EXPECT_NEAR(start.inner_contact_force[kk], q, 1e-3 * q_max) << "ball " << k << " (inner contact)";
    EXPECT_NEAR(start.outer_contact_force[kk], q, 1e-3 * q_max) << "ball " << k << " (outer contact)";
  }
  std::printf("[ radial ] quasi-static: ring (%.5f, %.5f) um, Q_max %.4f N; start-up: ring (%.5f, %.5f) um, Q_max "
              "%.4f N; worst ball difference / Q_max %.3g\n",
              1e6 * c.x(), 1e6 * c.y(), q_max, 1e6 * c_start.x(), 1e6 * c_start.y(),
              *std::max_element(start.inner_contact_force.begin(), start.inner_contact_force.end()), worst);
  EXPECT_GT(q_max, 500.0) << "Stribeck: Q_max ~ 5 F_r / Z = 625 N";
  EXPECT_LT((c_start - c).norm(), 1e-3 * c.norm());
}

// The dynamics against the quasi-static solution at every output time: each ball's azimuth psi_k
// is read from /balls/position (about the outer ring's axis, which is fixed at the origin), the
// test solves its equilibrium for those azimuths, and compares
//  - the largest ball load with the largest quasi-static load: within 1 %;
//  - every ball's inner-groove load with its quasi-static load: within 1 % of Q_max (the loads at
//    the edge of the zone are small and steep in psi, so an error relative to the ball's own load
//    would measure the edge, not the physics);
//  - the inner ring's displacement with the quasi-static one: within 0.5 % of its magnitude.
// 0.3 s at 120 rpm: the cage turns 82 deg, so every position in the 45 deg ball spacing is visited
// and the ball at the bottom leaves it while the next one arrives. Measured: loads within 5e-4 of
// Q_max, ring within 5e-5 of its displacement; what separates them is dynamics (ball inertia in the
// load zone, damping, traction) and CVODE's tolerance (rtol 1e-6).
TEST(SpatialPhysics, RadialLoadMatchesQuasiStatic) {
  const scene::Scene scene = radial_scene(0.3);
  const test::QuasiStaticBearing qs(scene);
  test::TempDir dir;
  run::RunOptions options;
  options.output_path = dir.file("radial.h5");
  const auto wall = std::chrono::steady_clock::now();
  const run::RunSummary sum = run_scene(scene, options);
  const double run_seconds = seconds_since(wall);
  const auto time = test::read_dataset(options.output_path, "/time");
  const auto balls = test::read_dataset(options.output_path, "/balls/position");
  const auto ring = test::read_dataset(options.output_path, "/inner_ring/position");
  const auto q = read_segments(options.output_path, "ball_inner_groove", "normal_force");
  ASSERT_EQ(q.ball.size(), static_cast<std::size_t>(qs.z));
  const Vec3 load(0, -1000, 0);
  Vec3 c(0, -(0.5 * qs.pd + 1e-6), 0);
  double worst_max = 0, worst_ball = 0, worst_ring = 0, q_max_seen = 0, q_min_seen = 1e300;
  double psi_bottom_min = pi, psi_bottom_max = -pi;
  for (std::size_t i = 0; i < time.values.size(); ++i) {
    std::vector<double> psi;
    for (std::size_t k = 0; k < q.ball.size(); ++k) psi.push_back(std::atan2(balls.at(i, k, 1), balls.at(i, k, 0)));
    c = qs.solve(psi, load, c, {0, 1});
    std::vector<double> expected(psi.size());
    double q_max = 0, dyn_max = 0;
    std::size_t bottom = 0;
    for (std::size_t k = 0; k < psi.size(); ++k) {
      expected[k] = qs.ball(psi[k], c).load;
      if (expected[k] > q_max) q_max = expected[k], bottom = k;
      dyn_max = std::max(dyn_max, q.values.at(i, static_cast<std::size_t>(k)));
    }
    // The column order of the output is the ball order (checked above through ASSERT_EQ and here).
    for (std::size_t k = 0; k < psi.size(); ++k) {
      ASSERT_EQ(q.ball[k], static_cast<int>(k));
      worst_ball = std::max(worst_ball, std::abs(q.values.at(i, k) - expected[k]) / q_max);
    }
    worst_max = std::max(worst_max, std::abs(dyn_max - q_max) / q_max);
    const Vec3 c_dyn(ring.at(i, 0), ring.at(i, 1), 0.0);
    worst_ring = std::max(worst_ring, (c_dyn - c).norm() / c.norm());
    q_max_seen = std::max(q_max_seen, q_max), q_min_seen = std::min(q_min_seen, q_max);
    psi_bottom_min = std::min(psi_bottom_min, psi[bottom]), psi_bottom_max = std::max(psi_bottom_max, psi[bottom]);
  }
  std::printf("[ radial ] 120 rpm, 0.3 s (%zu outputs, cage %.2f rpm, %ld steps, %.2f s wall): quasi-static Q_max "
              "%.2f..%.2f N, most loaded ball at psi %.1f..%.1f deg; worst |Q_max dyn - Q_max qs| / Q_max %.3g; "
              "worst ball |Q - Q_qs| / Q_max %.3g; worst ring |c - c_qs| / |c_qs| %.3g\n",
              time.values.size(), sum.cage_speed_rpm, sum.stats.steps, run_seconds, q_min_seen, q_max_seen,
              psi_bottom_min * 180 / pi, psi_bottom_max * 180 / pi, worst_max, worst_ball, worst_ring);
  // The run must have swept the load zone: the most loaded ball's position spans the ball spacing.
  EXPECT_GT(psi_bottom_max - psi_bottom_min, 0.9 * 2 * pi / qs.z);
  EXPECT_LT(worst_max, 1e-2);
  EXPECT_LT(worst_ball, 1e-2);
  EXPECT_LT(worst_ring, 5e-3);
}
}  // namespace
}  // namespace raceway::bearing
