// Check 10: physical sense of each segment, stated in the bearing's own terms (which way a race, a bar,
// a land pushes; which way friction drives the cage). Non-parameterised on purpose: each statement is
// specific to one segment.
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "segment_cases.hpp"

namespace raceway::contact::test {
namespace {

const SegmentCase& find_case(const std::string& name) {
  static const std::vector<SegmentCase> cases = all_segment_cases();
  for (const auto& c : cases) {
    if (c.name == name) return c;
  }
  throw std::invalid_argument("no segment case " + name);
}

constexpr double angles[] = {0.0, 1.3, -2.2, 3.0};

TEST(PhysicalSense, InnerRacePushesRollerOutward) {
  const SegmentCase& c = find_case("RollerInnerRace");
  const AnySegment seg = make_segment(c, {.traction = false});
  for (const double phi : angles) {
    const Placement p = place(c, seg, moving(0, 0, 104.7), moving(0, 0, -400), 5e-6, phi);
    const SegmentResult r = evaluate_any(seg, p.a, p.b);
    const Vec outward = unit(phi);  // from the ring centre through the roller centre
    const double f = norm(force(r.on_b));
    ASSERT_GT(f, 100.0);
    EXPECT_NEAR(dot(force(r.on_b), outward), f, 1e-12 * f);
    EXPECT_NEAR(r.on_a.mz, 0.0, 1e-12 * f * 0.03) << "the normal passes through the ring centre";
  }
}

TEST(PhysicalSense, OuterRacePushesRollerInward) {
  const SegmentCase& c = find_case("RollerOuterRace");
  const AnySegment seg = make_segment(c, {.traction = false});
  for (const double phi : angles) {
    const Placement p = place(c, seg, moving(0, 0, 0), moving(0, 0, -400), 5e-6, phi);
    const SegmentResult r = evaluate_any(seg, p.a, p.b);
    const Vec outward = unit(phi);
    const double f = norm(force(r.on_b));
    ASSERT_GT(f, 100.0);
    EXPECT_NEAR(dot(force(r.on_b), outward), -f, 1e-12 * f);
    // Beyond the race radius: the roller centre is at R - r + delta from the ring centre.
    EXPECT_NEAR(std::hypot(p.b.x - p.a.x, p.b.y - p.a.y),
                seed002::outer_race_radius - seed002::roller_radius + 5e-6, 1e-15);
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

TEST(PhysicalSense, FrontBarPushesRollerBackwards) {
  const SegmentCase& c = find_case("CageBarFront");
  const AnySegment seg = make_segment(c, {.traction = false});
  for (const double phi : angles) {
    const Placement p = place(c, seg, moving(0, 0, 42), moving(0, 0, -200), 5e-6, phi, 1e-4);
    const SegmentResult r = evaluate_any(seg, p.a, p.b);
    const Vec forward = perp(unit(phi));  // the cage's positive sense of rotation at the pocket
    const double f = norm(force(r.on_b));
    ASSERT_GT(f, 100.0);
    EXPECT_NEAR(dot(force(r.on_b), forward), -f, 1e-12 * f);
    // The roller is ahead of the pocket centre (it has caught up with the front bar) ...
    EXPECT_GT(dot({p.b.x - p.a.x, p.b.y - p.a.y}, forward), 0.0);
    // ... and, pushing the bar forward, drives the cage in its positive sense.
    EXPECT_GT(r.on_a.mz, 0.0);
    EXPECT_NEAR(r.on_a.mz, f * (seed002::pitch_radius + 1e-4), 1e-9 * f * seed002::pitch_radius);
  }
}

TEST(PhysicalSense, RearBarPushesRollerForwards) {
  const SegmentCase& c = find_case("CageBarRear");
  const AnySegment seg = make_segment(c, {.traction = false});
  for (const double phi : angles) {
    const Placement p = place(c, seg, moving(0, 0, 42), moving(0, 0, -200), 5e-6, phi);
    const SegmentResult r = evaluate_any(seg, p.a, p.b);
    const Vec forward = perp(unit(phi));
    const double f = norm(force(r.on_b));
    ASSERT_GT(f, 100.0);
    EXPECT_NEAR(dot(force(r.on_b), forward), f, 1e-12 * f);
    EXPECT_LT(r.on_a.mz, 0.0) << "a roller lagging behind brakes the cage";
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

}  // namespace
}  // namespace raceway::contact::test
