// The friction of a deep groove ball bearing's grooves against its analytic limit: under a radial
// load at zero contact angle a ball does not spin about its contact normals, and the planar contact
// ellipse of the ball-groove law (contact/laws/point_contact.hpp) then has no sliding to shear, so
// the grooves' friction power is the EHL rolling resistance of their contacts alone: each contact's
// Houpert force at its quasi-static load (tests/support/quasi_static_bearing.hpp, independent of the
// start-up and the dynamics; the outer contacts also carry the balls' centrifugal force) times the
// entrainment speed of pure rolling, omega_c r_o with omega_c = omega r_i / (r_i + r_o), averaged over
// the balls' positions. The run's grooves' power is the power balance's (integrated over the solver's
// steps), over the second half of one inner-ring revolution of the 6205 first scene without gravity.
// docs/validation_ball_bearings.md, "Friction torque", compares the whole torque with SKF's model; a
// law that adds the differential (Heathcote) slip of the groove's curved contact adds its loss to
// this limit, and the test then needs that term too.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "contact/laws/point_contact.hpp"
#include "io/scene/scene_parser.hpp"
#include "solver/run/run.hpp"
#include "tests/support/quasi_static_bearing.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::run {
namespace {

using test::pi;
using contact::Vec3;

/// Rolling-resistance power [W] of every groove contact of the bearing, averaged over `phases`
/// positions of the ball set across one ball spacing, in pure rolling at the inner ring's speed omega.
double rolling_resistance_power(const scene::Scene& s, double radial_load, double omega, int phases) {
  const test::QuasiStaticBearing qs(s);
  const double ri = qs.rp - qs.rb, ro = qs.rp + qs.rb;  // contact radii at zero contact angle
  const double cage = omega * ri / (ri + ro);
  const double entrainment = cage * ro;
  const auto& ball_material = s.materials.at(s.bearing.roller_material);
  const double mass = ball_material.density * 4.0 / 3.0 * pi * std::pow(qs.rb, 3);
  const double centrifugal = mass * cage * cage * qs.rp;
  const double rx_inner = 1.0 / (1.0 / qs.rb + 1.0 / ri), rx_outer = 1.0 / (1.0 / qs.rb - 1.0 / ro);
  const double ry_inner = 1.0 / (1.0 / qs.rb - 1.0 / qs.rgi), ry_outer = 1.0 / (1.0 / qs.rb - 1.0 / qs.rgo);
  const contact::PointLubricant oil{s.lubricant.viscosity, s.lubricant.pressure_viscosity,
                                    s.lubricant.limiting_shear_coefficient};
  // The law bounds F_R by the load (1/F = 1/F_R + 1/Q): a change of F_R / Q, kept here too.
  auto force = [&](double q, double rx, double ry) {
    const double f = contact::ehl_rolling_resistance(entrainment, q, rx, ry, qs.e_star, oil);
    return f > 0 ? f * q / (f + q) : 0.0;
  };
  double power = 0;
  Vec3 c(0, -15e-6, 0);  // beyond the radial play (6.25 um), where balls carry load
  for (int j = 0; j < phases; ++j) {
    std::vector<double> psi;
    for (int k = 0; k < qs.z; ++k) psi.push_back(2 * pi * (k + (j + 0.5) / phases) / qs.z);
    c = qs.solve(psi, Vec3(0, -radial_load, 0), c, {0, 1});
    for (const double p : psi) {
      const double q = qs.ball(p, c).load;
      power += (force(q, rx_inner, ry_inner) + force(q + centrifugal, rx_outer, ry_outer)) * entrainment;
    }
  }
  return power / phases;
}

TEST(GrooveFriction, IsTheRollingResistanceOfTheQuasiStaticLoadsAtZeroContactAngle) {
  const double radial_load = 1000, omega = 3000 * pi / 30;
  const std::vector<std::string> overrides = {"scene.gravity=false", "scene.end_time=20 ms",
                                              "scene.output_interval=0.5 ms", "output.segments=false",
                                              "inner_ring.load.fy=-1000 N"};
  const scene::Scene s =
      scene::load_scene(std::string(RACEWAY_SOURCE_DIR) + "/jobs/scenes/6205_first_scene.toml", overrides);
  ASSERT_TRUE(s.lubricant.viscosity > 0 && s.lubricant.pressure_viscosity > 0);
  test::TempDir dir;
  RunOptions options;
  options.output_path = dir.file("grooves.h5");
  run_scene(s, options);
  const test::Dataset time = test::read_dataset(options.output_path, "/time");
  const test::Dataset loss = test::read_dataset(options.output_path, "/power_balance/loss_work");
  const test::Dataset input = test::read_dataset(options.output_path, "/power_balance/input_work");
  const std::size_t first = time.values.size() / 2, last = time.values.size() - 1;
  const double window = time.values[last] - time.values[first];
  // Columns: the segment kinds in the model's order (ball_inner_groove, ball_outer_groove, ball_pocket),
  // then the supports and the nodes; the inputs' first column is the drive.
  auto power = [&](const test::Dataset& d, std::size_t column) {
    return (d.at(last, column) - d.at(first, column)) / window;
  };
  const double grooves = power(loss, 0) + power(loss, 1), pockets = power(loss, 2);
  const double expected = rolling_resistance_power(s, radial_load, omega, 24);
  const double torque = power(input, 0) / omega;
  std::printf("[ grooves ] %.4f W against %.4f W of rolling resistance (pockets %.4f W); drive torque over the "
              "window %.3f N mm, the rolling resistance's %.3f N mm\n",
              grooves, expected, pockets, 1e3 * torque, 1e3 * expected / omega);
  EXPECT_NEAR(grooves / expected, 1.0, 0.03);
}

}  // namespace
}  // namespace raceway::run
