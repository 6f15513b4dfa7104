// A spatial roller's own dynamics (solver/bearing/spatial_dynamics.cpp): a body of revolution whose
// axis a = Rx(ax) Ry(ay) e_z turns with its angular velocity w (bearing frame), Euler's equations
// I dw/dt = M - w x (I w), I = I_t (1 - a a^T) + I_a a a^T. Free of contacts and gravity it is a
// torque-free symmetric top, whose motion is known in closed form: the angular momentum L = I w
// and the kinetic energy stay constant, the spin a . w stays constant, and the axis turns about L
// at the rate |L| / I_t (nutation cone fixed). Integrated here with RK4 from the rates alone, the
// roller's state driven far from its rolling one (a 0.3 rad tilt, w off its axis).
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "io/scene/scene_parser.hpp"
#include "solver/bearing/body_dynamics.hpp"
#include "solver/bearing/model.hpp"
#include "tests/support/solver_test_support.hpp"

namespace raceway::bearing {
namespace {

using contact::Mat3;
using contact::Vec3;

constexpr const char* kScene = R"(
[scene]
name = "one roller"
model = "spatial"
end_time = "0.01 s"
output_interval = "1 ms"
[bearing]
type = "cylindrical_roller"
rolling_elements = 10
roller_diameter = "5 mm"
roller_length = "12 mm"
pitch_diameter = "40 mm"
radial_clearance = "20 um"
roller_end = "spherical"
[cage]
guidance = "rolling_element"
pocket_clearance = "0.1 mm"
[inner_ring]
motion = "driven"
speed = "0 rpm"
translation = "fixed"
axial = "fixed"
[outer_ring]
motion = "fixed"
)";

TEST(SpatialRollerDynamics, TorqueFreeSymmetricTop) {
  const Model m = build_model(scene::parse_scene(kScene, "one_roller.toml"));
  const auto dynamics = make_body_dynamics(m);
  const int b = m.first_element;
  const Body& roller = m.bodies[static_cast<std::size_t>(b)];
  ASSERT_GT(roller.transverse_inertia, roller.axial_inertia);  // a long roller: 12 mm against 5 mm
  const auto& sl = roller.slot;
  std::vector<double> z(static_cast<std::size_t>(m.state_size), 0.0);
  z[static_cast<std::size_t>(sl[sx])] = 0.02;
  z[static_cast<std::size_t>(sl[sax])] = 0.3, z[static_cast<std::size_t>(sl[say])] = -0.2;
  z[static_cast<std::size_t>(sl[swx])] = 40.0, z[static_cast<std::size_t>(sl[swy])] = -25.0;
  z[static_cast<std::size_t>(sl[swz])] = 600.0;
  auto axis = [&](const std::vector<double>& s) {
    // a = Rx(ax) Ry(ay) e_z, written out (the model's cardan_rotation is what is tested).
    const double ax = s[static_cast<std::size_t>(sl[sax])], ay = s[static_cast<std::size_t>(sl[say])];
    return Vec3(std::sin(ay), -std::sin(ax) * std::cos(ay), std::cos(ax) * std::cos(ay));
  };
  auto omega = [&](const std::vector<double>& s) {
    return Vec3(s[static_cast<std::size_t>(sl[swx])], s[static_cast<std::size_t>(sl[swy])], s[static_cast<std::size_t>(sl[swz])]);
  };
  auto momentum = [&](const std::vector<double>& s) {
    const Vec3 a = axis(s), w = omega(s);
    return Vec3(roller.transverse_inertia * (w - a.dot(w) * a) + roller.axial_inertia * a.dot(w) * a);
  };
  const Vec3 l0 = momentum(z);
  const double spin0 = axis(z).dot(omega(z)), energy0 = dynamics->body_energy(0.0, z.data());
  const double cone0 = axis(z).dot(l0.normalized());
  // The axis's precession about L, |L| / I_t: over the run it turns by this angle about L.
  const double precession = l0.norm() / roller.transverse_inertia;
  const Vec3 l_hat = l0.normalized();
  const Vec3 a0_perp = (axis(z) - cone0 * l_hat).normalized();
  auto rates = [&](double t, const std::vector<double>& s, std::vector<double>& out) {
    std::fill(out.begin(), out.end(), 0.0);
    Wrench net;
    dynamics->rates(b, t, s.data(), Wrench{}, net, out.data());
  };
  const double dt = 2e-6, end = 0.01;  // some 10 precession periods at |L| / I_t ~ 6000 rad/s
  int steps = static_cast<int>(std::lround(end / dt));
  for (int i = 0; i < steps; ++i) test::runge_kutta_step(rates, i * dt, dt, z);
  const Vec3 l1 = momentum(z);
  EXPECT_LT((l1 - l0).norm(), 1e-9 * l0.norm());
  EXPECT_NEAR(axis(z).dot(omega(z)), spin0, 1e-9 * std::abs(spin0));
  EXPECT_NEAR(dynamics->body_energy(end, z.data()), energy0, 1e-9 * energy0);
  EXPECT_NEAR(axis(z).dot(l_hat), cone0, 1e-9);  // the nutation cone
  // Where the axis is on its cone: turned by the precession angle about L.
  const Vec3 a1_perp = (axis(z) - axis(z).dot(l_hat) * l_hat).normalized();
  const double turned = std::atan2(a0_perp.cross(a1_perp).dot(l_hat), a0_perp.dot(a1_perp));
  const double expected = std::remainder(precession * end, 2 * std::numbers::pi);
  EXPECT_NEAR(turned, expected, 1e-6) << "precession rate " << precession << " rad/s";
  EXPECT_GT(std::abs(axis(z).dot(Vec3::UnitZ()) - std::cos(0.3) * std::cos(0.2)), 1e-3);  // the axis did move
}

// The per-thread memo of rotations (a roller's slices and Jacobian columns ask for its rotation
// again and again) returns exactly what cardan_rotation returns, whatever the order of the calls:
// angles that differ in one of the three only, in the last bit only, slots taken in turn.
TEST(MemoRotation, ReturnsCardanRotationsBitsWhateverTheOrderOfCalls) {
  const double a = 0.3, b = -0.2, c = 1.1;
  const double next = std::nextafter(b, 1.0);
  const double angles[][3] = {{a, b, c}, {a, b, 0.0}, {a, next, c}, {0.0, b, c}, {a, b, c}, {a, b, -0.0}};
  for (int round = 0; round < 2; ++round)
    for (std::size_t slot : {std::size_t{0}, std::size_t{7}, std::size_t{0}})
      for (const auto& x : angles) {
        const Mat3 memo = memo_rotation(slot, x[0], x[1], x[2]);
        const Mat3 direct = cardan_rotation(x[0], x[1], x[2]);
        for (int i = 0; i < 9; ++i)
          EXPECT_EQ(std::bit_cast<std::uint64_t>(memo.data()[i]), std::bit_cast<std::uint64_t>(direct.data()[i]))
              << "slot " << slot << " angles " << x[0] << " " << x[1] << " " << x[2];
      }
}

}  // namespace
}  // namespace raceway::bearing
