// The rotating carrier frame (seed 003 eq. 1-6; solver/bearing/carrier_frame.hpp) against the same
// motion in the inertial frame. A roller free of contacts moves on a straight line at constant speed
// and spins at a constant absolute rate in the inertial frame; seen from a carrier that turns at an
// accelerating speed (so the Euler term is on) its path, velocity and spin follow by an analytic
// rotation. The planar dynamics, integrated in the carrier frame with the centrifugal, Coriolis and
// Euler terms, must reproduce them. Then the frame terms' Jacobian against central differences of
// the right-hand side of a whole bearing, and a scene without [carrier] unchanged by the frame code.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "scheduler/executor.hpp"
#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/carrier_frame.hpp"
#include "solver/bearing/equations.hpp"
#include "solver/bearing/startup.hpp"
#include "solver/numerics/bordered_matrix.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

// The carrier: R_c = 0.1 m, speed psi'(t) = w0 + a t (a linear ramp through t = 0 held beyond
// +-1 s), so psi(t) = w0 t + a t^2 / 2 with psi(0) = 0: at t = 0 the frames coincide.
constexpr double carrier_radius = 0.1;
constexpr double w0 = 100.0;     // rad/s
constexpr double ramp = 2.0e4;   // rad/s^2: 100 -> 300 rad/s in 10 ms

scene::Scene planetary_seed002() {
  scene::Scene s = test::load_seed002_former_solver();
  s.gravity = false;
  s.carrier.present = true;
  s.carrier.radius = carrier_radius;
  s.carrier.speed = scene::TimeFunction{{-1.0, 1.0}, {w0 - ramp, w0 + ramp}};
  return s;
}

double carrier_angle(double t) { return w0 * t + 0.5 * ramp * t * t; }
double carrier_speed(double t) { return w0 + ramp * t; }

/// A vector of the carrier frame from the inertial one: rotation by -psi.
Eigen::Vector2d to_carrier(const Eigen::Vector2d& v, double psi) {
  return {std::cos(psi) * v.x() + std::sin(psi) * v.y(), -std::sin(psi) * v.x() + std::cos(psi) * v.y()};
}

/// State of one free body: x, y, vx, vy, w (bearing frame, relative to it).
using Free = std::array<double, 5>;

TEST(CarrierFrame, FreeRollerMatchesTheInertialFrame) {
  const scene::Scene scene = planetary_seed002();
  const Model m = build_model(scene);
  const auto dynamics = make_body_dynamics(m);
  const int b = m.first_element;
  const Body& roller = m.bodies[static_cast<std::size_t>(b)];
  ASSERT_GE(roller.slot[sx], 0);
  ASSERT_GE(roller.slot[swz], 0);

  // The derivative of a free body's state from the model's dynamics (no contacts).
  std::vector<double> z(static_cast<std::size_t>(m.state_size), 0.0), zdot(z.size(), 0.0);
  const auto rates = [&](double t, const Free& s) {
    const int idx[5] = {roller.slot[sx], roller.slot[sy], roller.slot[svx], roller.slot[svy], roller.slot[swz]};
    for (int i = 0; i < 5; ++i) z[static_cast<std::size_t>(idx[i])] = s[static_cast<std::size_t>(i)];
    Wrench net;
    dynamics->rates(b, t, z.data(), Wrench{}, net, zdot.data());
    Free d;
    d[0] = zdot[static_cast<std::size_t>(roller.slot[sx])];
    d[1] = zdot[static_cast<std::size_t>(roller.slot[sy])];
    d[2] = zdot[static_cast<std::size_t>(roller.slot[svx])];
    d[3] = zdot[static_cast<std::size_t>(roller.slot[svy])];
    d[4] = zdot[static_cast<std::size_t>(roller.slot[swz])];
    return d;
  };

  // Start: 20 mm from the bearing axis, moving at 3 m/s and 5 m/s relative to the frame, spinning.
  const Free start{0.02, -0.01, 3.0, 5.0, 40.0};
  const Eigen::Vector2d p0(carrier_radius + start[0], start[1]);
  const Eigen::Vector2d v0 = Eigen::Vector2d(start[2], start[3]) + carrier_speed(0) * Eigen::Vector2d(-p0.y(), p0.x());
  const double w_abs = start[4] + carrier_speed(0);

  // Classical RK4 (a few lines; the model is a 5-state linear ODE here), 10 ms in 20000 steps:
  // psi' dt <= 1.5e-4, local error ~ (psi' dt)^5, far below the tolerances.
  const double end = 0.01;
  const int steps = 20000;
  const double h = end / steps;
  Free s = start;
  for (int i = 0; i < steps; ++i) {
    const double t = i * h;
    const auto add = [](const Free& a, const Free& d, double f) {
      Free r;
      for (std::size_t k = 0; k < 5; ++k) r[k] = a[k] + f * d[k];
      return r;
    };
    const Free k1 = rates(t, s), k2 = rates(t + h / 2, add(s, k1, h / 2)), k3 = rates(t + h / 2, add(s, k2, h / 2)),
               k4 = rates(t + h, add(s, k3, h));
    for (std::size_t k = 0; k < 5; ++k) s[k] += h / 6 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
  }

  // The inertial straight line, seen from the carrier at t = end.
  const double psi = carrier_angle(end), wc = carrier_speed(end);
  const Eigen::Vector2d p = to_carrier(p0 + v0 * end, psi);
  const Eigen::Vector2d v = to_carrier(v0, psi) - wc * Eigen::Vector2d(-p.y(), p.x());
  std::printf("[ carrier ] after %.0f deg of carrier rotation: position error %.3g m, velocity error %.3g m/s, "
              "spin error %.3g rad/s\n",
              psi * 180 / test::pi, std::hypot(s[0] + carrier_radius - p.x(), s[1] - p.y()),
              std::hypot(s[2] - v.x(), s[3] - v.y()), s[4] - (w_abs - wc));
  ASSERT_GT(psi, 1.5);  // the frame has turned by a good part of a revolution
  EXPECT_NEAR(s[0] + carrier_radius, p.x(), 1e-10);
  EXPECT_NEAR(s[1], p.y(), 1e-10);
  EXPECT_NEAR(s[2], v.x(), 1e-8);
  EXPECT_NEAR(s[3], v.y(), 1e-8);
  EXPECT_NEAR(s[4], w_abs - wc, 1e-8);
  // The relative path is far from the inertial one: the frame terms are not small here.
  EXPECT_GT(std::hypot(s[0] - (p0.x() + v0.x() * end - carrier_radius), s[1] - (p0.y() + v0.y() * end)), 1e-2);
}

