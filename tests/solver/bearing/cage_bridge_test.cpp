// Flexible cage bridges (solver/bearing/cage_bridges.hpp): each bar between two pockets is a beam
// clamped in the cage's side rings whose tangential deflection is a state.
//  - A roller pressed against its front bar: the bridge's static deflection under the pocket force
//    against the deflection of a clamped-clamped beam under a load spread along its span, the mean
//    of w(x) = q x^2 (L - x)^2 / (24 E I) integrated here by Simpson's rule (not the builder's
//    closed form), and the bridge force in the output equal to the pocket force.
//  - The bridge's free bending frequency against the exact first mode of a clamped-clamped beam,
//    (4.7300)^2 sqrt(E I / (m L^3)).
//  - The Jacobian of a bearing whose bars ride on bridges (shared slots, the force passed on to the
//    cage) against central differences of the right-hand side.
//  - Action and reaction: the contact forces and moments summed over all bodies vanish; the cage and
//    its bridges change their angular momentum by the moment of the contacts on them.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/cage_bridges.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

constexpr double thickness = 3.0e-3, height = 7.0e-3;  // the bridge section in the test scene

/// Seed 003's bearing without the carrier, flexible slender (Euler-Bernoulli) bridges of a given section, a dry
/// bar contact (the Timoshenko bar: thick_beams_test.cpp).
scene::Scene bridge_scene() {
  scene::Scene s = test::load_job_scene("seed003_no_carrier.toml");
  s.cage.bridges = scene::CageBridges::flexible;
  s.cage.bridge_theory = scene::BeamTheory::euler_bernoulli;
  s.cage.bridge_thickness = thickness;
  s.cage.bridge_height = height;
  s.roller_cage.normal.id = contact::LawId::palmgren;
  return s;
}

int segment_named(const Model& m, const std::string& name) {
  for (std::size_t s = 0; s < m.segments.size(); ++s)
    if (m.segments[s].name == name) return static_cast<int>(s);
  ADD_FAILURE() << "no segment " << name;
  return -1;
}

/// The start-up state at rest (every velocity and rate zero) with the cage centred at the origin
/// and roller 0 at the pitch radius, pushed `push` beyond its pocket clearance into its front bar.
std::vector<double> pressed_state(const Model& m, double push) {
  std::vector<double> z = initial_state(m, 0.0).state;
  for (std::size_t i = 0; i < z.size(); ++i)
    if (m.state_class[i] == VariableClass::velocity || m.state_class[i] == VariableClass::angular_velocity) z[i] = 0;
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  z[static_cast<std::size_t>(cage.slot[sx])] = 0;
  z[static_cast<std::size_t>(cage.slot[sy])] = 0;
  const double theta = z[static_cast<std::size_t>(cage.slot[saz])];
  const double half = 0.5 * m.params().cage.pocket_clearance;
  const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element)];
  z[static_cast<std::size_t>(roller.slot[sx])] = m.pitch_radius * std::cos(theta) - (half + push) * std::sin(theta);
  z[static_cast<std::size_t>(roller.slot[sy])] = m.pitch_radius * std::sin(theta) + (half + push) * std::cos(theta);
  return z;
}

