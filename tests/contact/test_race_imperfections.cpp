// A race's spall and waviness (contact/laws/race_imperfections.hpp): the published ball path into a
// spall (limited by the ball radius and the spall's length and depth), its smooth variant, the
// spall's place on the race (wrapping at +-pi, its width), waviness, the height's azimuth slope
// against finite differences, and the ball-groove contact and a roller's slice seeing the height in
// their approach (the slice also in its approach rate, through its damping).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

#include "ball_cases.hpp"
#include "slice_cases.hpp"
#include "contact/laws/damping.hpp"
#include "contact/laws/element_imperfections.hpp"
#include "contact/laws/race_imperfections.hpp"
#include <Eigen/Geometry>

namespace raceway::contact::test {
namespace {

using std::numbers::pi;
constexpr double r = 0.5 * 7.94e-3;  // a 6205's ball

RaceSpall spall(double length, double depth, SpallEdge edge = SpallEdge::sharp) {
  return {.angle = 0.0, .length = length, .width = 1e-3, .depth = depth, .edge = edge};
}

// A short spall (CWRU's 0.007 in): the ball cannot reach its bottom; it drops by the sagitta of
// its radius over half the length. A long shallow one: the ball reaches the depth.
TEST(RaceSpall, EffectiveDepthIsLimitedByTheBallRadius) {
  const double L = 0.1778e-3;
  EXPECT_NEAR(spall_effective_depth(spall(L, 0.28e-3), r), r - std::sqrt(r * r - 0.25 * L * L), 1e-18);
  EXPECT_NEAR(spall_effective_depth(spall(L, 0.28e-3), r), 0.995e-6, 0.01e-6);  // by hand: L^2 / (8 r)
  EXPECT_EQ(spall_effective_depth(spall(2e-3, 5e-6), r), 5e-6);
}

// Sharp edges: the centre pivots on the leading edge, r - sqrt(r^2 - x^2), at most the depth, and
// symmetric over the trailing edge; nothing outside.
TEST(RaceSpall, SharpEdgePathPivotsOnTheEdges) {
  const RaceSpall s = spall(2e-3, 20e-6);
  for (const double x : {1e-4, 3e-4, 5e-4}) {
    const double expected = std::min(20e-6, r - std::sqrt(r * r - x * x));
    EXPECT_NEAR(spall_drop(s, r, x).drop, expected, 1e-18) << x;
    EXPECT_NEAR(spall_drop(s, r, s.length - x).drop, expected, 1e-18) << x;
  }
  EXPECT_EQ(spall_drop(s, r, 1e-3).drop, 20e-6);  // the bottom
  EXPECT_EQ(spall_drop(s, r, -1e-6).drop, 0.0);
  EXPECT_EQ(spall_drop(s, r, s.length + 1e-6).drop, 0.0);
  EXPECT_NEAR(spall_drop(s, r, 1e-9).drop, 0.0, 1e-15);  // continuous at the edge
}

// Smooth edges: a raised cosine to the same deepest drop, zero at both edges.
TEST(RaceSpall, SmoothEdgeIsARaisedCosine) {
  const RaceSpall s = spall(0.5e-3, 0.1e-3, SpallEdge::smooth);
  const double peak = spall_effective_depth(s, r);
  EXPECT_NEAR(spall_drop(s, r, 0.25e-3).drop, peak, 1e-18);
  EXPECT_NEAR(spall_drop(s, r, 0.125e-3).drop, 0.5 * peak, 1e-18);
  EXPECT_NEAR(spall_drop(s, r, 1e-12).drop, 0.0, 1e-18);
}

// The slope against central differences, both edges, over the sharp and the smooth path.
TEST(RaceSpall, SlopeIsTheDerivativeOfTheDrop) {
  for (const SpallEdge edge : {SpallEdge::sharp, SpallEdge::smooth}) {
    const RaceSpall s = spall(0.6e-3, 0.1e-3, edge);
    for (const double x : {0.02e-3, 0.1e-3, 0.22e-3, 0.41e-3, 0.55e-3}) {
      const double h = 1e-9;
      const double fd = (spall_drop(s, r, x + h).drop - spall_drop(s, r, x - h).drop) / (2 * h);
      EXPECT_NEAR(spall_drop(s, r, x).slope, fd, 1e-6 * std::abs(fd) + 1e-9) << x;
    }
  }
}

// On the race: centred at its angle, wrapping through +-pi, only within its width; waviness adds
// sum A cos(n theta + phase); the azimuth slope is the derivative of the height.
TEST(RaceHeight, SpallPlaceWidthAndWaviness) {
  RaceImperfections race;
  race.race_radius = 25.5e-3;
  race.ball_radius = r;
  race.has_spall = true;
  race.spall = spall(1e-3, 10e-6);
  race.spall.angle = pi;  // straddles +-pi
  const double half = 0.5e-3 / race.race_radius;
  EXPECT_EQ(race_height(race, pi, 0.0).height, -spall_drop(race.spall, r, 0.5e-3).drop);
  EXPECT_NEAR(race_height(race, -pi + 0.5 * half, 0.0).height, -spall_drop(race.spall, r, 0.75e-3).drop, 1e-15);
  EXPECT_EQ(race_height(race, pi - 1.01 * half, 0.0).height, 0.0);
  EXPECT_EQ(race_height(race, pi, 0.6e-3).height, 0.0);  // outside its width (1 mm)
  race.waviness = {{3, 11}, {1e-6, 0.5e-6}, {0.2, -1.0}};
  for (const double theta : {0.3, 1.7, -2.2}) {
    const double expected = 1e-6 * std::cos(3 * theta + 0.2) + 0.5e-6 * std::cos(11 * theta - 1.0);
    EXPECT_NEAR(race_height(race, theta, 0.0).height, expected, 1e-18);
  }
  for (const double theta : {pi - 0.8 * half, pi - 0.1 * half, 2.0}) {
    const double h = 1e-8;
    const double fd = (race_height(race, theta + h, 0.0).height - race_height(race, theta - h, 0.0).height) / (2 * h);
    EXPECT_NEAR(race_height(race, theta, 0.0).per_azimuth, fd, 1e-5 * std::abs(fd) + 1e-12) << theta;
  }
}

// The ball-groove contact sees the height in its approach, at the ball's azimuth in the ring's
// own frame (its spin angle taken off): a ball over the spall carries the force of a perfect race
// at the approach less the drop; a race without imperfections is untouched.
TEST(RaceHeight, GrooveContactApproachFollowsTheRace) {
  using namespace ball;
  const SpatialCase c{"outer", Kind::groove, true, 0, PocketShape::cylindrical};
  const BallGrooveSegment perfect = std::get<BallGrooveSegment>(make_segment(c, {.damping = false, .traction = false}));
  const Groove g = groove_of(c);
  BallGrooveSegment defective = perfect;
  auto race = std::make_shared<RaceImperfections>();
  race->race_radius = g.centre_radius + g.groove_radius;
  race->ball_radius = ball_radius;
  race->has_spall = true;
  race->spall = {.angle = 0.4, .length = 2e-3, .width = 2e-3, .depth = 3e-6, .edge = SpallEdge::sharp};
  defective.imperfections = race;
  SpatialKinematics ring;
  ring.spin_angle = 0.5;  // the ring has turned by 0.5 rad: the spall sits at 0.9 rad in the bearing frame
  const double m = g.groove_radius - ball_radius, approach = 10e-6;
  auto ball_at = [&](double psi, double extra) {
    SpatialKinematics ball;
    ball.position = (g.centre_radius + m + approach + extra) * radial(psi);
    return ball;
  };
  const SpatialSegmentResult over = evaluate(defective, ring, ball_at(0.9, 0.0));
  EXPECT_NEAR(over.diagnostics.approach, approach - 3e-6, 1e-15);
  const SpatialSegmentResult same = evaluate(perfect, ring, ball_at(0.9, -3e-6));
  EXPECT_NEAR(over.diagnostics.normal_force, same.diagnostics.normal_force, 1e-9 * same.diagnostics.normal_force);
  const SpatialSegmentResult beside = evaluate(defective, ring, ball_at(0.4, 0.0));  // the spall's ring-frame angle
  const SpatialSegmentResult clean = evaluate(perfect, ring, ball_at(0.4, 0.0));
  EXPECT_EQ(beside.diagnostics.approach, clean.diagnostics.approach);
  EXPECT_EQ(beside.diagnostics.normal_force, clean.diagnostics.normal_force);
}

// A ball's own spall (element_imperfections.hpp) sits in the ball's frame and turns with the ball: a
// ball turned by beta about its z axis carries a spall at longitude alpha to the bearing-frame
// direction alpha + beta; the contact there sees the spall's full drop, the contact at alpha does not
// (any more), and a spall turned away from every contact leaves the height 0.
TEST(ElementHeight, TheDefectTurnsWithTheBall) {
  RaceImperfections e;
  e.race_radius = e.ball_radius = r;
  e.has_spall = true;
  e.spall = {.angle = 0.3, .length = 0.4e-3, .width = 0.4e-3, .depth = 0.1e-3, .edge = SpallEdge::smooth};
  const double peak = spall_effective_depth(e.spall, r);
  const Vec3 zero = Vec3::Zero();
  auto direction = [](double a) { return Vec3(std::cos(a), std::sin(a), 0.0); };
  for (const double beta : {0.0, 1.0, -2.5, 4.0}) {
    const Mat3 turned = Eigen::AngleAxisd(beta, Vec3::UnitZ()).toRotationMatrix();
    EXPECT_NEAR(element_height(e, turned, direction(0.3 + beta), zero, zero).height, -peak, 1e-15) << beta;
    if (beta != 0.0) {
      EXPECT_EQ(element_height(e, turned, direction(0.3), zero, zero).height, 0.0) << beta;
    }
    EXPECT_NEAR(element_spall_distance(e, turned, direction(0.3 + beta)), 0.0, 1e-7) << beta;
  }
  // Tilted about x by 90 deg: the equator stands in the bearing's (x, z) plane; the spall at
  // longitude 0.3 is at (cos 0.3, 0, sin 0.3) in the bearing frame.
  const Mat3 tilted = Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitX()).toRotationMatrix();
  EXPECT_NEAR(element_height(e, tilted, Vec3(std::cos(0.3), 0.0, std::sin(0.3)), zero, zero).height, -peak, 1e-15);
  EXPECT_EQ(element_height(e, tilted, direction(0.3), zero, zero).height, 0.0);  // off its track (latitude 0.3)
}

// The height's rate as the ball turns under a fixed contact: d/dt h(R(t)^T n) against central
// differences of the height over the ball's rotation, for waviness round the equator (with a tilt
// of the ball's spin axis) and a contact frame that turns as well.
TEST(ElementHeight, RateIsTheDerivativeAlongTheMotion) {
  RaceImperfections e;
  e.race_radius = e.ball_radius = r;
  e.waviness = {.orders = {2, 5}, .amplitudes = {1e-6, 0.3e-6}, .phases = {0.2, -1.0}};
  const Vec3 w(30.0, -50.0, 900.0), frame(0.0, 0.0, 40.0);
  const Mat3 r0 = Eigen::AngleAxisd(0.7, Vec3(0.2, 0.1, 1.0).normalized()).toRotationMatrix();
  const Vec3 n0 = Vec3(0.6, -0.8, 0.05).normalized();
  auto at = [&](double t) {
    const Mat3 rot = Eigen::AngleAxisd(w.norm() * t, w.normalized()).toRotationMatrix() * r0;
    const Vec3 n = Eigen::AngleAxisd(frame.norm() * t, frame.normalized()).toRotationMatrix() * n0;
    return element_height(e, rot, n, frame, w).height;
  };
  const double h = 1e-7;
  const double rate = element_height(e, r0, n0, frame, w).rate;
  EXPECT_NEAR(rate, (at(h) - at(-h)) / (2 * h), 1e-6 * std::abs(rate) + 1e-12);
  EXPECT_GT(std::abs(rate), 1e-4);  // the waviness does pass the contact
}

// The groove contact's approach takes the ball's own height at the ball's side facing the race.
TEST(ElementHeight, GrooveContactApproachFollowsTheBall) {
  using namespace ball;
  const SpatialCase c{"inner", Kind::groove, false, 0, PocketShape::cylindrical};
  const BallGrooveSegment perfect = std::get<BallGrooveSegment>(make_segment(c, {.damping = false, .traction = false}));
  const Groove g = groove_of(c);
  BallGrooveSegment defective = perfect;
  auto e = std::make_shared<RaceImperfections>();
  e->race_radius = e->ball_radius = ball_radius;
  e->has_spall = true;
  e->spall = {.angle = 0.0, .length = 2e-3, .width = 2e-3, .depth = 2e-6, .edge = SpallEdge::sharp};
  defective.element_imperfections = e;
  const double m = g.groove_radius - ball_radius, approach = 10e-6, psi = 0.6;
  SpatialKinematics ring, ball;
  ball.position = (g.centre_radius - m - approach) * radial(psi);  // inside the inner groove's arc centre
  // The inner contact faces the bearing's axis, direction -e_r(psi): the ball turned by psi + pi brings its
  // spall (longitude 0) there.
  ball.rotation = Eigen::AngleAxisd(psi + std::numbers::pi, Vec3::UnitZ()).toRotationMatrix();
  const SpatialSegmentResult over = evaluate(defective, ring, ball);
  const SpatialSegmentResult clean = evaluate(perfect, ring, ball);
  EXPECT_NEAR(over.diagnostics.approach, clean.diagnostics.approach - 2e-6, 1e-15);
  ball.rotation = Mat3::Identity();  // unturned: the spall points along x, away from the contact
  EXPECT_EQ(evaluate(defective, ring, ball).diagnostics.approach, clean.diagnostics.approach);
}


// A roller's own defect (element_imperfections.hpp: round its circumference, its width along the
// axis) turns with the roller: a roller turned by beta about its axis carries a waviness of order n
// to the contact at longitude psi + pi - beta in its frame (the inner race's contact faces the ring
// axis), its approach's rate as orbit and spin advance together is the derivative along that
// motion (central differences, through the damping), and a spall drops the slices within its
// width when turned to the contact and none when turned away.
TEST(ElementHeight, RollerDefectTurnsWithTheRoller) {
  const slice::SliceCase c{"inner_middle", false, 4};
  const RollerSliceSegment perfect = slice::make(c, true, false);
  auto own = std::make_shared<RaceImperfections>();
  own->race_radius = own->ball_radius = perfect.roller_radius;
  own->waviness = {{3}, {1.5e-6}, {0.4}};
  RollerSliceSegment wavy = perfect;
  wavy.roller_imperfections = own;
  const double omega = 150.0, spin = -900.0, approach0 = 6e-6, psi0 = 0.37, beta0 = 1.1;
  SpatialKinematics ring;
  const double rho = slice::inner_race_radius + perfect.roller_radius - perfect.drop - approach0;
  auto roller_at = [&](double t) {
    SpatialKinematics roller;
    const double psi = psi0 + omega * t, beta = beta0 + spin * t;
    roller.position = rho * ball::radial(psi) - perfect.position * Vec3::UnitZ();  // the slice centre at z = 0
    roller.velocity = omega * Vec3::UnitZ().cross(roller.position);
    roller.rotation = Eigen::AngleAxisd(beta, Vec3::UnitZ()).toRotationMatrix();
    roller.angular_velocity = spin * Vec3::UnitZ();
    return roller;
  };
  const double height = 1.5e-6 * std::cos(3 * (psi0 + pi - beta0) + 0.4);
  EXPECT_NEAR(evaluate(perfect, ring, roller_at(0)).diagnostics.approach, approach0, 1e-15);
  const SpatialSegmentResult at = evaluate(wavy, ring, roller_at(0));
  EXPECT_NEAR(at.diagnostics.approach, approach0 + height, 1e-15);
  const double h = 1e-9;
  const double rate = (evaluate(wavy, ring, roller_at(h)).diagnostics.approach -
                       evaluate(wavy, ring, roller_at(-h)).diagnostics.approach) / (2 * h);
  EXPECT_GT(std::abs(rate), 1e-3);  // the waviness does turn through the contact
  const double elastic = perfect.stiffness * std::pow(approach0 + height, palmgren_exponent);
  const double expected = hunt_crossley(elastic, perfect.damping_factor, rate).force;
  EXPECT_NEAR(at.diagnostics.normal_force, expected, 1e-6 * expected);

  auto pit = std::make_shared<RaceImperfections>(*own);
  pit->waviness = {};
  pit->has_spall = true;
  pit->spall = {.angle = psi0 + pi - beta0, .length = 2e-3, .width = 1e-3, .depth = 1e-6, .edge = SpallEdge::sharp};
  RollerSliceSegment spalled = perfect;
  spalled.roller_imperfections = pit;
  EXPECT_NEAR(evaluate(spalled, ring, roller_at(0)).diagnostics.approach, approach0 - 1e-6, 1e-15);
  const double half_turn = pi / spin;  // the roller turned by a half turn, the orbit by a little
  EXPECT_NEAR(evaluate(spalled, ring, roller_at(half_turn)).diagnostics.approach,
              evaluate(perfect, ring, roller_at(half_turn)).diagnostics.approach, 1e-15);
  const slice::SliceCase end{"inner_end", false, 9};  // 4.5 mm from the middle: beyond the width
  RollerSliceSegment end_slice = slice::make(end, true, false);
  const double end_approach = evaluate(end_slice, ring, roller_at(0)).diagnostics.approach;
  end_slice.roller_imperfections = pit;
  EXPECT_EQ(evaluate(end_slice, ring, roller_at(0)).diagnostics.approach, end_approach);
  EXPECT_NEAR(roller_spall_distance(*pit, roller_at(0).rotation, -ball::radial(psi0)), 0.0, 1e-12);
}

}  // namespace

