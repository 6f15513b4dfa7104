// The spatial roller's pocket bar (contact/segments/roller_pocket_segment.hpp): in the plane it is
// the planar cage bar (roller_segments.hpp), force and moment; out of the plane a skewed roller
// loads its slices by their own distance to the bar (stated here from the geometry), a roller
// tilted in its radial plane loads them all alike; action equals reaction about any point.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/segments/roller_pocket_segment.hpp"
#include "contact/segments/roller_segments.hpp"

namespace raceway::contact {
namespace {

constexpr double e_star = 1.1e11, pitch = 32.5e-3, roller_radius = 5e-3, half_clearance = 0.1e-3, width = 10e-3;
constexpr double pocket = 0.4, damping = 0.5, max_approach = 1e-4;
const TractionCurve kTraction{0.1, 0.05};

RollerPocketBarSegment bar(int side, int slices) {
  return make_roller_pocket_bar_segment(e_star, width, slices, pitch, pocket, half_clearance, roller_radius, side, damping,
                                        max_approach, kTraction);
}

Mat3 rotation_about(double angle, const Vec3& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

/// A cage turned by theta about z at (x, y), a roller in its pocket pressed `approach` into the bar
/// on `side`, both moving in the plane.
struct Pair {
  SpatialKinematics cage, roller;
  PlanarKinematics cage2, roller2;
};
Pair in_plane(int side, double approach) {
  Pair p;
  const double theta = 0.3, angle = theta + pocket;
  p.cage2 = {1e-5, -2e-5, theta, 0.01, -0.02, 95.0};
  const double offset = side * (half_clearance + approach);
  const double x = p.cage2.x + pitch * std::cos(angle) - offset * std::sin(angle);
  const double y = p.cage2.y + pitch * std::sin(angle) + offset * std::cos(angle);
  p.roller2 = {x, y, 0.0, -3.0 * std::sin(angle), 3.0 * std::cos(angle), -640.0};
  p.cage.position = Vec3(p.cage2.x, p.cage2.y, 0);
  p.cage.rotation = rotation_about(theta, Vec3::UnitZ());
  p.cage.velocity = Vec3(p.cage2.vx, p.cage2.vy, 0);
  p.cage.angular_velocity = Vec3(0, 0, p.cage2.omega);
  p.roller.position = Vec3(x, y, 0);
  p.roller.rotation = rotation_about(1.7, Vec3::UnitZ());  // its angle about its own axis plays no part
  p.roller.velocity = Vec3(p.roller2.vx, p.roller2.vy, 0);
  p.roller.angular_velocity = Vec3(0, 0, p.roller2.omega);
  return p;
}

TEST(RollerPocketBar, InThePlaneItIsThePlanarCageBar) {
  for (const int side : {+1, -1})
    for (const int slices : {1, 4, 7})
      for (const double approach : {-1e-6, 2e-6, 1.5e-5}) {
        SCOPED_TRACE(testing::Message() << "side " << side << " slices " << slices << " approach " << approach);
        const Pair p = in_plane(side, approach);
        const CageBarSegment planar{pitch, pocket, half_clearance, roller_radius, side,
                                    make_line_contact_law(e_star, width, 1, 0.0, damping, max_approach), kTraction,
                                    std::nullopt};
        const SegmentResult r2 = evaluate(planar, p.cage2, p.roller2);
        const SpatialSegmentResult r3 = evaluate(bar(side, slices), p.cage, p.roller);
        ASSERT_TRUE(r3.valid);
        EXPECT_NEAR(r3.diagnostics.approach, r2.diagnostics.approach, 1e-15);
        const double scale = 1e-10 * (std::abs(r2.diagnostics.normal_force) + 1e-9);
        EXPECT_NEAR(r3.diagnostics.normal_force, r2.diagnostics.normal_force, scale);
        EXPECT_NEAR(r3.on_b.force.x(), r2.on_b.fx, scale);
        EXPECT_NEAR(r3.on_b.force.y(), r2.on_b.fy, scale);
        EXPECT_NEAR(r3.on_b.force.z(), 0.0, scale);
        EXPECT_NEAR(r3.on_b.moment.z(), r2.on_b.mz, scale * roller_radius);
        EXPECT_NEAR(r3.on_a.moment.z(), r2.on_a.mz, scale * pitch);
        EXPECT_NEAR(r3.diagnostics.power_loss, r2.diagnostics.power_loss, 1e-9 * (std::abs(r2.diagnostics.power_loss) + 1e-12));
        if (approach > 0) {
          EXPECT_GT(r3.diagnostics.normal_force, 0.0);
        }
      }
}

// Skew: the roller turned by `skew` about the pocket's radial line; slice j at x_j along the axis
// is side * x_j * sin(skew) nearer the bar. Tilt about the circumferential direction (in the radial
// plane) changes no slice's distance to the bar.
TEST(RollerPocketBar, SkewLoadsTheSlicesByTheirDistanceTiltDoesNot) {
  const int side = +1, slices = 5;
  const RollerPocketBarSegment seg = bar(side, slices);
  const double approach = 4e-6, skew = 1e-3;
  Pair p = in_plane(side, approach);
  p.roller.velocity = p.cage.velocity = p.roller.angular_velocity = p.cage.angular_velocity = Vec3::Zero();
  const Vec3 radial = p.cage.rotation * Vec3(std::cos(pocket), std::sin(pocket), 0);
  const Vec3 tangential = p.cage.rotation * Vec3(-std::sin(pocket), std::cos(pocket), 0);
  const double k = palmgren_stiffness(e_star, width) / slices;
  SpatialKinematics skewed = p.roller;
  skewed.rotation = rotation_about(skew, radial) * p.roller.rotation;
  // Slice j's centre is x_j along the axis a: side x_j (a . e_t) nearer the bar than the roller's centre.
  const Vec3 a = skewed.rotation.col(2);
  double force = 0, moment = 0;
  for (int j = 0; j < slices; ++j) {
    const double x = -0.5 * width + (j + 0.5) * width / slices;
    const double aj = approach + side * x * a.dot(tangential);
    const double fj = aj > 0 ? k * std::pow(aj, 10.0 / 9.0) : 0.0;
    force += fj;
    moment += fj * x * a.cross(-side * tangential).dot(radial);  // x_j a x F_j along the radial line
  }
  EXPECT_GT(std::abs(a.dot(tangential)), 0.9 * skew);
  const SpatialSegmentResult r = evaluate(seg, p.cage, skewed);
  EXPECT_NEAR(r.diagnostics.normal_force, force, 1e-9 * force);
  EXPECT_NEAR(r.on_b.moment.dot(radial), moment, 1e-9 * force * width);
  EXPECT_GT(std::abs(moment), 1e-3 * force * width);
  SpatialKinematics tilted = p.roller;
  tilted.rotation = rotation_about(2e-3, tangential) * p.roller.rotation;
  const SpatialSegmentResult t = evaluate(seg, p.cage, tilted);
  EXPECT_NEAR(t.diagnostics.normal_force, slices * k * std::pow(approach, 10.0 / 9.0), 1e-9 * t.diagnostics.normal_force);
}

TEST(RollerPocketBar, ActionEqualsReactionAndBadInputIsInvalid) {
  Pair p = in_plane(-1, 1e-5);
  p.roller.rotation = rotation_about(2e-3, Vec3(0.3, 1, 0.2)) * p.roller.rotation;
  p.roller.angular_velocity = Vec3(30, -20, -640);
  p.roller.velocity.z() = 0.02;
  const SpatialSegmentResult r = evaluate(bar(-1, 6), p.cage, p.roller);
  ASSERT_GT(r.diagnostics.normal_force, 0.0);
  ASSERT_GT(r.diagnostics.traction_force, 0.0);
  EXPECT_LE((r.on_a.force + r.on_b.force).norm(), 1e-12 * r.on_b.force.norm());
  const Vec3 about_origin = r.on_a.moment + p.cage.position.cross(r.on_a.force) + r.on_b.moment +
                            p.roller.position.cross(r.on_b.force);
  EXPECT_LE(about_origin.norm(), 1e-12 * r.on_b.force.norm() * pitch);
  EXPECT_GE(r.diagnostics.power_loss, 0.0);
  p.roller.position.x() = std::nan("");
  EXPECT_FALSE(evaluate(bar(-1, 6), p.cage, p.roller).valid);
  EXPECT_THROW(bar(+1, 0), std::invalid_argument);
}

}  // namespace
}  // namespace raceway::contact