TEST(CageBridge, StaticDeflectionMatchesTheClampedBeam) {
  const scene::Scene scene = bridge_scene();
  const Model m = build_model(scene);
  ASSERT_EQ(static_cast<int>(cage_bridges_of(m).size()), m.element_count);
  scheduler::SerialExecutor ex;
  Equations eq(m, ex);
  std::vector<double> z = pressed_state(m, 30e-6), zdot(z.size());
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  const CageBridge& bridge = *cage_bridges_of(m)[0];  // ahead of pocket 0
  const auto angle = static_cast<std::size_t>(bridge.angle_state());

  // The bridge's static deflection: its absolute angular acceleration (its own, relative to the
  // cage, plus the cage's) zero, by the secant method.
  auto acceleration = [&](double bending_angle) {
    z[angle] = bending_angle;
    EXPECT_EQ(eq.rhs(0.0, z.data(), zdot.data()), 0);
    return zdot[static_cast<std::size_t>(bridge.rate_state())] + zdot[static_cast<std::size_t>(cage.slot[swz])];
  };
  double a = 0, fa = acceleration(a), b = 1e-4, fb = acceleration(b);
  for (int i = 0; i < 60 && std::abs(b - a) > 1e-15; ++i) {
    const double c = b - fb * (b - a) / (fb - fa);
    a = b, fa = fb, b = c, fb = acceleration(c);
  }
  acceleration(b);
  const double deflection = m.pitch_radius * b;
  constexpr int force_field = contact::field_index(contact::line_diagnostic_fields, "normal_force");
  constexpr int approach_field = contact::field_index(contact::line_diagnostic_fields, "approach");
  const double pocket_force = eq.diagnostic(static_cast<std::size_t>(segment_named(m, "roller[0]/cage_bar_front")),
                                            force_field);
  const auto spring = static_cast<std::size_t>(segment_named(m, "cage_bridge[0]"));

  // The clamped-clamped beam under q = F / L: the mean of w(x) over the span, by Simpson's rule.
  const double e = scene.material(scene.cage.material).youngs_modulus;
  const double span = scene.cage.bar_width > 0 ? scene.cage.bar_width : scene.bearing.roller_length;
  const double inertia = height * thickness * thickness * thickness / 12.0;
  const double q = pocket_force / span;
  const int n = 2000;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double x = span * i / n;
    const double w = q * x * x * (span - x) * (span - x) / (24.0 * e * inertia);
    sum += (i == 0 || i == n ? 1.0 : (i % 2 ? 4.0 : 2.0)) * w;
  }
  const double beam_deflection = sum * (span / n) / 3.0 / span;
  std::printf("[ bridge ] pocket force %.1f N: bridge deflection %.4f um, clamped beam %.4f um (E %.3g GPa, "
              "section %.1f x %.1f mm, span %.1f mm)\n",
              pocket_force, 1e6 * deflection, 1e6 * beam_deflection, 1e-9 * e, 1e3 * thickness, 1e3 * height,
              1e3 * span);
  ASSERT_GT(pocket_force, 1000.0);             // a real pocket force
  ASSERT_GT(deflection, 1e-6);                 // and a real deflection
  EXPECT_LT(deflection, 30e-6);                // the bridge yields part of the push, not all
  // The bridge turns by b about the cage centre: the contact point slides along the bar by (half
  // the pocket clearance + push) b, which lengthens the moment arm by ~1e-6 of the pitch radius.
  EXPECT_NEAR(deflection, beam_deflection, 1e-5 * beam_deflection);
  // The bridge force in the output (/segments/cage_bridge) is the pocket force, its approach the deflection.
  EXPECT_NEAR(eq.diagnostic(spring, force_field), pocket_force, 1e-5 * pocket_force);
  EXPECT_NEAR(eq.diagnostic(spring, approach_field), deflection, 1e-9 * deflection);
}

TEST(CageBridge, BendingFrequencyMatchesTheClampedBeamMode) {
  scene::Scene scene = bridge_scene();
  scene.cage.bridge_damping_ratio = 0;
  const Model m = build_model(scene);
  scheduler::SerialExecutor ex;
  Equations eq(m, ex);
  std::vector<double> z = pressed_state(m, -50e-6), zdot(z.size());  // roller 0 clear of its bars
  const CageBridge& bridge = *cage_bridges_of(m)[5];
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  const double phi = 1e-5;
  z[static_cast<std::size_t>(bridge.angle_state())] = phi;
  ASSERT_EQ(eq.rhs(0.0, z.data(), zdot.data()), 0);
  // On a cage held still: the bridge's absolute acceleration (relative plus the cage's).
  const double absolute = zdot[static_cast<std::size_t>(bridge.rate_state())] + zdot[static_cast<std::size_t>(cage.slot[swz])];
  const double omega = std::sqrt(-absolute / phi);
  const double e = scene.material(scene.cage.material).youngs_modulus;
  const double span = scene.bearing.roller_length;
  const double mass = scene.material(scene.cage.material).density * thickness * height * span;
  const double inertia = height * thickness * thickness * thickness / 12.0;
  const double beta_l = 4.730040745;  // first root of cos(x) cosh(x) = 1
  const double exact = beta_l * beta_l * std::sqrt(e * inertia / (mass * span * span * span));
  std::printf("[ bridge ] first bending frequency %.1f Hz, exact clamped-clamped beam %.1f Hz\n",
              omega / (2 * test::pi), exact / (2 * test::pi));
  EXPECT_GT(omega, exact);  // Rayleigh's quotient bounds the first mode from above
  EXPECT_LT(omega, 1.005 * exact);
}

