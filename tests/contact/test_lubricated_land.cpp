// The lubricated cage land of a ball bearing (CageLandSegment3 with a film, contact/segments/
// land_film.hpp): the stations' strips add up to the whole land's short-bearing film, action equals
// reaction (forces and moments about any point), the force is continuous through the critical film
// where the dry contact takes over, and its derivatives agree with central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact/laws/line_contact.hpp"
#include "contact/segments/ball_segments.hpp"

namespace raceway::contact {
namespace {

constexpr double clearance = 0.3e-3, width = 8e-3, land_radius = 41e-3;

CageLandSegment3 lubricated_land(bool outer, int stations = 4) {
  CageLandSegment3 s;
  s.land_radius = land_radius;
  s.clearance = clearance;
  s.width = width;
  s.axial_offset = 0;
  s.stations = stations;
  s.outer_land = outer;
  s.law = make_line_contact_law(reduced_modulus(208e9, 0.3, 100e9, 0.34), width / stations, 1, 0.0, 0.0, 50e-6);
  s.friction = TractionCurve{0.1, 0.05};
  ShortBearingFilm f;
  f.viscosity = 0.02;
  f.radius = land_radius;
  f.width = width;
  f.clearance = clearance;
  f.film_floor = 0.5e-6;
  f.points = 64;
  s.film = f;
  return s;
}

SpatialKinematics ring_at_rest() { return {}; }
SpatialKinematics cage_at(double ex, double ey, double spin) {
  SpatialKinematics k;
  k.position = Vec3(ex, ey, 0.0);
  k.angular_velocity = Vec3(0, 0, spin);
  return k;
}

// An aligned cage: the four strips together carry Ocvirk's film of the whole land.
TEST(LubricatedLand, StripsAddUpToTheWholeLand) {
  for (const bool outer : {false, true}) {
    const CageLandSegment3 s = lubricated_land(outer);
    const double eps = 0.7;
    const SpatialSegmentResult r = evaluate(s, cage_at(eps * clearance, 0, 300.0), ring_at_rest());
    ShortBearingFilm whole = *s.film;
    // The cage is the journal on an outer land, the ring on an inner one (its centre at -e from the cage's).
    const double sign = outer ? 1.0 : -1.0;
    const ShortBearingForce w =
        evaluate_short_bearing(whole, {sign * eps * clearance, 0.0}, {0, 0}, outer ? 300.0 : 0.0, outer ? 0.0 : 300.0);
    const Vec3 on_ring = outer ? Vec3(-w.on_journal[0], -w.on_journal[1], 0) : Vec3(w.on_journal[0], w.on_journal[1], 0);
    std::printf("[ land ] %s land, eps 0.7, 300 rad/s: %.5g N on the ring (the whole land's film %.5g N)\n",
                outer ? "outer" : "inner", r.on_b.force.norm(), on_ring.norm());
    EXPECT_NEAR((r.on_b.force - on_ring).norm(), 0.0, 1e-9 * on_ring.norm());
    EXPECT_GT(r.on_b.force.norm(), 0.1);
    EXPECT_EQ(r.diagnostics.approach, eps * clearance - clearance);
    EXPECT_GT(r.diagnostics.power_loss, 0.0);
  }
}

void expect_action_reaction(const SpatialSegmentResult& r, const SpatialKinematics& a, const SpatialKinematics& b) {
  const double scale = r.on_b.force.norm() + 1e-12;
  EXPECT_NEAR((r.on_a.force + r.on_b.force).norm(), 0.0, 1e-12 * scale);
  const Vec3 total = r.on_a.moment + a.position.cross(r.on_a.force) + r.on_b.moment + b.position.cross(r.on_b.force);
  EXPECT_NEAR(total.norm(), 0.0, 1e-12 * scale);
}

TEST(LubricatedLand, ActionEqualsReaction) {
  for (const bool outer : {false, true}) {
    const CageLandSegment3 s = lubricated_land(outer);
    SpatialKinematics cage = cage_at(0.2e-3, -0.1e-3, 250.0), ring = ring_at_rest();
    cage.rotation = Eigen::AngleAxisd(2e-3, Vec3::UnitX()).toRotationMatrix();  // tilted: stations differ
    cage.velocity = Vec3(0.01, 0.02, 0.0);
    ring.position = Vec3(1e-5, 0, 2e-3);
    ring.angular_velocity = Vec3(0, 0, 40.0);
    const SpatialSegmentResult r = evaluate(s, cage, ring);
    ASSERT_TRUE(r.valid);
    expect_action_reaction(r, cage, ring);
    // In contact too (film and dry together).
    const SpatialSegmentResult touching = evaluate(s, cage_at(clearance + 5e-6, 0, 250.0), ring);
    expect_action_reaction(touching, cage_at(clearance + 5e-6, 0, 250.0), ring);
  }
}

// Through the critical film: the floored film force is continuous and the dry force rises from zero
// at touch, so the total has no jump as the cage moves through it.
TEST(LubricatedLand, ContinuousPassageToDryContact) {
  const CageLandSegment3 s = lubricated_land(true);
  double previous = 0;
  for (double e = clearance - 5e-6; e < clearance + 5e-6; e += 2e-8) {
    const SpatialSegmentResult r = evaluate(s, cage_at(e, 0, 300.0), ring_at_rest());
    ASSERT_TRUE(r.valid);
    const double force = r.on_b.force.norm();
    if (previous > 0) {
      EXPECT_GT(force, previous * (1 - 1e-9)) << e;
      EXPECT_LT(force, previous * 1.05 + 1.0) << e;
    }
    previous = force;
  }
  CageLandSegment3 dry = s;
  dry.film.reset();
  EXPECT_GT(previous, evaluate(dry, cage_at(clearance + 5e-6, 0, 300.0), ring_at_rest()).on_b.force.norm());
}

// Derivatives: forward differences of the wrench (as the equations take them) against central ones,
// in the cage's position and velocity, apart and in contact.
TEST(LubricatedLand, DerivativesAgainstCentralDifferences) {
  const CageLandSegment3 s = lubricated_land(false);
  for (const double e : {0.15e-3, 0.29e-3, clearance + 2e-6}) {
    SpatialKinematics cage = cage_at(e, 0.02e-3, 250.0);
    cage.velocity = Vec3(-0.02, 0.03, 0.0);
    for (int column = 0; column < 4; ++column) {
      const auto force = [&](double d) {
        SpatialKinematics k = cage;
        if (column < 2) k.position[column] += d; else k.velocity[column - 2] += d;
        return evaluate(s, k, ring_at_rest()).on_b.force;
      };
      const double step = column < 2 ? 1e-11 : 1e-7;
      const Vec3 forward = (force(step) - force(0)) / step;
      const Vec3 central = (force(100 * step) - force(-100 * step)) / (200 * step);
      EXPECT_LE((forward - central).norm(), 2e-3 * central.norm() + 1e-6) << "e " << e << " column " << column;
    }
  }
}

}  // namespace
}  // namespace raceway::contact
