// A ball's own defect ([rolling_element], solver/bearing/ball_model.cpp, race_defects.cpp):
//  1. the model: without a ball defect the balls keep their 9 states and no orientation; with one,
//     every ball gets its 3 Cardan angles (equal blocks) and only the defective ball's groove laws
//     carry the defect;
//  2. the angles turn with the ball: the rates the dynamics give move R = Rx Ry Rz as dR/dt = [w]x R
//     (against a finite difference of the rotation), so a point fixed on the ball follows the ball;
//  3. the step limit: a ball's spall turning towards a contact limits the step to the time it takes
//     to reach the contact's edge at the ball's spin;
//  4. the Jacobian with a ball's waviness under load against central differences of the right-hand
//     side, the ball's angle columns among them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "io/scene/scene_parser.hpp"
#include "scheduler/executor.hpp"
#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "solver/numerics/integrator.hpp"
#include "tests/support/solver_test_support.hpp"
#include "solver/bearing/model.hpp"
#include "solver/bearing/race_defects.hpp"

namespace raceway::bearing {
namespace {

using contact::Mat3;
using contact::Vec3;

constexpr const char* kScene = R"(
[scene]
name = "ball defect"
model = "spatial"
end_time = "0.01 s"
output_interval = "1 ms"
[bearing]
type = "deep_groove_ball"
rolling_elements = 9
ball_diameter = "7.94 mm"
inner_conformity = 0.52
outer_conformity = 0.53
pitch_diameter = "39.04 mm"
ring_width = "15 mm"
[cage]
guidance = "rolling_element"
pocket_clearance = "0.2 mm"
pocket_shape = "spherical"
[inner_ring]
motion = "driven"
speed = "1797 rpm"
load = { fy = "-500 N" }
[outer_ring]
motion = "fixed"
)";

constexpr const char* kSpall =
    "[rolling_element]\nspall = { element = 4, angle = \"30 deg\", length = \"0.5 mm\", width = \"1 mm\", depth = \"0.1 mm\" }\n";

Model model_of(const std::string& extra) {
  return build_model(scene::parse_scene(std::string(kScene) + extra, "test"));
}

TEST(BallDefect, OrientationStatesOnlyWithABallDefect) {
  const Model plain = model_of("");
  const Model spalled = model_of(kSpall);
  EXPECT_EQ(plain.block_size, 9);
  EXPECT_EQ(spalled.block_size, 12);
  EXPECT_EQ(spalled.state_size - plain.state_size, 3 * 9);
  for (int k = 0; k < 9; ++k) {
    const Body& p = plain.bodies[std::size_t(plain.first_element + k)];
    const Body& s = spalled.bodies[std::size_t(spalled.first_element + k)];
    EXPECT_FALSE(p.ball_orientation || p.has(sax) || p.has(saz));
    EXPECT_TRUE(s.ball_orientation && s.has(sax) && s.has(say) && s.has(saz));
  }
  for (const Segment& seg : spalled.segments) {
    if (seg.kind != SegmentKind::ball_inner_groove && seg.kind != SegmentKind::ball_outer_groove) continue;
    const auto& e = spalled.law<contact::BallGrooveSegment>(seg).element_imperfections;
    EXPECT_EQ(e != nullptr, seg.element == 4) << seg.name;
    if (e) {
      EXPECT_NEAR(e->spall.angle, std::numbers::pi / 6, 1e-15);
    }
  }
  EXPECT_TRUE(has_spall(spalled));
  EXPECT_FALSE(has_spall(plain));
}

// dR/dt = [w]x R: R(a + h da/dt) - R(a - h da/dt) over 2h against w x (each column of R), for a
// ball turned and spinning about a tilted axis; its kinematics' rotation is R(a).
TEST(BallDefect, AnglesTurnWithTheBall) {
  const Model m = model_of(kSpall);
  const int b = m.first_element + 4;
  const Body& ball = m.bodies[std::size_t(b)];
  std::vector<double> z(std::size_t(m.state_size), 0.0), zdot(z.size(), 0.0);
  const double a[3] = {0.3, -0.4, 2.0};
  const Vec3 w(150.0, -80.0, 1200.0);
  for (int d = 0; d < 3; ++d) z[std::size_t(ball.slot[sax + d])] = a[d], z[std::size_t(ball.slot[swx + d])] = w[d];
  const auto dynamics = make_body_dynamics(m);
  Wrench net;
  dynamics->rates(b, 0.0, z.data(), Wrench{}, net, zdot.data());
  const Mat3 r = cardan_rotation(a[0], a[1], a[2]);
  EXPECT_TRUE(m.kinematics(b, 0.0, z.data()).rotation.isApprox(r, 1e-15));
  const double h = 1e-7;
  auto at = [&](double s) {
    const double* rate = &zdot[std::size_t(ball.slot[sax])];
    return cardan_rotation(a[0] + s * rate[0], a[1] + s * rate[1], a[2] + s * rate[2]);
  };
  const Mat3 derivative = (at(h) - at(-h)) / (2 * h);
  for (int c = 0; c < 3; ++c) {
    const Vec3 expected = w.cross(r.col(c));
    EXPECT_NEAR((derivative.col(c) - expected).norm(), 0.0, 1e-6 * w.norm()) << c;
  }
}

// Ball 4 at rest on the pitch circle but for its spin w about z: both contact frames stand still
// (the inner ring's spin and the ball's azimuth rate relative to it cancel), the outer contact faces
// e_r of the ball's azimuth psi, the inner one -e_r. Its spall (30 deg round its equator) trails the
// outer contact by 0.5 rad: the limit is (0.5 rad - the spall's half angle) / w; at the contact, a
// tenth of the passage.
TEST(BallDefect, StepLimitStopsAtTheContact) {
  const Model m = model_of(kSpall);
  const int b = m.first_element + 4;
  const Body& ball = m.bodies[std::size_t(b)];
  std::vector<double> z(std::size_t(m.state_size), 0.0);
  const double psi = 2 * std::numbers::pi * 4 / 9, spin = 1000.0, r = 0.5 * 7.94e-3;
  z[std::size_t(ball.slot[sx])] = m.pitch_radius * std::cos(psi);
  z[std::size_t(ball.slot[sy])] = m.pitch_radius * std::sin(psi);
  z[std::size_t(ball.slot[swz])] = spin;
  const double half = 0.5 * 0.5e-3 / r, behind = 0.5;
  z[std::size_t(ball.slot[saz])] = psi - behind - std::numbers::pi / 6;  // the spall's centre at psi - 0.5
  EXPECT_NEAR(spall_step_limit(m, 0.0, z.data()), (behind - half) / spin, 1e-12);
  z[std::size_t(ball.slot[saz])] = psi - std::numbers::pi / 6;  // the spall at the outer contact
  EXPECT_NEAR(spall_step_limit(m, 0.0, z.data()), 2 * half / spin / steps_within_spall, 1e-12);
}

// Ball 6 starts near the bottom of the load zone (fy = -500 N on the inner ring); its waviness of
// order 2 (1 um) changes its contacts' approach with its angles. 2 ms into the run, the Jacobian
// (each element's block by forward differences through the ball's angle columns, and the bodies'
// own terms) against central differences of the whole right-hand side; ball 6's angle columns are
// not zero.
TEST(BallDefect, JacobianMatchesCentralDifferences) {
  const scene::Scene scene = scene::parse_scene(
      std::string(kScene) + "[rolling_element]\nwaviness = { element = 6, orders = [2], amplitudes = [\"1 um\"] }\n",
      "test");
  const Model m = build_model(scene);
  scheduler::SerialExecutor executor;
  Equations eq{m, executor};
  executor.attach(eq.task_catalogue());
  std::vector<double> z;
  const double t = 2e-3;  // past the start, whose spin accelerations are large
  numerics::Integrator integrator(eq, scene.solver, 0.0, initial_state(m, 0.0).state);
  integrator.advance_to(t, z);
  const Eigen::MatrixXd fd = test::central_difference_jacobian(eq, m, t, z);
  numerics::BorderedMatrix jac(m.border_size, m.element_count, m.block_size);
  ASSERT_EQ(eq.jacobian(t, z.data(), jac), 0);
  const Eigen::MatrixXd dense = jac.to_dense();
  double class_norm[4] = {0, 0, 0, 0};  // a near-zero column is measured against its class's largest
  for (int j = 0; j < m.state_size; ++j) {
    double& c = class_norm[static_cast<int>(m.state_class[std::size_t(j)])];
    c = std::max(c, fd.col(j).norm());
  }
  // A ball's angle columns: its spin rows (the moment about its centre, a sum of contact moments of
  // some 1e6 rad/s^2 that nearly cancel) carry the forward difference's round-off over its 1e-10 rad
  // step, some 50 rad/s^2 per rad against columns of some 3000: those rows within 5 %, the others
  // (positions, velocities, the other bodies) within 1e-3 as every other column.
  double worst = 0, worst_spin = 0;
  int worst_column = 0;
  for (int j = 0; j < m.state_size; ++j) {
    const double c = class_norm[static_cast<int>(m.state_class[std::size_t(j)])];
    Eigen::VectorXd diff = dense.col(j) - fd.col(j);
    const double ref = fd.col(j).norm(), scale = ref > 1e-9 * c ? ref : c;
    for (int k = m.first_element; k < static_cast<int>(m.bodies.size()); ++k) {
      const Body& b = m.bodies[std::size_t(k)];
      if (j < b.slot[sax] || j > b.slot[saz]) continue;
      for (int d = 0; d < 3; ++d) {
        worst_spin = std::max(worst_spin, std::abs(diff(b.slot[swx + d])) / scale);
        diff(b.slot[swx + d]) = 0.0;
      }
    }
    if (diff.norm() / scale > worst) worst = diff.norm() / scale, worst_column = j;
  }
  std::printf("[ ball defect ] worst column error %.3g (%s); a ball's spin rows over its angles: %.3g\n", worst,
              m.state_name[std::size_t(worst_column)].c_str(), worst_spin);
  EXPECT_LT(worst, 1e-3);
  EXPECT_LT(worst_spin, 5e-2);
  const Body& ball = m.bodies[std::size_t(m.first_element + 6)];
  EXPECT_GT(fd.col(ball.slot[saz]).norm(), 0.0) << "the waviness turns with the ball";
}

}  // namespace
}  // namespace raceway::bearing