TEST(CageBridge, JacobianMatchesCentralDifferences) {
  const scene::Scene scene = bridge_scene();
  const Model m = build_model(scene);
  scheduler::SerialExecutor ex;
  Equations eq(m, ex);
  std::vector<double> z = pressed_state(m, 20e-6);
  const CageBridge& bridge = *cage_bridges_of(m)[0];
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  z[static_cast<std::size_t>(bridge.angle_state())] = 1e-4;
  z[static_cast<std::size_t>(bridge.rate_state())] = 3.0;  // and moving: the damper works
  const int nb = m.border_size, blocks = m.element_count, bs = m.block_size;
  numerics::BorderedMatrix jac(nb, blocks, bs);
  ASSERT_EQ(eq.jacobian(0.0, z.data(), jac), 0);
  const Eigen::MatrixXd model = jac.to_dense();
  const Eigen::MatrixXd fd = test::central_difference_jacobian(eq, m, 0.0, z);
  // The border (cage, bridges) and roller 0's block, which presses on bridge 0. (The other rollers
  // sit at the onset of their race contacts, where a central difference straddles the kink.)
  const Body& roller = m.bodies[static_cast<std::size_t>(m.first_element)];
  const int n = roller.offset + roller.size;
  const double scale = fd.topLeftCorner(n, n).cwiseAbs().maxCoeff();
  Eigen::Index worst_row = 0, worst_col = 0;
  const double error = (model - fd).topLeftCorner(n, n).cwiseAbs().maxCoeff(&worst_row, &worst_col);
  std::printf("[ bridge ] largest error at d %s / d %s: %.6g against %.6g\n",
              m.state_name[static_cast<std::size_t>(worst_row)].c_str(),
              m.state_name[static_cast<std::size_t>(worst_col)].c_str(), model(worst_row, worst_col),
              fd(worst_row, worst_col));
  std::printf("[ bridge ] Jacobian: largest entry %.4g, largest error against central differences %.3g\n", scale,
              error);
  // The entries that carry the bridge: its acceleration from its angle and from the roller's
  // position, the cage's acceleration from the roller's position (the force passed on).
  for (const auto& [row, col] : {std::pair{bridge.rate_state(), bridge.angle_state()}, {bridge.rate_state(), roller.slot[sx]},
                                 {cage.slot[svx], roller.slot[sx]}, {cage.slot[swz], bridge.angle_state()},
                                 {bridge.rate_state(), cage.slot[saz]}}) {
    ASSERT_GT(std::abs(fd(row, col)), 1.0) << m.state_name[static_cast<std::size_t>(row)];
    EXPECT_NEAR(model(row, col), fd(row, col), 1e-4 * std::abs(fd(row, col)))
        << m.state_name[static_cast<std::size_t>(row)] << " / " << m.state_name[static_cast<std::size_t>(col)];
  }
  EXPECT_LT(error, 1e-5 * scale);
}

TEST(CageBridge, ActionEqualsReaction) {
  const scene::Scene scene = bridge_scene();
  const Model m = build_model(scene);
  scheduler::SerialExecutor ex;
  Equations eq(m, ex);
  std::vector<double> z = pressed_state(m, 20e-6), zdot(z.size());
  const CageBridge& bridge = *cage_bridges_of(m)[0];
  z[static_cast<std::size_t>(bridge.rate_state())] = 3.0;
  ASSERT_EQ(eq.rhs(0.0, z.data(), zdot.data()), 0);
  // Every segment's wrenches on A and B: equal and opposite forces, moments balanced about the origin.
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  double moment = 0, largest = 0;
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const double* rec = eq.segment_records().data() + s * SegmentRecord::size;
    for (int side = 0; side < 2; ++side) {
      const double* w = rec + (side == 0 ? SegmentRecord::on_a : SegmentRecord::on_b);
      const Segment& seg = m.segments[s];
      const auto k = m.planar_kinematics(side == 0 ? seg.body_a : seg.body_b, 0.0, z.data());
      force += Eigen::Vector3d(w[0], w[1], w[2]);
      moment += w[5] + k.x * w[1] - k.y * w[0];
      largest = std::max(largest, std::hypot(w[0], w[1]));
    }
  }
  ASSERT_GT(largest, 1000.0);
  EXPECT_LT(force.norm(), 1e-9 * largest);
  EXPECT_LT(std::abs(moment), 1e-9 * largest * m.pitch_radius);

  // The cage with its bridges: the rate of their angular momentum about the cage centre is the
  // moment of the contacts on them (the bridge springs are internal). A bridge's angle and rate
  // are relative to the cage's, so its absolute acceleration is its own plus the cage's.
  const Body& cage = m.bodies[static_cast<std::size_t>(m.cage)];
  const double cage_rate = zdot[static_cast<std::size_t>(cage.slot[swz])];
  double momentum_rate = cage.axial_inertia * cage_rate, external = 0;
  for (const CageBridge* b : cage_bridges_of(m))
    momentum_rate += b->inertia() * (cage_rate + zdot[static_cast<std::size_t>(b->rate_state())]);
  for (std::size_t s = 0; s < m.segments.size(); ++s) {
    const Segment& seg = m.segments[s];
    if (seg.kind == SegmentKind::cage_bridge) continue;
    const double* rec = eq.segment_records().data() + s * SegmentRecord::size;
    const auto on_cage = [&](int b) { return b == m.cage; };  // the bars ride on the bridges, which move with it
    if (on_cage(seg.body_a)) external += rec[SegmentRecord::on_a + 5];
    if (on_cage(seg.body_b)) external += rec[SegmentRecord::on_b + 5];
  }
  std::printf("[ bridge ] cage and bridges: angular momentum rate %.6g N m, contact moment %.6g N m\n", momentum_rate,
              external);
  ASSERT_GT(std::abs(external), 10.0);
  EXPECT_NEAR(momentum_rate, external, 1e-9 * std::abs(external));
}

}  // namespace
}  // namespace raceway::bearing
