// Physics of the spatial ball-bearing model (solver/spatial_*.cpp) checked against results derived
// here, independently of the solver's own start-up:
//  1. pure axial load: every ball carries the same load at the same contact angle, and the balls
//     balance the axial load (Z Q sin(alpha) = F_a), deep groove and four-point;
//  2. radial load at low speed: ball loads and ring displacement against a quasi-static
//     equilibrium solved in this file (Hertz per ball, Newton on the ring displacement);
//  3. frame invariance: the whole problem turned about the bearing axis gives the same scalars and
//     rotated vectors;
//  4. SpatialEquations::jacobian against central differences of rhs over all states, and the
//     bordered structure (no ball-ball coupling) of the true Jacobian;
//  5. dense and bordered Newton solves give the same trajectory;
//  6. the contact forces and moments of the whole bearing sum to zero (action = reaction).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <cstdlib>
#include <cstdio>
#include <string>
#include <vector>

#include "contact/line_contact.hpp"
#include "contact/point_contact.hpp"
#include "scheduler/executor.hpp"
#include "solver/bordered_matrix.hpp"
#include "solver/integrator.hpp"
#include "solver/run.hpp"
#include "solver/spatial_equations.hpp"
#include "solver/spatial_model.hpp"
#include "solver/spatial_startup.hpp"
#include "solver_test_support.hpp"
#include "spatial_scene_builder.hpp"

