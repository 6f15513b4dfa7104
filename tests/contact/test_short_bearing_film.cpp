// The short journal-bearing film of a cage on its land (contact/laws/short_bearing_film.hpp) against
// Ocvirk's published pi-film forces of a steady rotation, the squeeze integral by brute-force
// quadrature, frame invariance, the sum of rolling and squeeze that it is not, and the bounded,
// continuous passage to a closed film.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "contact/laws/short_bearing_film.hpp"

namespace raceway::contact {
namespace {

constexpr double pi = std::numbers::pi;

ShortBearingFilm land(int points = 64) {
  ShortBearingFilm f;
  f.viscosity = 0.02;
  f.radius = 60e-3;
  f.width = 8e-3;
  f.clearance = 0.2e-3;
  f.film_floor = 0;
  f.points = points;
  return f;
}

// Steady rotation, e along x: radial force mu w R L^3/c^2 eps^2/(1-eps^2)^2 back to the centre and
// tangential pi eps/(4 (1-eps^2)^1.5) in the sense of rotation (Ocvirk's short bearing, half-Sommerfeld;
// Hamrock, Fundamentals of Fluid Film Lubrication, ch. 20), with w the sum of the surfaces' speeds.
TEST(ShortBearingFilm, OcvirkSteadyForces) {
  const ShortBearingFilm f = land();
  const double journal = 300.0, bore = 20.0, sum = journal + bore;
  const double scale = f.viscosity * sum * f.radius * std::pow(f.width, 3) / (f.clearance * f.clearance);
  for (const double eps : {0.1, 0.5, 0.8, 0.95}) {
    const ShortBearingForce r = evaluate_short_bearing(f, {eps * f.clearance, 0.0}, {0.0, 0.0}, journal, bore);
    const double radial = scale * eps * eps / std::pow(1 - eps * eps, 2);
    const double tangential = scale * pi * eps / (4 * std::pow(1 - eps * eps, 1.5));
    std::printf("[ ocvirk ] eps %.2f: radial %.5g (closed %.5g), tangential %.5g (closed %.5g) N\n", eps,
                -r.on_journal[0], radial, r.on_journal[1], tangential);
    EXPECT_NEAR(-r.on_journal[0], radial, 0.01 * radial) << eps;
    EXPECT_NEAR(r.on_journal[1], tangential, 0.01 * tangential) << eps;
    // Petroff's Couette torque, 2 pi mu R^3 L (w_j - w_b) / (c sqrt(1 - eps^2)).
    const double petroff = 2 * pi * f.viscosity * std::pow(f.radius, 3) * f.width * (journal - bore) /
                           (f.clearance * std::sqrt(1 - eps * eps));
    EXPECT_NEAR(-r.couette_torque, petroff, 1e-6 * petroff);
  }
}

// Pure squeeze towards x: the film over cos(phi) > 0, F = -mu de/dt R L^3 / c^3 int cos^2 / (1 - eps
// cos)^3, the integral by Simpson's rule on 200000 intervals here.
TEST(ShortBearingFilm, SqueezeAgainstQuadrature) {
  const ShortBearingFilm f = land();
  const double rate = 0.02;  // m/s towards the wall
  for (const double eps : {0.0, 0.5, 0.9, 0.98}) {
    const int n = 200000;
    double integral = 0;
    for (int i = 0; i <= n; ++i) {
      const double phi = -pi / 2 + pi * i / n, c = std::cos(phi);
      integral += (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2)) * c * c / std::pow(1 - eps * c, 3);
    }
    integral *= pi / n / 3;
    const double expected = f.viscosity * rate * f.radius * std::pow(f.width, 3) / std::pow(f.clearance, 3) * integral;
    const ShortBearingForce r = evaluate_short_bearing(f, {eps * f.clearance, 0.0}, {rate, 0.0}, 0.0, 0.0);
    EXPECT_NEAR(-r.on_journal[0], expected, 0.005 * expected) << eps;
    EXPECT_NEAR(r.on_journal[1], 0.0, 1e-9 * expected) << eps;
    EXPECT_GT(r.power_loss, 0.0);
    // Separating: the same film cavitates on the other side and pulls nothing.
    const ShortBearingForce away = evaluate_short_bearing(f, {eps * f.clearance, 0.0}, {-rate, 0.0}, 0.0, 0.0);
    EXPECT_GE(away.on_journal[0], 0.0);
  }
  // At eps = 0: pi/2 exactly (the squeeze of a centred short bearing, half film).
  const ShortBearingForce centred = evaluate_short_bearing(f, {0.0, 0.0}, {rate, 0.0}, 0.0, 0.0);
  const double closed = f.viscosity * rate * f.radius * std::pow(f.width, 3) / std::pow(f.clearance, 3) * pi / 2;
  EXPECT_NEAR(-centred.on_journal[0], closed, 1e-3 * closed);
}

// The same motion seen in a rotated frame gives the rotated force; rolling and squeeze together
// differ from the sum of each alone (the cavitated arc moves).
TEST(ShortBearingFilm, FrameInvarianceAndNoSuperposition) {
  const ShortBearingFilm f = land();
  const std::array<double, 2> e{0.6 * f.clearance, 0.0}, rate{0.01, 0.004};
  const ShortBearingForce r = evaluate_short_bearing(f, e, rate, 400.0, 0.0);
  const double a = 1.1, c = std::cos(a), s = std::sin(a);
  const auto turn = [&](std::array<double, 2> v) { return std::array<double, 2>{c * v[0] - s * v[1], s * v[0] + c * v[1]}; };
  const ShortBearingForce t = evaluate_short_bearing(f, turn(e), turn(rate), 400.0, 0.0);
  const auto expected = turn(r.on_journal);
  const double size = std::hypot(r.on_journal[0], r.on_journal[1]);
  EXPECT_NEAR(t.on_journal[0], expected[0], 1e-12 * size);
  EXPECT_NEAR(t.on_journal[1], expected[1], 1e-12 * size);
  const ShortBearingForce roll = evaluate_short_bearing(f, e, {0.0, 0.0}, 400.0, 0.0);
  const ShortBearingForce squeeze = evaluate_short_bearing(f, e, rate, 0.0, 0.0);
  const double summed = std::hypot(roll.on_journal[0] + squeeze.on_journal[0], roll.on_journal[1] + squeeze.on_journal[1]);
  std::printf("[ short bearing ] joint %.5g N, sum of rolling and squeeze %.5g N\n", size, summed);
  EXPECT_GT(std::abs(summed / size - 1), 0.05);
}

// Film collapse: with a floor the force stays bounded and continuous as the eccentricity passes the
// clearance (the dry contact of the overlap adds from zero at touch, in the segment); without one
// the closed film carries nothing (the dry contact alone).
TEST(ShortBearingFilm, ContinuousPassageAtTheCriticalFilm) {
  ShortBearingFilm f = land(96);
  f.film_floor = 0.5e-6;
  double previous = 0;
  for (double gap = 5e-6; gap > -5e-6; gap -= 2e-8) {
    const ShortBearingForce r = evaluate_short_bearing(f, {f.clearance - gap, 0.0}, {0.0, 0.0}, 300.0, 0.0);
    ASSERT_TRUE(r.valid);
    const double force = std::hypot(r.on_journal[0], r.on_journal[1]);
    EXPECT_GE(r.minimum_film, f.film_floor);
    if (previous > 0) {
      EXPECT_GT(force, previous * (1 - 1e-9)) << gap;  // rises as the film closes
      EXPECT_LT(force, previous * 1.05) << gap;        // without a jump
    }
    previous = force;
  }
  // Bounded: deep in the overlap no more than at the floor's own film thickness.
  ShortBearingFilm bare = f;
  bare.film_floor = 0;
  const double at_floor = std::hypot(evaluate_short_bearing(bare, {f.clearance - 0.5e-6, 0.0}, {0, 0}, 300.0, 0.0).on_journal[0],
                                     evaluate_short_bearing(bare, {f.clearance - 0.5e-6, 0.0}, {0, 0}, 300.0, 0.0).on_journal[1]);
  EXPECT_LE(previous, at_floor * (1 + 1e-9));
  const ShortBearingForce closed = evaluate_short_bearing(bare, {f.clearance * 1.01, 0.0}, {0, 0}, 300.0, 0.0);
  EXPECT_TRUE(closed.valid);
  EXPECT_EQ(closed.on_journal[0], 0.0);  // no film: the dry contact alone
  EXPECT_FALSE(evaluate_short_bearing(f, {f.clearance, 0.0}, {NAN, 0}, 300.0, 0.0).valid);
}

// Quadrature: the Sommerfeld substitution resolves a nearly closed film with few points; 32 and 256
// points agree within 1 % at eps = 0.995.
TEST(ShortBearingFilm, QuadratureConverges) {
  const double eps = 0.995;
  const auto force = [&](int points) {
    const ShortBearingFilm f = land(points);
    const ShortBearingForce r = evaluate_short_bearing(f, {eps * f.clearance, 0.0}, {0.003, -0.002}, 300.0, -10.0);
    return std::hypot(r.on_journal[0], r.on_journal[1]);
  };
  EXPECT_NEAR(force(32), force(256), 0.01 * force(256));
  EXPECT_NEAR(force(64), force(256), 0.003 * force(256));
}

}  // namespace
}  // namespace raceway::contact
