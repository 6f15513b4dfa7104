// Checks particular to the planar (roller) segments, over the six configurations of roller_cases.hpp:
// the sliced and crowned line-contact law, elastic energy as the integral of the force, the traction
// curve and the signed traction diagnostics, friction acting at the surfaces, and the physical sense
// of each segment stated in the bearing's own terms (which way a race, a bar, a land pushes; which way
// friction drives the cage). The checks every segment kind shares are in test_segment_conformance.cpp.
#include <bit>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "roller_cases.hpp"

namespace raceway::contact::test::roller {
namespace {

constexpr double n_exp = 10.0 / 9.0;

class RollerSegment : public SegmentTest {};

// N slices without crown give the 1-slice force; a crown lowers it and moves the onset to the crown
// drop of the central slices.
TEST_P(RollerSegment, SlicingAndCrown) {
  const AnySegment one = segment({.damping = false, .traction = false});
  for (const int slices : {2, 7, 20}) {
    const AnySegment many = segment({.damping = false, .traction = false, .slices = slices});
    for (const double approach : {1e-7, 4e-6, 3e-5}) {
      const Placement p = place(seg_case(), one, motions()[2].first, motions()[2].second, approach, 1.1);
      const double f1 = evaluate_any(one, p.a, p.b).diagnostics.normal_force;
      const SegmentResult rn = evaluate_any(many, p.a, p.b);
      EXPECT_NEAR(rn.diagnostics.normal_force, f1, 1e-12 * f1) << slices << " slices";
      EXPECT_NEAR(norm(force(rn.on_b)), f1, 1e-12 * f1);
    }
  }
  const int slices = 10;  // even: the central slices sit at +-(1/slices) of the half length
  const double crown = 5e-6;
  const double central_drop = crown / (slices * slices);  // 5e-8 m
  const AnySegment crowned =
      segment({.damping = false, .traction = false, .slices = slices, .crown_drop = crown});
  const double k = expected_stiffness(seg_case());
  auto force_at = [&](const AnySegment& s, double approach) {
    const Placement p = place(seg_case(), s, motions()[1].first, motions()[1].second, approach, -0.8, 1e-5);
    return evaluate_any(s, p.a, p.b).diagnostics.normal_force;
  };
  EXPECT_EQ(force_at(crowned, 0.99 * central_drop), 0.0);
  // Just past the central drop, only the two central slices carry: 2 (K/N) (delta - drop)^(10/9).
  const double just_past = 1.2 * central_drop;
  const double two_slices = 2.0 * k / slices * std::pow(just_past - central_drop, n_exp);
  EXPECT_NEAR(force_at(crowned, just_past), two_slices, 1e-6 * two_slices);
  for (const double approach : {1e-6, 5e-6, 2e-5}) {
    double expected = 0;
    for (int j = 0; j < slices; ++j) {
      const double x = 2.0 * (j + 0.5) / slices - 1.0;
      const double d = approach - crown * x * x;
      if (d > 0) expected += k / slices * std::pow(d, n_exp);
    }
    const double f = force_at(crowned, approach);
    EXPECT_LT(f, force_at(one, approach));
    EXPECT_NEAR(f, expected, 1e-9 * expected);
  }
}

// Elastic energy is the integral of the elastic force (Simpson), with and without a crown.
TEST_P(RollerSegment, EnergyIsIntegralOfForce) {
  struct Variant {
    LawOptions options;
    double from, to;
  };
  const Variant variants[] = {
      {{.damping = false, .traction = false}, 2e-6, 2e-5},
      {{.damping = false, .traction = true, .slices = 10, .crown_drop = 5e-6}, 5e-6, 2e-5},
  };
  for (const auto& v : variants) {
    const AnySegment seg = segment(v.options);
    const auto [ma, mb] = motions()[1];
    auto eval_at = [&](double approach) {
      const Placement p = place(seg_case(), seg, ma, mb, approach, 2.1, -2e-5);
      return evaluate_any(seg, p.a, p.b);
    };
    const int intervals = 2000;
    const double h = (v.to - v.from) / intervals;
    double integral = 0;
    for (int i = 0; i <= intervals; ++i) {
      const double w = (i == 0 || i == intervals) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
      integral += w * eval_at(v.from + i * h).diagnostics.normal_force;
    }
    integral *= h / 3.0;
    const double delta_e =
        eval_at(v.to).diagnostics.elastic_energy - eval_at(v.from).diagnostics.elastic_energy;
    EXPECT_NEAR(delta_e, integral, 1e-8 * integral);
  }
}

// The traction curve, and the tangential force on B opposing the slip.
TEST_P(RollerSegment, TractionCurve) {
  const TractionCurve curve =
      std::visit([](const auto& s) { return s.traction; }, segment({.traction = true}));
  const double mu = seed002::friction_coefficient, scale = seed002::slip_velocity_scale;
  EXPECT_EQ(curve.coefficient(0.0), 0.0);
  for (const double u : {1e-9, 1e-3, 0.02, 0.05, 0.3, 3.0, 1e3}) {
    EXPECT_EQ(curve.coefficient(-u), -curve.coefficient(u)) << "odd";
    EXPECT_GT(curve.coefficient(u), 0.0) << "opposes the slip";
    EXPECT_LE(std::abs(curve.coefficient(u)), mu);
  }
  EXPECT_NEAR(curve.coefficient(1e3), mu, 1e-12);
  // Continuous at zero slip: no jump across 0.
  EXPECT_LT(curve.coefficient(1e-12) - curve.coefficient(-1e-12), 1e-10);
  // Continuity away from zero: small steps give small changes.
  for (double u = -0.2; u < 0.2; u += 0.013) {
    EXPECT_LE(std::abs(curve.coefficient(u + 1e-9) - curve.coefficient(u)), 1.01 * mu / scale * 1e-9);
  }
  // Slope at zero slip: mu / u_scale.
  const double h = 1e-6 * scale;
  EXPECT_NEAR((curve.coefficient(h) - curve.coefficient(-h)) / (2 * h), mu / scale, 1e-6 * mu / scale);
  // Traction off.
  const TractionCurve off =
      std::visit([](const auto& s) { return s.traction; }, segment({.traction = false}));
  EXPECT_EQ(off.coefficient(0.7), 0.0);
}

TEST_P(RollerSegment, TractionOpposesSlip) {
  const AnySegment with = segment({.traction = true});
  const AnySegment without = segment({.traction = false});
  const double mu = seed002::friction_coefficient;
  for (const auto& [ma, mb] : motions()) {
    for (const double dir : directions) {
      const Placement p = place(seg_case(), with, ma, mb, 6e-6, dir, -3e-5);
      const SegmentResult r = evaluate_any(with, p.a, p.b);
      const SegmentResult r0 = evaluate_any(without, p.a, p.b);
      const auto& d = r.diagnostics;
      ASSERT_GT(d.normal_force, 0.0);
      EXPECT_LE(d.traction_force * d.slip_velocity, 0.0);
      EXPECT_LE(std::abs(d.traction_force), mu * d.normal_force * (1 + 1e-12));
      EXPECT_NEAR(std::abs(d.traction_force),
                  mu * d.normal_force * std::abs(std::tanh(d.slip_velocity / seed002::slip_velocity_scale)),
                  1e-12 * d.normal_force);
      EXPECT_GE(d.power_loss, 0.0);
      // The force on B: normal part N along the expected normal, tangential part of size |T|.
      const Vec n = expected_normal_on_b(seg_case(), p);
      const Vec fb = force(r.on_b);
      EXPECT_NEAR(dot(fb, n), d.normal_force, 1e-12 * d.normal_force);
      EXPECT_NEAR(std::abs(cross(n, fb)), std::abs(d.traction_force), 1e-12 * d.normal_force);
      // Traction does not change the normal force.
      EXPECT_NEAR(r0.diagnostics.normal_force, d.normal_force, 1e-14 * d.normal_force);
      // The friction forces do negative work on the two bodies, equal to the friction loss.
      SegmentResult friction = r;
      friction.on_a = {r.on_a.fx - r0.on_a.fx, r.on_a.fy - r0.on_a.fy, r.on_a.mz - r0.on_a.mz};
      friction.on_b = {r.on_b.fx - r0.on_b.fx, r.on_b.fy - r0.on_b.fy, r.on_b.mz - r0.on_b.mz};
      const double p_friction = power_on_bodies(friction, p);
      const double loss = d.power_loss - r0.diagnostics.power_loss;
      EXPECT_LE(p_friction, 1e-12 * d.normal_force);
      EXPECT_NEAR(p_friction, -loss, 1e-9 * (loss + 1e-6 * d.normal_force));
    }
  }
  // Both bodies at rest: no slip, no traction.
  const Placement still = place(seg_case(), with, moving(0, 0, 0), moving(0, 0, 0), 6e-6, 0.3, 0);
  const SegmentResult rs = evaluate_any(with, still.a, still.b);
  EXPECT_EQ(rs.diagnostics.slip_velocity, 0.0);
  EXPECT_EQ(rs.diagnostics.traction_force, 0.0);
}

// The normal force acts through B's centre (roller or ring): B's moment is friction only, friction
// opposes B's spin when A is at rest, and it acts at B's surface: |M_b| = |T| * (B's radius) within the
// approach. For the land, the cage's friction moment has the lever of the cage's guided surface (bore
// on an inner land, outside on an outer land), which fixes on which side of the cage the contact is.
TEST_P(RollerSegment, FrictionActsAtTheSurfaces) {
  const AnySegment without = segment({.traction = false});
  const AnySegment with = segment({.traction = true});
  const double approach = 4e-6;
  for (const double dir : directions) {
    for (const double spin : {-300.0, -2.0, 0.5, 104.7}) {
      const Placement p = place(seg_case(), with, moving(0, 0, 0), moving(0, 0, spin), approach, dir, 2e-5);
      const SegmentResult r0 = evaluate_any(without, p.a, p.b);
      const double f = r0.diagnostics.normal_force;
      EXPECT_NEAR(r0.on_b.mz, 0.0, 1e-12 * f * 0.03);
      const SegmentResult r = evaluate_any(with, p.a, p.b);
      EXPECT_LT(r.on_b.mz * spin, 0.0) << "spin " << spin;
      const double t = std::abs(r.diagnostics.traction_force);
      ASSERT_GT(t, 0.0);
      // Anywhere across the overlap is a fair contact point; B's centre or A's surface far off is not.
      EXPECT_NEAR(std::abs(r.on_b.mz) / t, surface_radius_b(seg_case()), 1.5 * approach) << "spin " << spin;
      if (seg_case().kind == Kind::land) {
        const double cage_surface = seg_case().internal ? surface_radius_b(seg_case()) - seed002::land_clearance
                                                        : surface_radius_b(seg_case()) + seed002::land_clearance;
        EXPECT_NEAR(std::abs(r.on_a.mz - r0.on_a.mz) / t, cage_surface, 1.5 * approach) << "spin " << spin;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllRollerSegments, RollerSegment, ::testing::ValuesIn(all_segment_cases()), case_name);

// ---- physical sense: each statement is specific to one segment ----------------------------------

const SegmentCase& find_case(const std::string& name) {
  static const std::vector<SegmentCase> cases = all_segment_cases();
  for (const auto& c : cases) {
    if (c.name == name) return c;
  }
  throw std::invalid_argument("no segment case " + name);
}

constexpr double angles[] = {0.0, 1.3, -2.2, 3.0};

// The inner race pushes the roller outward, the outer race inward; the normal passes through the
// ring centre, and the roller centre sits at R + (r - delta) (inner) or R - (r - delta) (outer).
TEST(PhysicalSense, RacesPushRollerTowardsThePitchCircle) {
  for (const char* name : {"RollerInnerRace", "RollerOuterRace"}) {
    const SegmentCase& c = find_case(name);
    const double outward_sign = c.internal ? -1.0 : 1.0;
    const double race_radius = c.internal ? seed002::outer_race_radius : seed002::inner_race_radius;
    const AnySegment seg = make_segment(c, {.traction = false});
    for (const double phi : angles) {
      const Placement p = place(c, seg, moving(0, 0, c.internal ? 0.0 : 104.7), moving(0, 0, -400), 5e-6, phi);
      const SegmentResult r = evaluate_any(seg, p.a, p.b);
      const Vec outward = unit(phi);  // from the ring centre through the roller centre
      const double f = norm(force(r.on_b));
      ASSERT_GT(f, 100.0) << name;
      EXPECT_NEAR(dot(force(r.on_b), outward), outward_sign * f, 1e-12 * f) << name;
      EXPECT_NEAR(r.on_a.mz, 0.0, 1e-12 * f * 0.03) << name << ": the normal passes through the ring centre";
      EXPECT_NEAR(std::hypot(p.b.x - p.a.x, p.b.y - p.a.y),
                  race_radius + outward_sign * (seed002::roller_radius - 5e-6), 1e-15) << name;
    }
  }
}

// Rolling on the inner race, friction turns the roller the other way round from the ring.
TEST(PhysicalSense, DrivingInnerRingSpinsRollerBackwards) {
  const SegmentCase& c = find_case("RollerInnerRace");
  const AnySegment seg = make_segment(c);
  const Placement p = place(c, seg, moving(0, 0, 104.7), moving(0, 0, 0), 5e-6, 0.8);
  const SegmentResult r = evaluate_any(seg, p.a, p.b);
  EXPECT_LT(r.on_b.mz, 0.0);
  EXPECT_LT(r.on_a.mz, 0.0) << "the roller brakes the ring";
}

// A bar pushes the roller back into the pocket: the front bar (ahead in the cage's positive sense of
// rotation) backwards, the rear bar forwards. A roller that has caught up with the front bar, pushing
// it forward, drives the cage in its positive sense (with the lever of the roller's radius from the
// cage centre); one lagging behind against the rear bar brakes it.
TEST(PhysicalSense, BarsPushRollerBackIntoThePocket) {
  for (const char* name : {"CageBarFront", "CageBarRear"}) {
    const SegmentCase& c = find_case(name);
    const AnySegment seg = make_segment(c, {.traction = false});
    const double shift = c.side > 0 ? 1e-4 : 2e-5;  // radial offset of the roller from the pocket centre
    for (const double phi : angles) {
      const Placement p = place(c, seg, moving(0, 0, 42), moving(0, 0, -200), 5e-6, phi, shift);
      const SegmentResult r = evaluate_any(seg, p.a, p.b);
      const Vec forward = perp(unit(phi));  // the cage's positive sense of rotation at the pocket
      const double f = norm(force(r.on_b));
      ASSERT_GT(f, 100.0) << name;
      EXPECT_NEAR(dot(force(r.on_b), forward), -c.side * f, 1e-12 * f) << name;
      EXPECT_GT(c.side * dot({p.b.x - p.a.x, p.b.y - p.a.y}, forward), 0.0) << name << ": on the bar's side";
      EXPECT_GT(c.side * r.on_a.mz, 0.0) << name;
      EXPECT_NEAR(r.on_a.mz, c.side * f * (seed002::pitch_radius + shift), 1e-9 * f * seed002::pitch_radius) << name;
    }
  }
}

TEST(PhysicalSense, LandPushesCageTowardRingCentre) {
  for (const char* name : {"CageInnerLand", "CageOuterLand"}) {
    const SegmentCase& c = find_case(name);
    const AnySegment seg = make_segment(c, {.traction = false});
    for (const double phi : angles) {
      PlanarKinematics cage = moving(0, 0, 42);
      cage.x = 1e-3;
      cage.y = -2e-3;
      const Placement p = place(c, seg, cage, moving(0, 0, 104.7), 5e-6, phi);
      const SegmentResult r = evaluate_any(seg, p.a, p.b);
      const Vec eccentricity{p.a.x - p.b.x, p.a.y - p.b.y};  // the cage is off the ring centre along it
      EXPECT_NEAR(norm(eccentricity), seed002::land_clearance + 5e-6, 1e-15);
      const double f = norm(force(r.on_a));
      ASSERT_GT(f, 100.0) << name;
      EXPECT_NEAR(dot(force(r.on_a), eccentricity) / norm(eccentricity), -f, 1e-12 * f) << name;
      EXPECT_NEAR(r.on_a.mz, 0.0, 1e-12 * f * 0.03) << name << ": the normal passes through the cage centre";
    }
  }
}

// Friction on the cage from a land turning faster than the cage drives the cage forward; a land
// turning slower (a fixed outer ring) drags it.
TEST(PhysicalSense, FasterLandDrivesCageForward) {
  for (const char* name : {"CageInnerLand", "CageOuterLand"}) {
    const SegmentCase& c = find_case(name);
    const AnySegment seg = make_segment(c);
    for (const double phi : angles) {
      const Placement fast = place(c, seg, moving(0, 0, 42), moving(0, 0, 104.7), 5e-6, phi);
      const SegmentResult r = evaluate_any(seg, fast.a, fast.b);
      EXPECT_GT(r.on_a.mz, 0.0) << name << " phi " << phi;
      EXPECT_LT(r.on_b.mz, 0.0) << name << ": the cage brakes the ring";
      // The friction force on the cage follows the land's surface where they touch: an inner land
      // touches the cage bore opposite to the cage's eccentricity, where the land moves along
      // -perp(e); an outer land touches the cage outside on the side of the eccentricity, moving along
      // +perp(e). (This is what drives the cage's whirl.)
      const Vec e{fast.a.x - fast.b.x, fast.a.y - fast.b.y};
      const double along = dot(force(r.on_a), perp(e)) / norm(e);
      const double expected_sign = c.internal ? 1.0 : -1.0;
      EXPECT_GT(expected_sign * along, 0.9 * seed002::friction_coefficient * r.diagnostics.normal_force) << name;
      const Placement slow = place(c, seg, moving(0, 0, 42), moving(0, 0, 0), 5e-6, phi);
      EXPECT_LT(evaluate_any(seg, slow.a, slow.b).on_a.mz, 0.0) << name << " phi " << phi;
      // With the ring much faster the traction saturates: |M| ~ mu N R.
      const double m_sat = seed002::friction_coefficient * r.diagnostics.normal_force * seed002::inner_land_radius;
      EXPECT_GT(r.on_a.mz, 0.9 * m_sat) << name;
    }
  }
}

// The pocket tolerance's gap alone (bar_approach) is the full evaluation's approach bit for bit: both
// bars, apart and in contact, off the pocket's middle radially, the cage turned and moved; and it is
// the approach placed. Then the 13 pockets in turn, each bar's gap asked before its evaluation and
// after another pocket's, twice: the pocket's direction kept per angle is each pocket's own.
TEST(CageBar, ApproachAloneIsTheEvaluatedOne) {
  const auto bits = [](double v) { return std::bit_cast<std::uint64_t>(v); };
  PlanarKinematics cage = moving(0.02, -0.01, 42);
  cage.x = 1.3e-4, cage.y = -2.1e-4;
  for (const char* name : {"CageBarFront", "CageBarRear"}) {
    const SegmentCase& c = find_case(name);
    const CageBarSegment law = std::get<CageBarSegment>(make_segment(c));
    for (const double approach : {-2.0 * law.half_clearance, -1e-5, 2e-6, 3e-5})
      for (const double phi : angles)
        for (const double shift : {0.0, 3e-4}) {
          const Placement p = place(c, law, cage, moving(0.4, -0.3, -200), approach, phi, shift);
          const double alone = bar_approach(law, p.a, p.b.x, p.b.y);
          EXPECT_EQ(bits(alone), bits(evaluate(law, p.a, p.b).diagnostics.approach)) << name << " phi " << phi;
          EXPECT_NEAR(alone, approach, 1e-15) << name;
        }
  }
  CageBarSegment law = std::get<CageBarSegment>(make_segment(find_case("CageBarFront")));
  for (int round = 0; round < 2; ++round)
    for (int k = 0; k < 13; ++k) {
      law.pocket_angle = 2 * std::numbers::pi * k / 13;
      law.side = k % 2 == 0 ? +1 : -1;
      PlanarKinematics roller;
      const double off = law.side * (k + 1) * 1e-5;  // off the pocket's middle along its tangent
      const Vec r = unit(cage.theta + law.pocket_angle), t = perp(r);
      roller.x = cage.x + seed002::pitch_radius * r[0] + off * t[0];
      roller.y = cage.y + seed002::pitch_radius * r[1] + off * t[1];
      const double alone = bar_approach(law, cage, roller.x, roller.y);
      EXPECT_NEAR(alone, std::abs(off) - law.half_clearance, 1e-15);
      EXPECT_EQ(bits(alone), bits(evaluate(law, cage, roller).diagnostics.approach)) << k;
      law.side = -law.side;  // the pocket's other bar, after its partner's evaluation
      EXPECT_EQ(bits(bar_approach(law, cage, roller.x, roller.y)), bits(evaluate(law, cage, roller).diagnostics.approach));
    }
}

}  // namespace
}  // namespace raceway::contact::test::roller