namespace raceway::solver {
namespace {

using contact::Vec3;
using test::BallSceneOptions;
using test::pi;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// Per-segment diagnostic of one kind, with the ball index of each column.
struct SegmentSeries {
  test::Dataset values;       ///< [T x s]
  std::vector<int> ball;      ///< column -> ball
  std::vector<std::string> names;
};

SegmentSeries read_segments(const std::string& file, const std::string& kind, const std::string& diagnostic) {
  SegmentSeries s;
  s.values = test::read_dataset(file, "/segments/" + kind + "/" + diagnostic);
  const auto b = test::read_dataset(file, "/segments/" + kind + "/ball");
  for (double v : b.values) s.ball.push_back(static_cast<int>(std::lround(v)));
  s.names = test::read_strings(file, "/segments/" + kind + "/names");
  return s;
}

// ---------------------------------------------------------------------------------------------
// 1. Pure axial load
// ---------------------------------------------------------------------------------------------

struct AxialOutcome {
  double worst_load_spread = 0;   ///< max over times/balls of |Q_k - mean| / mean (loaded arcs)
  double worst_angle_spread = 0;  ///< same for |alpha_k|
  double worst_equilibrium = 0;   ///< max over times of |Z mean(Q sin alpha) - F_a| / F_a
  double worst_unloaded = 0;      ///< four-point: largest load on an arc that should be open [N]
  double mean_load = 0, mean_angle = 0;
  RunSummary summary;
};

/// Runs `scene` with a pure axial load F_a on the inner ring and measures, over the output times
/// of the second half, how equal the balls' loaded inner contacts are and how well they balance
/// F_a. For a four-point bearing each ball touches one inner arc and the opposite outer arc.
AxialOutcome run_axial(io::Scene scene, double fa, const char* label) {
  test::TempDir dir;
  RunOptions options;
  options.output_path = dir.file("axial.h5");
  const auto wall = std::chrono::steady_clock::now();
  AxialOutcome o;
  o.summary = run_spatial_scene(scene, options);
  if (std::getenv("SPDBG")) std::filesystem::copy_file(options.output_path, std::string("/tmp/sp_") + label + ".h5", std::filesystem::copy_options::overwrite_existing);
  const auto time = test::read_dataset(options.output_path, "/time");
  const auto q = read_segments(options.output_path, "ball_inner_groove", "normal_force");
  const auto angle = read_segments(options.output_path, "ball_inner_groove", "contact_angle");
  const int z = scene.bearing.rolling_elements;
  const std::size_t columns = q.ball.size();
  int samples = 0;
  for (std::size_t i = 0; i < time.values.size(); ++i) {
    if (time.values[i] < 0.5 * scene.scene.end_time - 1e-12) continue;
    // Loaded column of each ball: its inner arc with the larger load (the only one for deep groove).
    std::vector<double> load(static_cast<std::size_t>(z), 0.0), alpha(static_cast<std::size_t>(z), 0.0);
    std::vector<std::size_t> loaded(static_cast<std::size_t>(z), columns);
    for (std::size_t c = 0; c < columns; ++c) {
      const auto k = static_cast<std::size_t>(q.ball[c]);
      if (loaded[k] == columns || q.values.at(i, c) > q.values.at(i, loaded[k])) loaded[k] = c;
    }
    for (std::size_t c = 0; c < columns; ++c) {
      const auto k = static_cast<std::size_t>(q.ball[c]);
      if (c != loaded[k]) o.worst_unloaded = std::max(o.worst_unloaded, q.values.at(i, c));
    }
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
    o.worst_equilibrium = std::max(o.worst_equilibrium, std::abs(axial - fa) / fa);
    if (std::getenv("SPDBG")) std::printf("DBG t %.5f eq %+.5f\n", time.values[i], axial / fa - 1);
    o.mean_load += mean_q, o.mean_angle += mean_a, ++samples;
  }
  o.mean_load /= samples, o.mean_angle /= samples;
  std::printf("[ axial ] %s, F_a %g N: %d samples; mean ball load %.4f N at %.4f deg; spread of loads %.3g, of "
              "angles %.3g; worst |Z Q sin(a) - F_a| / F_a %.3g; unloaded arcs <= %.3g N; inner-ring contact "
              "force z %.4f N; %ld steps, %.2f s wall\n",
              label, fa, samples, o.mean_load, o.mean_angle * 180 / pi, o.worst_load_spread, o.worst_angle_spread,
              o.worst_equilibrium, o.worst_unloaded, o.summary.inner_ring_contact_force_n.at(2), o.summary.stats.steps,
              seconds_since(wall));
  EXPECT_GT(samples, 10);
  return o;
}

// Tolerances: 0.5 % of the mean for the spread between balls (the problem is exactly symmetric
// about the axis; what is left is the start-up transient of the dynamics: the balls start at the
// quasi-static seat with spins for rolling without sliding, and the inner ring's axial
// oscillation, excited by the remaining imbalance, is the same for every ball, so it does not
// spread the loads; the cage's clearance lets the balls drift apart in azimuth, which changes
// nothing by symmetry). 1 % for Z Q sin(alpha) = F_a at each output time: the inner ring's inertia
// times its axial acceleration and the axial components of traction are the only other axial
// forces on it, both small once the start-up transient has decayed.
TEST(SpatialPhysics, PureAxialLoadEqualBallsDeepGroove) {
  BallSceneOptions o;
  o.fz = 1000;
  o.speed_rpm = 1000;
  o.end_time = 0.02;
  o.output_interval = 1e-4;
  const AxialOutcome r = run_axial(test::deep_groove_scene(o), o.fz, "deep groove");
  EXPECT_GT(r.mean_angle, 5 * test::deg) << "an axially loaded deep-groove ball must run at a contact angle";
  EXPECT_LT(r.worst_load_spread, 5e-3);
  EXPECT_LT(r.worst_angle_spread, 5e-3);
  EXPECT_LT(r.worst_equilibrium, 1e-2);
  // The summary's mean contact force on the inner ring balances the load along z.
  EXPECT_NEAR(-r.summary.inner_ring_contact_force_n.at(2), o.fz, 1e-2 * o.fz);
}

TEST(SpatialPhysics, PureAxialLoadEqualBallsFourPoint) {
  BallSceneOptions o;
  o.fz = 2000;
  o.speed_rpm = 1000;
  o.end_time = 0.02;
  o.output_interval = 1e-4;
  const AxialOutcome r = run_axial(test::four_point_scene(o), o.fz, "four-point");
  EXPECT_GT(r.mean_angle, 30 * test::deg) << "the loaded arcs of a four-point bearing run near 35 deg";
  EXPECT_LT(r.worst_load_spread, 5e-3);
  EXPECT_LT(r.worst_angle_spread, 5e-3);
  EXPECT_LT(r.worst_equilibrium, 1e-2);
  // Two-point contact: the other inner arc of every ball is open under a pure axial load.
  EXPECT_EQ(r.worst_unloaded, 0.0);
  EXPECT_NEAR(-r.summary.inner_ring_contact_force_n.at(2), o.fz, 1e-2 * o.fz);
}

}  // namespace
}  // namespace raceway::solver
