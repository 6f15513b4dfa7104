// Test support for the spatial (ball) segments: the eight segment configurations of a 6309-like
// ball bearing (seed 000) -- ball/groove (deep groove, inner and outer ring; one arc of a four-point
// inner and outer ring), ball/pocket (cylindrical, spherical) and cage/land (inner, outer) -- and a
// placement helper that puts the two bodies where the segment's approach has a chosen value, with
// arbitrary velocities and spins.
//
// The typed conformance suite (test_segment_conformance.cpp) runs these configurations next to the
// roller segments'; the ball-specific checks are in test_ball_segments.cpp. The geometry each check
// expects (contact normal, contact point, Hertz and Palmgren constants) is stated here,
// independently of contact/segments/ball_segments.cpp, so that the two can disagree.
#pragma once

#include <Eigen/Geometry>
#include <numbers>
#include <ostream>
#include <string>
#include <variant>
#include <vector>

#include "contact/laws/line_contact.hpp"
#include "contact/laws/point_contact.hpp"
#include "contact/segments/ball_segments.hpp"
#include "placement.hpp"

namespace raceway::contact::test::ball {

/// A 6309-like deep-groove ball bearing (seed 000), SI. The four-point arcs use the same ball and
/// grooves with a 35 degree design angle; the cage is brass.
namespace bearing {
using std::numbers::pi;
inline constexpr double ball_radius = 0.5 * 17.462e-3;
inline constexpr double pitch_radius = 0.5 * 72.5e-3;
inline constexpr double inner_groove_radius = 0.52 * 17.462e-3;  // conformity 0.52
inline constexpr double outer_groove_radius = 0.53 * 17.462e-3;  // conformity 0.53
inline constexpr double arc_angle = 35.0 * pi / 180.0;
inline constexpr double max_approach = 0.02 * ball_radius;  // 175 um
inline constexpr double damping_factor = 0.5;               // s/m
inline constexpr double friction = 0.08, slip_scale = 0.2;  // traction curve: mu_max, m/s
inline constexpr double viscosity = 0.02, pressure_viscosity = 2e-8, limiting_shear = 0.08;
inline constexpr double pocket_clearance = 0.5e-3;
inline constexpr double pocket_angle = 3.0 * 2.0 * pi / 8.0;
inline constexpr double pocket_max_approach = 1e-4;
inline constexpr double inner_land_radius = 33e-3, outer_land_radius = 41e-3;
inline constexpr double land_clearance = 0.3e-3, land_width = 8e-3, land_axial_offset = 0.5e-3;
inline constexpr int land_stations = 4;
inline constexpr double land_max_approach = 50e-6;
double steel_steel();
double steel_brass();
}  // namespace bearing
using namespace bearing;

// ---- configurations ---------------------------------------------------------------------------

enum class Kind { groove, pocket, land };

struct SpatialCase {
  std::string name;
  Kind kind = Kind::groove;
  bool outer = false;  ///< groove: outer ring; land: outer-land guidance
  int arc = 0;         ///< groove: 0 deep groove; +-1 four-point arc with its centre at +-e axially
  PocketShape shape = PocketShape::cylindrical;
};
inline void PrintTo(const SpatialCase& c, std::ostream* os) { *os << c.name; }

std::vector<SpatialCase> all_cases();

/// The test's statement of a groove arc: centre circle and radius, from the bearing's numbers.
struct Groove {
  double centre_radius, centre_axial, groove_radius;
  bool outer;
};
Groove groove_of(const SpatialCase& c);
/// Angle at which a ball at the pitch circle touches the arc (0 deep groove).
double design_angle(const SpatialCase& c);
/// Relative curvatures of ball and race at contact angle a (cos_angle = cos a): rolling direction
/// 1/r_b +- cos a / rho (rho: radius of the contact point), transverse 1/r_b - 1/r_groove.
void groove_curvatures(const Groove& g, double cos_angle, double& kx, double& ky);
HertzPointContact pocket_hertz(PocketShape shape);

struct LawOptions {
  bool damping = true;
  bool traction = true;  ///< traction / friction, film and rolling resistance
};

using AnySegment = std::variant<BallGrooveSegment, BallPocketSegment, CageLandSegment3>;

AnySegment make_segment(const SpatialCase& c, const LawOptions& o = {});
SpatialSegmentResult evaluate_any(const AnySegment& s, const SpatialKinematics& a,
                                  const SpatialKinematics& b);

/// K of the whole contact: Hertz at the placement's contact angle, or Palmgren of all stations.
double expected_stiffness(const SpatialCase& c, double contact_angle);
double law_exponent(const SpatialCase& c);
/// Relative tolerance on K: the Hertz table of a groove interpolates (error below 1e-4 of exact).
/// Round-off in the approach (1e-17 m of coordinates near 0.04 m) allows 1e-10 otherwise.
double stiffness_tolerance(const SpatialCase& c);
/// The validity limit of the configuration's law [m].
double approach_limit(const SpatialCase& c);

// ---- placement --------------------------------------------------------------------------------

Mat3 rotation_about(double angle, const Vec3& axis);
inline Vec3 radial(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }
inline Vec3 tangential(double angle) { return {-std::sin(angle), std::cos(angle), 0.0}; }

/// Groove, pocket: `point` is the contact point; land: the first station on the cage axis.
using Placement = Placed<SpatialKinematics>;

/// Contact angle used for a placement along `dir`: spread around the arc's design angle.
double contact_angle_for(const SpatialCase& c, double dir);

/// Places the bodies so that the segment's approach is `approach` [m] (negative: apart).
/// `dir` [rad] selects the contact: groove, the ball's azimuth in the ring frame (and the contact
/// angle, contact_angle_for); pocket, the direction of the offset around the pocket; land, the
/// direction of the cage's eccentricity in the ring frame. A (ring, cage) and the land's ring sit
/// off-centre and slightly tilted. `shift`: cylindrical pocket, offset along the pocket axis.
Placement place(const SpatialCase& c, double approach, double dir, double shift = 3e-5);

/// Motion of the pair: A spins about its own axis plus a wobble; B moves with A's rigid velocity
/// field at its centre plus `v_rel`, and spins about its own z plus a wobble. Approach rates stay
/// well below 1/damping_factor, so Hunt-Crossley never clips a force in contact.
struct Motion {
  double spin_a;
  Vec3 wobble_a, v_a;
  double spin_b;
  Vec3 wobble_b, v_rel;
};
/// At rest; running (traction saturated); creep (linear part of the traction curve).
std::vector<Motion> motions();
void set_motion(Placement& p, const Motion& m);
/// An upper bound of the approach rate [m/s].
double speed_bound(const Placement& p);

inline constexpr double directions[] = {0.37, 2.1, -2.6};

Placement placed(const SpatialCase& c, double approach, double dir, const Motion& m, double shift = 3e-5);

// ---- helpers ----------------------------------------------------------------------------------

double wrench_norm(const SpatialSegmentResult& r);

/// Makes the approach rate zero (the test's own kinematics): the contact then does no elastic or
/// damping work and the whole power of the contact forces is dissipation.
void stop_approach(const SpatialCase& c, Placement& p);

/// A body's kinematics in a frame rotated by q.
SpatialKinematics rotated(const SpatialKinematics& k, const Mat3& q);

/// Rigid motion of both bodies over a time `dt` with their velocities and angular velocities.
Placement advanced(const Placement& p, double dt);

}  // namespace raceway::contact::test::ball