// A roller's slice on a wavy inner race (order 5, 2 um) orbiting at Omega: the approach is the
// perfect race's plus the height at the slice centre's ring-frame azimuth, and the damping sees the
// approach's rate along the orbit, Omega d(approach)/d(psi) by central differences: the normal force
// is Hunt-Crossley's at that approach and rate. A spall 1 mm wide at the race's middle reaches the
// slices whose centres lie within 0.5 mm of it and not the end slice.
TEST(RaceHeight, RollerSliceApproachAndRateFollowTheRace) {
  const slice::SliceCase c{"inner_middle", false, 4};
  const RollerSliceSegment perfect = slice::make(c, true, false);
  RollerSliceSegment wavy = perfect;
  auto race = std::make_shared<RaceImperfections>();
  race->race_radius = slice::inner_race_radius;
  race->ball_radius = perfect.roller_radius;
  race->waviness = {{5}, {2e-6}, {0.3}};
  wavy.imperfections = race;
  const double omega = 150.0, approach0 = 6e-6, psi0 = 0.37;
  SpatialKinematics ring;
  ring.spin_angle = 0.2;
  const double rho = slice::inner_race_radius + perfect.roller_radius - perfect.drop - approach0;
  auto roller_at = [&](double psi) {
    SpatialKinematics roller;
    roller.position = rho * ball::radial(psi) - perfect.position * Vec3::UnitZ();  // the slice centre at z = 0
    roller.velocity = omega * Vec3::UnitZ().cross(roller.position);
    return roller;
  };
  const double height = 2e-6 * std::cos(5 * (psi0 - 0.2) + 0.3);
  const SpatialSegmentResult at = evaluate(wavy, ring, roller_at(psi0));
  EXPECT_NEAR(evaluate(perfect, ring, roller_at(psi0)).diagnostics.approach, approach0, 1e-15);
  EXPECT_NEAR(at.diagnostics.approach, approach0 + height, 1e-15);
  const double h = 1e-6;
  const double rate = omega * (evaluate(wavy, ring, roller_at(psi0 + h)).diagnostics.approach -
                               evaluate(wavy, ring, roller_at(psi0 - h)).diagnostics.approach) / (2 * h);
  EXPECT_GT(std::abs(rate), 1e-4);  // the waviness does pass under the slice
  const double elastic = perfect.stiffness * std::pow(approach0 + height, palmgren_exponent);
  const double expected = hunt_crossley(elastic, perfect.damping_factor, rate).force;
  EXPECT_NEAR(at.diagnostics.normal_force, expected, 1e-6 * expected);

  RollerSliceSegment spalled = perfect;
  auto pit = std::make_shared<RaceImperfections>(*race);
  pit->waviness = {};
  pit->has_spall = true;
  pit->spall = {.angle = psi0 - 0.2, .length = 2e-3, .width = 1e-3, .depth = 1e-6, .edge = SpallEdge::sharp};
  spalled.imperfections = pit;
  EXPECT_NEAR(evaluate(spalled, ring, roller_at(psi0)).diagnostics.approach, approach0 - 1e-6, 1e-15);
  const slice::SliceCase end{"inner_end", false, 9};  // 4.5 mm from the middle
  RollerSliceSegment end_slice = slice::make(end, true, false);
  const double end_approach = evaluate(end_slice, ring, roller_at(psi0)).diagnostics.approach;
  end_slice.imperfections = pit;
  EXPECT_EQ(evaluate(end_slice, ring, roller_at(psi0)).diagnostics.approach, end_approach);
}

}  // namespace raceway::contact::test
