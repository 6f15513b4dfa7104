// Checks particular to the spatial (ball) segments, over the configurations of ball_cases.hpp: the
// diagnostics that follow from the point-contact geometry (contact angle, Hertz pressure, film,
// circumferential force), the contact angle from the geometry and the four-point arcs, film and
// rolling resistance from the entrainment speed, spin, the pocket shapes, and the land's tilt
// moments and guidance. The checks every segment kind shares are in test_segment_conformance.cpp.
#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "ball_cases.hpp"
#include "contact/segments/diagnostic_fields.hpp"

namespace raceway::contact::test::ball {
namespace {

class BallSegment : public ::testing::TestWithParam<SpatialCase> {
 protected:
  const SpatialCase& seg_case() const { return GetParam(); }
};

// The elastic law's diagnostics besides force and energy (test_segment_conformance.cpp checks
// those): no film without lubricant, the force on B along the bearing's circumferential direction,
// the Hertz pressure p_max = 3 Q / (2 pi a b) with the exact semi-axes at the contact angle (cage-land:
// a positive line-contact estimate), and the contact angle from the placement.
TEST_P(BallSegment, NormalLawDiagnostics) {
  const AnySegment seg = make_segment(seg_case(), {.damping = false, .traction = false});
  for (const double approach : {1e-6, 5e-6, 3e-5}) {
    for (const double dir : directions) {
      const Placement p = placed(seg_case(), approach, dir, motions()[1]);
      const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
      ASSERT_TRUE(r.valid);
      const PointDiagnostics& d = r.diagnostics;
      ASSERT_GT(d.normal_force, 0.0);
      EXPECT_EQ(d.film_thickness, 0.0);
      if (seg_case().kind == Kind::land) {
        EXPECT_EQ(d.circumferential_force, 0.0);  // B is the ring: no circumferential direction
        EXPECT_GT(d.max_pressure, 0.0);
      } else {
        const Vec3 e_theta = Vec3::UnitZ().cross(Vec3(p.b.position.x(), p.b.position.y(), 0).normalized());
        EXPECT_NEAR(d.circumferential_force, r.on_b.force.dot(e_theta), 1e-12 * d.normal_force);
        // Hertz: p_max = 3 Q / (2 pi a b) with the exact semi-axes at the contact angle.
        HertzPointContact h = pocket_hertz(seg_case().shape);
        if (seg_case().kind == Kind::groove) {
          double kx = 0, ky = 0;
          groove_curvatures(groove_of(seg_case()), std::cos(p.contact_angle), kx, ky);
          h = hertz_point_contact(kx, ky, steel_steel());
        }
        const double q13 = std::cbrt(d.normal_force);
        const double p_max = 1.5 * d.normal_force / (pi * h.a_coefficient * h.b_coefficient * q13 * q13);
        EXPECT_NEAR(d.max_pressure, p_max, 2e-4 * p_max);
      }
      if (seg_case().kind == Kind::groove) {
        EXPECT_NEAR(d.contact_angle, p.contact_angle, 1e-12);
      } else {
        EXPECT_EQ(d.contact_angle, 0.0);
      }
    }
  }
}

std::string spatial_case_name(const ::testing::TestParamInfo<SpatialCase>& info) { return info.param.name; }
INSTANTIATE_TEST_SUITE_P(AllBallSegments, BallSegment, ::testing::ValuesIn(all_cases()), spatial_case_name);

// ---- ball / groove ----------------------------------------------------------------------------

SpatialCase groove_case(bool outer, int arc = 0) {
  return {outer ? "outer" : "inner", Kind::groove, outer, arc, PocketShape::cylindrical};
}

// A ball pushed axially in a deep groove: the contact angle is the angle of the triangle (arc
// centre, ball centre) and the approach its hypotenuse minus (r_groove - r_ball), in the ring frame
// whatever the ring's pose.
TEST(BallGroove, ContactAngleFromAxialPush) {
  for (const bool outer : {false, true}) {
    const SpatialCase c = groove_case(outer);
    const AnySegment seg = make_segment(c, {.damping = false, .traction = false});
    const Groove g = groove_of(c);
    const double m = g.groove_radius - ball_radius;
    for (const double play : {0.0, 3e-5}) {  // radial play: the ball centre off the groove towards the other ring
      for (const double dz : {4e-4, 1.5e-3, -9e-4, 3e-3}) {
        for (const bool tilted : {false, true}) {
          SpatialKinematics ring;
          if (tilted) {
            ring.position = Vec3(1e-3, -2e-3, 5e-4);
            ring.rotation = rotation_about(0.02, Vec3(1, 1, 0)) * rotation_about(0.6, Vec3::UnitZ());
          }
          const double psi = 0.9;
          const double radial_offset = (outer ? 1.0 : -1.0) * (m - play);  // ball centre - arc centre
          const Vec3 ball_ring = (g.centre_radius + radial_offset) * radial(psi) + dz * Vec3::UnitZ();
          SpatialKinematics ball;
          ball.position = ring.position + ring.rotation * ball_ring;
          const SpatialSegmentResult r = evaluate_any(seg, ring, ball);
          const double hyp = std::hypot(radial_offset, dz);
          const double angle = std::atan2(dz, std::abs(radial_offset));
          EXPECT_NEAR(r.diagnostics.contact_angle, angle, 1e-12) << "dz " << dz;
          EXPECT_NEAR(r.diagnostics.approach, hyp - m, 1e-15);
          ASSERT_GT(r.diagnostics.normal_force, 0.0) << "dz " << dz;
          // The force on the ball pushes it back axially: -Q sin(angle) along the ring axis.
          const Vec3 f_ring = ring.rotation.transpose() * r.on_b.force;
          EXPECT_NEAR(f_ring.z(), -r.diagnostics.normal_force * std::sin(angle), 1e-12 * r.diagnostics.normal_force);
          EXPECT_NEAR(f_ring.dot(radial(psi)), -(outer ? 1.0 : -1.0) * r.diagnostics.normal_force * std::cos(angle),
                      1e-12 * r.diagnostics.normal_force);
        }
      }
    }
  }
}

// Four-point bearing: the two arcs of a ring, centres offset axially by +-e = (r_g - r_b) sin(35 deg),
// both touch a ball on the pitch circle with zero clearance at +-35 deg; pushed radially into the
// ring, both carry equal loads whose axial parts cancel, at the angles of the new triangles.
TEST(BallGroove, FourPointArcsTouchAtDesignAngle) {
  for (const bool outer : {false, true}) {
    const SpatialCase lower = groove_case(outer, +1), upper = groove_case(outer, -1);
    const AnySegment seg_l = make_segment(lower, {.damping = false, .traction = false});
    const AnySegment seg_u = make_segment(upper, {.damping = false, .traction = false});
    const double m = groove_of(lower).groove_radius - ball_radius;
    SpatialKinematics ring;
    ring.rotation = rotation_about(2.0, Vec3::UnitZ());
    for (const double push : {0.0, 1e-5, 4e-5}) {
      const double psi = -0.4;
      SpatialKinematics ball;
      ball.position = ring.rotation * ((pitch_radius + (outer ? push : -push)) * radial(psi));
      const SpatialSegmentResult rl = evaluate_any(seg_l, ring, ball), ru = evaluate_any(seg_u, ring, ball);
      const double angle = std::atan2(m * std::sin(arc_angle), m * std::cos(arc_angle) + push);
      const double approach = std::hypot(m * std::sin(arc_angle), m * std::cos(arc_angle) + push) - m;
      EXPECT_NEAR(ru.diagnostics.contact_angle, angle, 1e-12);
      EXPECT_NEAR(rl.diagnostics.contact_angle, -angle, 1e-12);
      EXPECT_NEAR(ru.diagnostics.approach, approach, 1e-15);
      EXPECT_NEAR(rl.diagnostics.approach, approach, 1e-15);
      if (push == 0.0) {
        EXPECT_NEAR(angle, arc_angle, 1e-15);
        EXPECT_LT(ru.on_b.force.norm() + rl.on_b.force.norm(), 1e-12);  // approach 0 up to round-off
        continue;
      }
      const double q = ru.diagnostics.normal_force;
      ASSERT_GT(q, 0.0);
      EXPECT_NEAR(rl.diagnostics.normal_force, q, 1e-12 * q);
      EXPECT_NEAR(ru.on_b.force.z() + rl.on_b.force.z(), 0.0, 1e-12 * q);
      EXPECT_NEAR(ru.on_b.force.z(), -q * std::sin(angle), 1e-12 * q);  // upper arc pushes the ball down
      const double radial_sum = (ru.on_b.force + rl.on_b.force).dot(ring.rotation * radial(psi));
      EXPECT_NEAR(radial_sum, (outer ? -2.0 : 2.0) * q * std::cos(angle), 1e-12 * q);
    }
  }
}

// The film and the rolling resistance use the entrainment speed relative to the contact point,
// which moves with the ball centre's azimuth: a ball rolling without slip in a fixed outer ring,
// its centre orbiting at V, gives u_e = V rho_c / r_centre (rho_c: radius of the contact point).
// Rolling resistance: a couple F_R Rx opposing the rolling, F_R bounded by Q (1/F = 1/F_R + 1/Q),
// dissipating F_R Rx |Omega| with Omega Rx = u_e in pure rolling.
TEST(BallGroove, FilmAndRollingResistanceFromEntrainment) {
  const SpatialCase c = groove_case(true);
  const AnySegment seg = make_segment(c, {.damping = true, .traction = true});
  const Groove g = groove_of(c);
  const double approach = 2e-5, psi = 1.2, speed = 6.0;
  SpatialKinematics ring, ball;
  const double r_centre = g.centre_radius + g.groove_radius - ball_radius + approach;
  ball.position = r_centre * radial(psi);
  ball.velocity = speed * tangential(psi);
  // At rest at the contact point on the groove, x_b + (r_b - approach) e_r.
  ball.angular_velocity = -speed / (ball_radius - approach) * Vec3::UnitZ();
  const SpatialSegmentResult r = evaluate_any(seg, ring, ball);
  ASSERT_TRUE(r.valid);
  const double q = r.diagnostics.normal_force;
  const double rho_c = g.centre_radius + g.groove_radius;
  const double entrainment = speed / r_centre * rho_c;
  const double rx = 1.0 / (1.0 / ball_radius - 1.0 / rho_c), ry = 1.0 / (1.0 / ball_radius - 1.0 / g.groove_radius);
  const PointLubricant lubricant{viscosity, pressure_viscosity, limiting_shear};
  const FilmThickness film = hamrock_dowson_film(entrainment, q, rx, ry, steel_steel(), lubricant);
  ASSERT_GT(film.central, 0.0);
  EXPECT_NEAR(r.diagnostics.film_thickness, film.central, 1e-10 * film.central);
  EXPECT_NEAR(r.diagnostics.slip_velocity, 0.0, 1e-12);
  EXPECT_NEAR(r.diagnostics.traction_force, 0.0, 1e-9 * q);
  const double f_r = ehl_rolling_resistance(entrainment, q, rx, ry, steel_steel(), lubricant);
  ASSERT_GT(f_r, 0.0);
  const double f_eff = f_r * q / (f_r + q);
  const double omega = speed / (ball_radius - approach);
  const double couple = f_eff * rx * std::tanh(omega * rx / slip_scale);
  // The ball turns about -z: the couple on it is about +z, on the ring about -z.
  EXPECT_NEAR(r.on_b.moment.z(), couple, 1e-9 * couple);
  EXPECT_NEAR(r.diagnostics.power_loss, couple * omega, 1e-9 * couple * omega);
  EXPECT_NEAR(omega * rx, entrainment, 5e-3 * entrainment);  // = u_e up to approach / r_b
}

// Spin of the ball about the contact normal meets a moment that opposes it.
TEST(BallGroove, SpinMomentOpposesSpin) {
  for (const bool outer : {false, true}) {
    const SpatialCase c = groove_case(outer);
    const AnySegment seg = make_segment(c);
    Placement p = place(c, 2e-5, 0.7);
    const Vec3 n_into_ring = -p.normal_on_b;
    for (const double spin : {-50.0, 3.0, 200.0}) {
      p.b.angular_velocity = spin * n_into_ring;
      const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
      ASSERT_TRUE(r.valid);
      EXPECT_NEAR(r.diagnostics.spin_velocity, spin, 1e-12 * std::abs(spin));
      EXPECT_LT(r.on_b.moment.dot(n_into_ring) * spin, 0.0);
      EXPECT_LT(r.diagnostics.traction_force, 1e-9 * r.diagnostics.normal_force);  // symmetric
    }
  }
}

// A fine traction grid is computed in fixed blocks so that one contact can be shared between
// processes: block k at the contact's kinematics, the blocks summed in block order, and the contact
// prepared up to its traction, sent as doubles (write, read) and completed with that sum give
// exactly evaluate's bits (no tolerance), for limiting shear with spin and slide, loaded and apart. The grid decides the blocks: 5 x 5 is one, 40 x 40 several.
TEST(BallGroove, TractionBlocksGiveEvaluatesBits) {
  PointTraction coarse;
  EXPECT_EQ(traction_block_count(coarse), 1);
  coarse.grid_x = coarse.grid_y = 128;
  EXPECT_GT(traction_block_count(coarse), 32);
  EXPECT_LE(traction_block_count(coarse), max_traction_blocks);
  for (const bool outer : {false, true}) {
    const SpatialCase c = groove_case(outer);
    auto seg = std::get<BallGrooveSegment>(make_segment(c));
    seg.traction.model = TractionModel::limiting_shear;
    seg.traction.grid_x = seg.traction.grid_y = 40;
    const int blocks = traction_block_count(seg);
    ASSERT_GT(blocks, 1);
    for (const double approach : {2e-5, -1e-6}) {
      Placement p = place(c, std::abs(approach), 0.7);
      if (approach < 0) p = placed(c, approach, 0.7, motions()[1]);
      p.b.angular_velocity += 40.0 * p.normal_on_b;  // spin on top of the rolling
      p.b.velocity += Vec3(1e-3, -2e-3, 5e-4);       // and some sliding
      const SpatialSegmentResult whole = evaluate(seg, p.a, p.b);
      std::vector<TractionResult> parts;
      PreparedGrooveContact prepared;
      for (int k = 0; k < blocks; ++k) parts.push_back(evaluate_traction_block(seg, p.a, p.b, k, k == 1 ? &prepared : nullptr));
      EXPECT_EQ(prepared.in_contact, approach > 0);
      std::array<double, PreparedGrooveContact::size> sent{};
      prepared.write(sent.data());
      const SpatialSegmentResult cut = finish_groove_contact(PreparedGrooveContact::read(sent.data()), sum_traction_blocks(parts));
      EXPECT_EQ(whole.valid, cut.valid);
      for (int i = 0; i < 3; ++i) {
        EXPECT_EQ(whole.on_a.force[i], cut.on_a.force[i]);
        EXPECT_EQ(whole.on_a.moment[i], cut.on_a.moment[i]);
        EXPECT_EQ(whole.on_b.force[i], cut.on_b.force[i]);
        EXPECT_EQ(whole.on_b.moment[i], cut.on_b.moment[i]);
      }
      EXPECT_EQ(whole.diagnostics.traction_force, cut.diagnostics.traction_force);
      EXPECT_EQ(whole.diagnostics.power_loss, cut.diagnostics.power_loss);
      for (std::size_t f = 0; f < point_diagnostic_fields.size(); ++f)
        EXPECT_EQ(whole.diagnostics.*(point_diagnostic_fields[f].member), cut.diagnostics.*(point_diagnostic_fields[f].member))
            << point_diagnostic_fields[f].name;
      if (approach > 0) {
        EXPECT_GT(whole.diagnostics.traction_force, 0.0);
        EXPECT_THROW(evaluate_traction_block(seg, p.a, p.b, blocks), std::invalid_argument);
      }
    }
  }
}

// ---- ball / pocket ----------------------------------------------------------------------------

SpatialCase pocket_case(PocketShape shape) { return {"pocket", Kind::pocket, false, 0, shape}; }

TEST(BallPocket, CentredBallNoForce) {
  for (const PocketShape shape : {PocketShape::cylindrical, PocketShape::spherical}) {
    const AnySegment seg = make_segment(pocket_case(shape));
    Placement p = placed(pocket_case(shape), -0.5 * pocket_clearance, 0.3, motions()[1], 0.0);
    const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
    EXPECT_TRUE(r.valid);
    EXPECT_EQ(wrench_norm(r), 0.0);
    EXPECT_NEAR(r.diagnostics.approach, -0.5 * pocket_clearance, 1e-15);
  }
}

// The cylindrical pocket's axis is radial: an offset along it is free; a spherical pocket holds it.
TEST(BallPocket, CylindricalIgnoresOffsetAlongAxis) {
  const double along = 0.3e-3;  // more than half the clearance
  for (const double sign : {1.0, -1.0}) {
    const Placement p = placed(pocket_case(PocketShape::cylindrical), -0.5 * pocket_clearance, 0.3,
                               motions()[1], sign * along);
    const SpatialSegmentResult cyl = evaluate_any(make_segment(pocket_case(PocketShape::cylindrical)), p.a, p.b);
    EXPECT_EQ(wrench_norm(cyl), 0.0);
    EXPECT_NEAR(cyl.diagnostics.approach, -0.5 * pocket_clearance, 1e-15);
    const AnySegment sph = make_segment(pocket_case(PocketShape::spherical), {.damping = false, .traction = false});
    const SpatialSegmentResult r = evaluate_any(sph, p.a, p.b);
    const double approach = along - 0.5 * pocket_clearance;
    EXPECT_NEAR(r.diagnostics.approach, approach, 1e-15);
    const double q = pocket_hertz(PocketShape::spherical).stiffness * std::pow(approach, 1.5);
    EXPECT_NEAR(r.diagnostics.normal_force, q, 1e-12 * q);
    const Vec3 axis = p.a.rotation * radial(pocket_angle);  // the ball is pushed back along the axis
    EXPECT_LE((r.on_b.force + sign * q * axis).norm(), 1e-10 * q);
  }
}

// A ball ahead of its pocket centre (in +theta) touches the front bar, which pushes it back:
// negative circumferential force; behind, the rear bar pushes it forward.
TEST(BallPocket, CircumferentialForceSign) {
  for (const PocketShape shape : {PocketShape::cylindrical, PocketShape::spherical}) {
    const AnySegment seg = make_segment(pocket_case(shape), {.damping = false, .traction = false});
    for (const double side : {1.0, -1.0}) {
      SpatialKinematics cage, ball;
      ball.position = pitch_radius * radial(pocket_angle) + side * (0.5 * pocket_clearance + 2e-5) * tangential(pocket_angle);
      const SpatialSegmentResult r = evaluate_any(seg, cage, ball);
      const double q = r.diagnostics.normal_force;
      ASSERT_GT(q, 0.0);
      EXPECT_LT(side * r.diagnostics.circumferential_force, 0.0);
      EXPECT_NEAR(r.diagnostics.circumferential_force, -side * q, 1e-4 * q);  // e_theta of the ball ~ pocket's
      EXPECT_LE((r.on_b.force + side * q * tangential(pocket_angle)).norm(), 1e-10 * q);
      EXPECT_LE((r.on_a.force - side * q * tangential(pocket_angle)).norm(), 1e-10 * q);  // bar pushed ahead
    }
  }
}

// A ball spinning in its pocket about an axis in the contact plane slides on the bar at r_b w:
// the friction at the ball's surface brakes the spin, M = -r_b mu(r_b w) Q about the spin axis.
TEST(BallPocket, FrictionBrakesSpinningBall) {
  for (const PocketShape shape : {PocketShape::cylindrical, PocketShape::spherical}) {
    const AnySegment seg = make_segment(pocket_case(shape), {.damping = false, .traction = true});
    SpatialKinematics cage, ball;
    const Vec3 et = tangential(pocket_angle);
    ball.position = pitch_radius * radial(pocket_angle) + (0.5 * pocket_clearance + 2e-5) * et;
    for (const double w : {30.0, -5.0}) {
      ball.angular_velocity = w * Vec3::UnitZ();
      const SpatialSegmentResult r = evaluate_any(seg, cage, ball);
      const double q = r.diagnostics.normal_force;
      ASSERT_GT(q, 0.0);
      const double sliding = w * ball_radius;  // surface velocity at x_b + r_b e_t: -w r_b e_r
      const double f = friction * std::tanh(std::abs(sliding) / slip_scale) * q;
      EXPECT_NEAR(r.diagnostics.slip_velocity, std::abs(sliding), 1e-12);
      EXPECT_NEAR(r.on_b.moment.z(), -(w > 0 ? 1.0 : -1.0) * ball_radius * f, 1e-9 * ball_radius * f);
      EXPECT_NEAR(r.diagnostics.power_loss, f * std::abs(sliding), 1e-9 * f * std::abs(sliding));
    }
  }
}

// The pocket tolerance's gap alone (pocket_approach) is the full evaluation's approach bit for bit,
// apart and in contact, both shapes, the cage turned and moved; and it is the approach placed. Then
// pockets at nine angles in turn, twice: the axis kept per angle is each pocket's own.
TEST(BallPocket, ApproachAloneIsTheEvaluatedOne) {
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  for (const PocketShape shape : {PocketShape::cylindrical, PocketShape::spherical}) {
    const BallPocketSegment law = std::get<BallPocketSegment>(make_segment(pocket_case(shape)));
    for (const double approach : {-0.5 * pocket_clearance, -1e-5, 2e-6, 3e-5})
      for (const double dir : directions) {
        const Placement p = placed(pocket_case(shape), approach, dir, motions()[1]);
        const double alone = pocket_approach(law, p.a, p.b.position);
        EXPECT_EQ(bits(alone), bits(evaluate(law, p.a, p.b).diagnostics.approach));
        EXPECT_NEAR(alone, approach, 1e-12);
      }
  }
  BallPocketSegment law = std::get<BallPocketSegment>(make_segment(pocket_case(PocketShape::cylindrical)));
  for (int round = 0; round < 2; ++round)
    for (int k = 0; k < 9; ++k) {
      law.pocket_angle = 2 * pi * k / 9;
      SpatialKinematics cage, ball;
      const double off = (k + 1) * 1e-5;  // off the pocket's middle along e_theta
      ball.position = pitch_radius * radial(law.pocket_angle) + off * tangential(law.pocket_angle);
      const double alone = pocket_approach(law, cage, ball.position);
      EXPECT_NEAR(alone, off - 0.5 * pocket_clearance, 1e-15);
      EXPECT_EQ(bits(alone), bits(evaluate(law, cage, ball).diagnostics.approach));
    }
}

// ---- cage / land ------------------------------------------------------------------------------

SpatialCase land_case(bool outer) { return {outer ? "outer_land" : "inner_land", Kind::land, outer, 0, PocketShape::cylindrical}; }

TEST(CageLand3, CentredCageNoForce) {
  for (const bool outer : {false, true}) {
    const AnySegment seg = make_segment(land_case(outer));
    const Placement p = placed(land_case(outer), -land_clearance, 0.0, motions()[1]);
    const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
    EXPECT_TRUE(r.valid);
    EXPECT_EQ(wrench_norm(r), 0.0);
    EXPECT_NEAR(r.diagnostics.approach, -land_clearance, 1e-15);
  }
}

// A cage tilted by theta about x in a coaxial ring: the stations at +-zeta are off the axis by
// zeta sin(theta); the outer ones touch and the land acts as a couple against the tilt,
// M_x = -2 zeta cos(theta) Q(zeta sin(theta) - c) on the cage, zero net force.
TEST(CageLand3, TiltGivesRestoringMoment) {
  for (const bool outer : {false, true}) {
    CageLandSegment3 seg = std::get<CageLandSegment3>(make_segment(land_case(outer), {.damping = false, .traction = false}));
    seg.axial_offset = 0.0;
    SpatialKinematics cage, ring;
    for (const double theta : {0.105, 0.11, -0.115}) {
      cage.rotation = rotation_about(theta, Vec3::UnitX());
      const SpatialSegmentResult r = evaluate(seg, cage, ring);
      ASSERT_TRUE(r.valid);
      const double zeta = 3e-3;  // outer stations of four over 8 mm
      const double approach = zeta * std::abs(std::sin(theta)) - land_clearance;
      const double q = palmgren_stiffness(steel_brass(), land_width / land_stations) * std::pow(approach, palmgren_exponent);
      EXPECT_NEAR(r.diagnostics.approach, approach, 1e-15);
      EXPECT_NEAR(r.diagnostics.normal_force, 2 * q, 1e-12 * q);
      EXPECT_LE(r.on_a.force.norm(), 1e-10 * q);
      const double expected = -2 * zeta * std::cos(theta) * q * (theta > 0 ? 1.0 : -1.0);
      EXPECT_NEAR(r.on_a.moment.x(), expected, 1e-9 * std::abs(expected));
      EXPECT_NEAR(r.on_b.moment.x(), -expected, 1e-9 * std::abs(expected));
      EXPECT_LE(std::abs(r.on_a.moment.y()) + std::abs(r.on_a.moment.z()), 1e-10 * std::abs(expected));
    }
  }
}

// Inner and outer land both push a displaced cage back towards the ring axis (Palmgren on every
// station); a ring spinning at omega drags the cage along through friction at the contact line,
// whose lever from the cage centre tells on which side the cage touches: the inner land meets the
// cage bore opposite the eccentricity (lever r_l + c + delta/2), the outer land the cage's outside
// on its side (lever r_l - c - delta/2): the contact point is midway between the two surfaces.
TEST(CageLand3, LandsPushCageBackAndDragIt) {
  for (const bool outer : {false, true}) {
    const AnySegment seg = make_segment(land_case(outer), {.damping = false, .traction = true});
    const double land = outer ? outer_land_radius : inner_land_radius;
    for (const double dir : directions) {
      for (const double approach : {2e-6, 1e-5}) {
        SpatialKinematics cage, ring;
        const Vec3 u = radial(dir);
        cage.position = (land_clearance + approach) * u;
        const double q = land_stations * palmgren_stiffness(steel_brass(), land_width / land_stations) *
                         std::pow(approach, palmgren_exponent);
        SpatialSegmentResult r = evaluate(std::get<CageLandSegment3>(seg), cage, ring);
        ASSERT_TRUE(r.valid);
        EXPECT_LE((r.on_a.force + q * u).norm(), 1e-12 * q) << (outer ? "outer" : "inner");
        const double omega = 80.0;
        ring.angular_velocity = omega * Vec3::UnitZ();
        r = evaluate(std::get<CageLandSegment3>(seg), cage, ring);
        const double r_contact = outer ? land + 0.5 * approach : land - 0.5 * approach;
        const double drag = friction * std::tanh(omega * r_contact / slip_scale) * q;
        const double arm = outer ? land - land_clearance - 0.5 * approach : land + land_clearance + 0.5 * approach;
        EXPECT_NEAR(r.on_a.moment.z(), drag * arm, 1e-9 * drag * arm) << (outer ? "outer" : "inner");
        EXPECT_NEAR(r.diagnostics.traction_force, drag, 1e-9 * drag);
        EXPECT_NEAR(r.diagnostics.power_loss, drag * omega * r_contact, 1e-9 * drag * omega * r_contact);
      }
    }
  }
}

}  // namespace
}  // namespace raceway::contact::test::ball
