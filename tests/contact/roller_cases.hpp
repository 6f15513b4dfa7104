// Test support for the planar (roller) segments: the six segment configurations of the seed-002
// cylindrical roller bearing, built with realistic SI numbers, and a placement helper that puts body
// B where the segment's approach has a chosen value along a chosen direction, with arbitrary
// velocities and spins.
//
// The typed conformance suite (test_segment_conformance.cpp) runs these configurations next to the
// ball segments'; the roller-specific checks run each configuration through a value-parameterised
// fixture (SegmentTest). The test's own statements of the geometry (expected_normal_on_b,
// expected_stiffness) are written here independently of contact/, so that they can disagree with it.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "contact/laws/line_contact.hpp"
#include "contact/segments/roller_segments.hpp"
#include "placement.hpp"

namespace raceway::contact::test::roller {

/// Seed 002 (13-roller cylindrical roller bearing), SI units. Values not given by the paper are marked.
namespace seed002 {
inline constexpr double roller_diameter = 9.2e-3;
inline constexpr double roller_radius = 0.5 * roller_diameter;
inline constexpr double roller_length = 10e-3;
inline constexpr double pitch_diameter = 45.74e-3;
inline constexpr double pitch_radius = 0.5 * pitch_diameter;
inline constexpr double inner_race_radius = 0.5 * (pitch_diameter - roller_diameter);  // 18.27 mm
inline constexpr double outer_race_radius = 0.5 * (pitch_diameter + roller_diameter);  // 27.47 mm
inline constexpr double steel_youngs = 208e9, steel_poisson = 0.3;
inline constexpr double brass_youngs = 100e9, brass_poisson = 0.34;
inline constexpr double pocket_clearance = 0.2e-3;  // circumferential, whole pocket
inline constexpr double land_clearance = 0.3e-3;    // radial
inline constexpr double damping_factor = 0.5;       // s/m
inline constexpr double friction_coefficient = 0.1;
inline constexpr double slip_velocity_scale = 0.05;  // m/s
// Not in the paper: taken as solver/bearing/model.cpp builds them (a land rib half a roller radius high,
// land width half the roller length, validity limit 2 % of the roller radius); the bar segments use
// pocket 3 of 13.
inline constexpr double inner_land_radius = inner_race_radius + 0.5 * roller_radius;  // 20.57 mm
inline constexpr double outer_land_radius = outer_race_radius - 0.5 * roller_radius;  // 25.17 mm
inline constexpr double land_length = 0.5 * roller_length;
inline constexpr double max_approach = 0.02 * roller_radius;  // 92 um
inline constexpr double pocket_angle = 3.0 * 2.0 * std::numbers::pi / 13.0;
}  // namespace seed002

enum class Kind { race, bar, land };

/// One segment configuration of the suite.
struct SegmentCase {
  std::string name;
  Kind kind = Kind::race;
  bool internal = false;    ///< race: outer race (roller inside the bore); land: outer-land guidance
  int side = +1;            ///< bar: +1 front bar, -1 rear bar
  double youngs_a = 0, poisson_a = 0, youngs_b = 0, poisson_b = 0;
  double length = 0;        ///< contact length of the line-contact law [m]
};
inline void PrintTo(const SegmentCase& c, std::ostream* os) { *os << c.name; }

/// The six configurations: roller/inner race, roller/outer race, front and rear cage bar, inner and
/// outer land.
std::vector<SegmentCase> all_segment_cases();

/// What to switch on in the law of a configuration.
struct LawOptions {
  bool damping = true;
  bool traction = true;
  int slices = 1;
  double crown_drop = 0;  ///< m, parabolic crown drop at the roller ends
  double max_approach = seed002::max_approach;
};

using AnySegment = std::variant<RollerRaceSegment, CageBarSegment, CageLandSegment>;

AnySegment make_segment(const SegmentCase& c, const LawOptions& options = {});
SegmentResult evaluate_any(const AnySegment& s, const PlanarKinematics& a, const PlanarKinematics& b);

/// Palmgren K computed by the test from the configuration's materials: 0.70866 E* l^(8/9).
double expected_stiffness(const SegmentCase& c);

using Vec = std::array<double, 2>;
inline Vec unit(double angle) { return {std::cos(angle), std::sin(angle)}; }
inline double dot(Vec a, Vec b) { return a[0] * b[0] + a[1] * b[1]; }
inline double cross(Vec a, Vec b) { return a[0] * b[1] - a[1] * b[0]; }
inline double norm(Vec a) { return std::hypot(a[0], a[1]); }
inline Vec perp(Vec a) { return {-a[1], a[0]}; }
inline Vec position(const PlanarKinematics& k) { return {k.x, k.y}; }
inline Vec force(const PlanarWrench& w) { return {w.fx, w.fy}; }

/// Kinematics from velocities and spin (position left at zero).
PlanarKinematics moving(double vx, double vy, double omega, double theta = 0);

/// Motions of (A, B) used across the checks: at rest; running (A slow, B fast, arbitrary directions);
/// a slow creep in the linear part of the traction curve; both spinning fast. Approach rates stay
/// below 2 m/s, so that Hunt-Crossley damping (0.5 s/m) never clips the force in contact.
using Motion = std::pair<PlanarKinematics, PlanarKinematics>;
std::vector<Motion> motions();
inline constexpr double directions[] = {0.37, 2.1, -2.6};

/// Sum of the magnitudes of all force and moment components on both bodies.
double wrench_norm(const SegmentResult& r);

using Placement = Placed<PlanarKinematics>;

/// Places body B for segment configuration `c` so that the segment's approach is `approach` [m]
/// (negative: apart by that much), with the test's normal (expected_normal_on_b) and a point on the
/// line of action (on an undeformed surface). `direction` [rad] is the bearing-frame angle of the
/// line the contact acts along: race, the ray from the ring centre through the roller centre; bar,
/// the pocket's radial line (A's theta is set to direction - pocket_angle); land, the cage's
/// eccentricity from the ring centre (B, the ring, is placed opposite). `shift` [m]: bar only,
/// radial offset of the roller from the pocket centre. A's position, velocities and spin are taken
/// from `a`; B's theta, velocities and spin from `b_motion`.
Placement place(const SegmentCase& c, const AnySegment& s, PlanarKinematics a,
                PlanarKinematics b_motion, double approach, double direction, double shift = 0);

/// The test's statement of the unit direction of the normal force on B (inner race pushes the roller
/// out, outer race in, a bar pushes the roller back into the pocket, a land pushes the cage back, so
/// the ring along the cage's eccentricity).
Vec expected_normal_on_b(const SegmentCase& c, const Placement& p);

/// Radius of B's surface at the contact: the roller radius (race, bar) or the ring's land radius.
double surface_radius_b(const SegmentCase& c);

/// The whole configuration (bodies, normal and point) rotated by `angle` about the bearing axis
/// through the origin.
Placement rotated(const Placement& p, double angle);
/// The whole configuration translated by (dx, dy).
Placement translated(const Placement& p, double dx, double dy);

/// Rigid motion of both bodies over a time `dt` with their velocities and spins (first order);
/// normal and point are left as they were.
Placement advanced(const Placement& p, double dt);

/// Sum of F.v + M omega over both bodies [W].
double power_on_bodies(const SegmentResult& r, const Placement& p);

/// Value-parameterised base fixture: one instance of every test per configuration.
class SegmentTest : public ::testing::TestWithParam<SegmentCase> {
 protected:
  const SegmentCase& seg_case() const { return GetParam(); }
  AnySegment segment(const LawOptions& options = {}) const { return make_segment(GetParam(), options); }
};

/// Name generator for INSTANTIATE_TEST_SUITE_P.
inline std::string case_name(const ::testing::TestParamInfo<SegmentCase>& info) { return info.param.name; }

}  // namespace raceway::contact::test::roller
