// The lubricated cage land of a ball bearing (CageLandSegment3 with a film, contact/segments/
// land_film.hpp): the stations' strips add up to the whole land's short-bearing film, action equals
// reaction (forces and moments about any point), the force is continuous through the critical film
// where the dry contact takes over, and its derivatives agree with central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "contact/laws/line_contact.hpp"
#include "contact/segments/ball_segments.hpp"
#include "contact/segments/roller_segments.hpp"

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

// ---- the planar (roller-bearing) cage land -------------------------------------------------------

CageLandSegment planar_land(bool outer) {
  CageLandSegment s;
  s.land_radius = land_radius;
  s.clearance = clearance;
  s.outer_land = outer;
  s.law = make_line_contact_law(reduced_modulus(208e9, 0.3, 100e9, 0.34), width, 1, 0.0, 0.0, 50e-6);
  s.traction = TractionCurve{0.1, 0.05};
  s.film = *lubricated_land(outer).film;
  return s;
}

// The planar land carries the whole land's Ocvirk film: on the ring, the journal's force on an inner
// land (the ring is the journal) and its opposite on an outer one; action equals reaction about any
// point; the Couette torque resists the relative rotation; the film's work rate is its power loss.
TEST(LubricatedLand, PlanarLandCarriesTheFilm) {
  for (const bool outer : {false, true}) {
    const CageLandSegment s = planar_land(outer);
    PlanarKinematics cage, ring;
    cage.x = 0.6 * clearance, cage.y = -0.3 * clearance, cage.vx = 0.01, cage.vy = 0.02, cage.omega = 250.0;
    ring.omega = -20.0;
    const SegmentResult r = evaluate(s, cage, ring);
    ASSERT_TRUE(r.valid);
    const double sign = outer ? 1.0 : -1.0;
    const ShortBearingForce w =
        evaluate_short_bearing(*s.film, {sign * cage.x, sign * cage.y}, {sign * cage.vx, sign * cage.vy},
                               outer ? cage.omega : ring.omega, outer ? ring.omega : cage.omega);
    const double to_ring = outer ? -1.0 : 1.0;
    EXPECT_NEAR(r.on_b.fx, to_ring * w.on_journal[0], 1e-12 * std::abs(w.on_journal[0]));
    EXPECT_NEAR(r.on_b.fy, to_ring * w.on_journal[1], 1e-12 * std::abs(w.on_journal[1]));
    EXPECT_EQ(r.on_a.fx, -r.on_b.fx);
    EXPECT_EQ(r.on_a.fy, -r.on_b.fy);
    const double moment_about_origin = r.on_a.mz + r.on_b.mz + (cage.x * r.on_a.fy - cage.y * r.on_a.fx) +
                                       (ring.x * r.on_b.fy - ring.y * r.on_b.fx);
    EXPECT_NEAR(moment_about_origin, 0.0, 1e-12 * std::abs(r.on_b.mz) + 1e-15);
    EXPECT_LT(r.on_a.mz * (cage.omega - ring.omega), 0.0);  // the Couette torque resists the relative spin
    const double work = r.on_a.fx * cage.vx + r.on_a.fy * cage.vy + r.on_a.mz * cage.omega + r.on_b.fx * ring.vx +
                        r.on_b.fy * ring.vy + r.on_b.mz * ring.omega;
    std::printf("[ land ] planar %s land: %.5g N on the ring, power loss %.5g W (work rate %.5g W)\n",
                outer ? "outer" : "inner", std::hypot(r.on_b.fx, r.on_b.fy), r.diagnostics.power_loss, -work);
    // The short bearing's power loss is its Couette shear and squeeze dissipation; the wedge's work on the
    // cage's translation (and its moment's on the rotation), 2e-6 of it here, is not counted in it.
    EXPECT_NEAR(r.diagnostics.power_loss, -work, 1e-5 * std::abs(work));
    EXPECT_GT(std::hypot(r.on_b.fx, r.on_b.fy), 0.01);
    EXPECT_NEAR(r.diagnostics.normal_force, std::hypot(r.on_b.fx, r.on_b.fy), 1e-12);
  }
}

// The force passes continuously from the film to the dry contact at touch.
TEST(LubricatedLand, PlanarLandContinuousAtTouch) {
  for (const bool outer : {false, true}) {
    const CageLandSegment s = planar_land(outer);
    PlanarKinematics before, after, ring;
    before.x = clearance - 1e-12, after.x = clearance + 1e-12;
    before.omega = after.omega = 300.0;
    const SegmentResult a = evaluate(s, before, ring), b = evaluate(s, after, ring);
    EXPECT_GT(std::abs(a.on_b.fx) + std::abs(a.on_b.fy), 0.0);
    EXPECT_NEAR(a.on_b.fx, b.on_b.fx, 1e-4 * std::hypot(a.on_b.fx, a.on_b.fy));
    EXPECT_NEAR(a.on_b.fy, b.on_b.fy, 1e-4 * std::hypot(a.on_b.fx, a.on_b.fy));
    // Without the film, the dry land alone: bit for bit the segment without a film.
    CageLandSegment dry = s;
    dry.film.reset();
    const SegmentResult d = evaluate(dry, after, ring);
    EXPECT_EQ(d.diagnostics.power_loss, evaluate(dry, after, ring).diagnostics.power_loss);
    EXPECT_GT(b.diagnostics.normal_force, d.diagnostics.normal_force);
  }
}

}  // namespace
}  // namespace raceway::contact