// The frame terms are linear in the state: the Jacobian the model assembles with the carrier minus
// the one without must equal the same difference of central differences of the right-hand side
// (the contact parts, identical in both, cancel).
TEST(CarrierFrame, JacobianTermsMatchCentralDifferences) {
  scene::Scene inertial = test::load_seed002_former_solver();
  inertial.gravity = false;
  const scene::Scene rotating = planetary_seed002();
  const Model mi = build_model(inertial), mr = build_model(rotating);
  scheduler::SerialExecutor ei, er;
  Equations eqi(mi, ei), eqr(mr, er);
  const std::vector<double> z = initial_state(mi, 0.0).state;
  const double t = 0.004;  // carrier at 180 rad/s, accelerating
  const int nb = mi.border_size, blocks = mi.element_count, bs = (mi.state_size - nb) / blocks;
  numerics::BorderedMatrix ji(nb, blocks, bs), jr(nb, blocks, bs);
  ASSERT_EQ(eqi.jacobian(t, z.data(), ji), 0);
  ASSERT_EQ(eqr.jacobian(t, z.data(), jr), 0);
  const Eigen::MatrixXd model_difference = jr.to_dense() - ji.to_dense();
  const Eigen::MatrixXd fd_difference =
      test::central_difference_jacobian(eqr, mr, t, z) - test::central_difference_jacobian(eqi, mi, t, z);
  const double w = carrier_speed(t);
  ASSERT_GT(model_difference.cwiseAbs().maxCoeff(), 0.99 * w * w);  // the terms are there
  const double error = (model_difference - fd_difference).cwiseAbs().maxCoeff();
  std::printf("[ carrier ] Jacobian frame terms: largest %.4g, largest error against central differences %.3g\n",
              model_difference.cwiseAbs().maxCoeff(), error);
  // Round-off of the contact terms (~1e11 1/s^2) in both differences: measured 0.36; the smallest
  // frame term, the Coriolis 2 psi' = 360 1/s, is a thousand times larger.
  EXPECT_LT(error, 1e-4 * w * w);
  // Each roller's velocity rows: d(ax)/dx = psi'^2, d(ax)/dvy = 2 psi', d(ay)/dx = -psi''.
  const Body& r = mr.bodies[static_cast<std::size_t>(mr.first_element)];
  // (Differences of sums with the contact stiffness, ~1e11 1/s^2: round-off ~1e-5.)
  EXPECT_NEAR(model_difference(r.slot[svx], r.slot[sx]), w * w, 1e-6 * w * w);
  EXPECT_NEAR(model_difference(r.slot[svx], r.slot[svy]), 2 * w, 1e-6 * w * w);
  EXPECT_NEAR(model_difference(r.slot[svy], r.slot[sx]), -ramp, 1e-6 * w * w);
}

// Without [carrier] the scene's carrier is absent and the frame adds nothing: the rates of a
// bearing are those of the inertial equations, bit for bit (the reference runs check whole runs).
TEST(CarrierFrame, AbsentCarrierChangesNothing) {
  const scene::Scene scene = test::load_seed002_former_solver();
  EXPECT_FALSE(scene.carrier.present);
  EXPECT_FALSE(carrier_frame(scene.carrier, 0.0).has_value());
  scene::Scene zero_speed = scene;  // a carrier at rest at any radius: the same rates
  zero_speed.carrier = {true, 0.2, scene::TimeFunction::constant(0.0)};
  const Model a = build_model(scene), c = build_model(zero_speed);
  scheduler::SerialExecutor ea, ec;
  Equations eqa(a, ea), eqc(c, ec);
  const std::vector<double> z = initial_state(a, 0.0).state;
  std::vector<double> fa(z.size()), fc(z.size());
  ASSERT_EQ(eqa.rhs(0.001, z.data(), fa.data()), 0);
  ASSERT_EQ(eqc.rhs(0.001, z.data(), fc.data()), 0);
  for (std::size_t i = 0; i < z.size(); ++i) EXPECT_EQ(fa[i], fc[i]) << a.state_name[i];
}

}  // namespace
}  // namespace raceway::bearing
