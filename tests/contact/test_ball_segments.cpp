// Conformance suite for the spatial contact segments of a ball bearing (contact/ball_segments.hpp,
// STYLE.md habit 11). Every segment kind -- ball/groove (deep groove, inner and outer ring; one arc
// of a four-point inner and outer ring), ball/pocket (cylindrical, spherical) and cage/land (inner,
// outer) -- passes the same checks: no force apart, continuity at onset, action = reaction, its
// normal law, frame invariance, the forward-difference Jacobian of spatial_segment_jacobian against
// central differences, the validity flag, traction opposing sliding, and the power balance. Checks
// particular to each kind follow (contact angle from the geometry, four-point arcs, film from the
// entrainment speed, pocket shapes, land tilt and guidance).
//
// The geometry each check expects (contact normal, contact point, Hertz and Palmgren constants) is
// stated here, independently of contact/ball_segments.cpp, so that the two can disagree.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <ostream>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "contact/segments/ball_segments.hpp"
#include "contact/laws/line_contact.hpp"
#include "contact/laws/point_contact.hpp"
#include "contact/segments/segment_jacobian.hpp"

namespace raceway::contact::test {
namespace {

using std::numbers::pi;

/// A 6309-like deep-groove ball bearing (seed 000), SI. The four-point arcs use the same ball and
/// grooves with a 35 degree design angle; the cage is brass.
namespace bearing {
constexpr double ball_radius = 0.5 * 17.462e-3;
constexpr double pitch_radius = 0.5 * 72.5e-3;
constexpr double inner_groove_radius = 0.52 * 17.462e-3;  // conformity 0.52
constexpr double outer_groove_radius = 0.53 * 17.462e-3;  // conformity 0.53
constexpr double arc_angle = 35.0 * pi / 180.0;
constexpr double max_approach = 0.02 * ball_radius;  // 175 um
constexpr double damping_factor = 0.5;               // s/m
constexpr double friction = 0.08, slip_scale = 0.2;  // traction curve: mu_max, m/s
constexpr double viscosity = 0.02, pressure_viscosity = 2e-8, limiting_shear = 0.08;
constexpr double pocket_clearance = 0.5e-3;
constexpr double pocket_angle = 3.0 * 2.0 * pi / 8.0;
constexpr double pocket_max_approach = 1e-4;
constexpr double inner_land_radius = 33e-3, outer_land_radius = 41e-3;
constexpr double land_clearance = 0.3e-3, land_width = 8e-3, land_axial_offset = 0.5e-3;
constexpr int land_stations = 4;
constexpr double land_max_approach = 50e-6;
double steel_steel() { return reduced_modulus(208e9, 0.3, 208e9, 0.3); }
double steel_brass() { return reduced_modulus(208e9, 0.3, 100e9, 0.34); }
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
[[maybe_unused]] void PrintTo(const SpatialCase& c, std::ostream* os) { *os << c.name; }

std::vector<SpatialCase> all_cases() {
  return {
      {"inner_groove", Kind::groove, false, 0, PocketShape::cylindrical},
      {"outer_groove", Kind::groove, true, 0, PocketShape::cylindrical},
      {"four_point_inner_arc", Kind::groove, false, -1, PocketShape::cylindrical},
      {"four_point_outer_arc", Kind::groove, true, +1, PocketShape::cylindrical},
      {"cylindrical_pocket", Kind::pocket, false, 0, PocketShape::cylindrical},
      {"spherical_pocket", Kind::pocket, false, 0, PocketShape::spherical},
      {"inner_land", Kind::land, false, 0, PocketShape::cylindrical},
      {"outer_land", Kind::land, true, 0, PocketShape::cylindrical},
  };
}

/// The test's statement of a groove arc: centre circle and radius, from the bearing's numbers.
struct Groove {
  double centre_radius, centre_axial, groove_radius;
  bool outer;
};
Groove groove_of(const SpatialCase& c) {
  const double g = c.outer ? outer_groove_radius : inner_groove_radius;
  const double m = g - ball_radius;
  const double cos_a = c.arc == 0 ? 1.0 : std::cos(arc_angle);
  const double e = c.arc == 0 ? 0.0 : c.arc * m * std::sin(arc_angle);  // scene.hpp's offset
  return {c.outer ? pitch_radius - m * cos_a : pitch_radius + m * cos_a, e, g, c.outer};
}
/// Angle at which a ball at the pitch circle touches the arc (0 deep groove).
double design_angle(const SpatialCase& c) { return -c.arc * arc_angle; }

/// Relative curvatures of ball and race at contact angle a (cos_angle = cos a): rolling direction
/// 1/r_b +- cos a / rho (rho: radius of the contact point), transverse 1/r_b - 1/r_groove.
void groove_curvatures(const Groove& g, double cos_angle, double& kx, double& ky) {
  const double rho = g.centre_radius + (g.outer ? 1.0 : -1.0) * g.groove_radius * cos_angle;
  kx = 1.0 / ball_radius + (g.outer ? -cos_angle : cos_angle) / rho;
  ky = 1.0 / ball_radius - 1.0 / g.groove_radius;
}

HertzPointContact pocket_hertz(PocketShape shape) {
  const double conform = 1.0 / ball_radius - 1.0 / (ball_radius + 0.5 * pocket_clearance);
  return hertz_point_contact(conform, shape == PocketShape::spherical ? conform : 1.0 / ball_radius,
                             steel_brass());
}

struct LawOptions {
  bool damping = true;
  bool traction = true;  ///< traction / friction, film and rolling resistance
};

using AnySegment = std::variant<BallGrooveSegment, BallPocketSegment, CageLandSegment3>;

AnySegment make_segment(const SpatialCase& c, const LawOptions& o = {}) {
  const double damping = o.damping ? damping_factor : 0.0;
  const TractionCurve curve{o.traction ? friction : 0.0, slip_scale};
  switch (c.kind) {
    case Kind::groove: {
      const Groove g = groove_of(c);
      BallGrooveSegment s;
      s.centre_radius = g.centre_radius;
      s.centre_axial = g.centre_axial;
      s.groove_radius = g.groove_radius;
      s.ball_radius = ball_radius;
      s.outer = g.outer;
      s.normal.hertz = HertzTable(
          [g](double cos_angle, double& kx, double& ky) { groove_curvatures(g, cos_angle, kx, ky); },
          0.3, 1.0, 29, steel_steel());
      s.normal.reduced_modulus = steel_steel();
      s.normal.damping_factor = damping;
      s.normal.max_approach = max_approach;
      s.traction.model = o.traction ? TractionModel::curve : TractionModel::none;
      s.traction.friction_coefficient = friction;
      s.traction.slip_velocity_scale = slip_scale;
      if (o.traction) s.lubricant = {viscosity, pressure_viscosity, limiting_shear};
      s.rolling_resistance = o.traction;
      return s;
    }
    case Kind::pocket: {
      BallPocketSegment s;
      s.pitch_radius = pitch_radius;
      s.pocket_angle = pocket_angle;
      s.clearance = pocket_clearance;
      s.ball_radius = ball_radius;
      s.shape = c.shape;
      s.normal.hertz = HertzTable(pocket_hertz(c.shape));
      s.normal.reduced_modulus = steel_brass();
      s.normal.damping_factor = damping;
      s.normal.max_approach = pocket_max_approach;
      s.friction = curve;
      return s;
    }
    case Kind::land: {
      CageLandSegment3 s;
      s.land_radius = c.outer ? outer_land_radius : inner_land_radius;
      s.clearance = land_clearance;
      s.width = land_width;
      s.axial_offset = land_axial_offset;
      s.stations = land_stations;
      s.outer_land = c.outer;
      s.law = make_line_contact_law(steel_brass(), land_width / land_stations, 1, 0.0, damping,
                                    land_max_approach);
      s.friction = curve;
      return s;
    }
  }
  throw std::logic_error("unknown segment kind");
}

SpatialSegmentResult evaluate_any(const AnySegment& s, const SpatialKinematics& a,
                                  const SpatialKinematics& b) {
  return std::visit([&](const auto& seg) { return evaluate(seg, a, b); }, s);
}

bool jacobian_any(const AnySegment& s, const SpatialKinematics& a, const SpatialKinematics& b,
                  const SpatialSegmentResult& base, const SpatialSteps& step, SpatialJacobian& jac) {
  return std::visit(
      [&](const auto& seg) { return segment_jacobian(seg, a, b, base, step, jac); }, s);
}

/// K of the whole contact: Hertz at the placement's contact angle, or Palmgren of all stations.
double expected_stiffness(const SpatialCase& c, double contact_angle) {
  switch (c.kind) {
    case Kind::groove: {
      double kx = 0, ky = 0;
      groove_curvatures(groove_of(c), std::cos(contact_angle), kx, ky);
      return hertz_point_contact(kx, ky, steel_steel()).stiffness;
    }
    case Kind::pocket: return pocket_hertz(c.shape).stiffness;
    case Kind::land: return land_stations * palmgren_stiffness(steel_brass(), land_width / land_stations);
  }
  return 0;
}
double law_exponent(const SpatialCase& c) { return c.kind == Kind::land ? palmgren_exponent : 1.5; }
/// Relative tolerance on K: the Hertz table of a groove interpolates (error below 1e-4 of exact).
/// Round-off in the approach (1e-17 m of coordinates near 0.04 m) allows 1e-10 otherwise.
double stiffness_tolerance(const SpatialCase& c) { return c.kind == Kind::groove ? 2e-4 : 1e-10; }

// ---- placement --------------------------------------------------------------------------------

Mat3 rotation_about(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}
Vec3 radial(double angle) { return {std::cos(angle), std::sin(angle), 0.0}; }
Vec3 tangential(double angle) { return {-std::sin(angle), std::cos(angle), 0.0}; }

struct Placement {
  SpatialKinematics a, b;
  Vec3 normal_on_b = Vec3::Zero();  ///< the test's statement: unit direction of the normal force on B
  Vec3 point = Vec3::Zero();        ///< on the line of action (groove, pocket: the contact point)
  double contact_angle = 0;         ///< groove: the placed contact angle
};

/// Contact angle used for a placement along `dir`: spread around the arc's design angle.
double contact_angle_for(const SpatialCase& c, double dir) {
  return c.arc == 0 ? 0.25 * std::sin(2 * dir + 0.4) : design_angle(c) + 0.05 * std::sin(dir);
}

/// Places the bodies so that the segment's approach is `approach` [m] (negative: apart).
/// `dir` [rad] selects the contact: groove, the ball's azimuth in the ring frame (and the contact
/// angle, contact_angle_for); pocket, the direction of the offset around the pocket; land, the
/// direction of the cage's eccentricity in the ring frame. A (ring, cage) and the land's ring sit
/// off-centre and slightly tilted. `shift`: cylindrical pocket, offset along the pocket axis.
Placement place(const SpatialCase& c, double approach, double dir, double shift = 3e-5) {
  Placement p;
  const Vec3 a_offset(2e-4, -1e-4, 5e-5);
  const Mat3 a_rotation = rotation_about(0.004, Vec3(1, 2, 0)) * rotation_about(1.3, Vec3::UnitZ());
  switch (c.kind) {
    case Kind::groove: {
      p.a.position = a_offset;
      p.a.rotation = a_rotation;
      const Groove g = groove_of(c);
      const double alpha = contact_angle_for(c, dir);
      const Vec3 n_ring = (c.outer ? 1.0 : -1.0) * std::cos(alpha) * radial(dir) + std::sin(alpha) * Vec3::UnitZ();
      const Vec3 centre = g.centre_radius * radial(dir) + g.centre_axial * Vec3::UnitZ();
      const Vec3 ball = centre + (g.groove_radius - ball_radius + approach) * n_ring;
      p.b.position = p.a.position + p.a.rotation * ball;
      p.normal_on_b = -(p.a.rotation * n_ring);
      p.point = p.a.position + p.a.rotation * (centre + g.groove_radius * n_ring);
      p.contact_angle = alpha;
      break;
    }
    case Kind::pocket: {
      p.a.position = a_offset;
      p.a.rotation = a_rotation;
      const Vec3 er = radial(pocket_angle), et = tangential(pocket_angle);
      Vec3 n_cage = std::cos(dir) * et + std::sin(dir) * Vec3::UnitZ();
      Vec3 offset = shift * er;
      if (c.shape == PocketShape::spherical) {
        const double gamma = 0.3 * std::sin(dir + 1.0);
        n_cage = std::cos(gamma) * n_cage + std::sin(gamma) * er;
        offset = Vec3::Zero();
      }
      const Vec3 ball = pitch_radius * er + (0.5 * pocket_clearance + approach) * n_cage + offset;
      p.b.position = p.a.position + p.a.rotation * ball;
      p.normal_on_b = -(p.a.rotation * n_cage);
      p.point = p.b.position + ball_radius * (p.a.rotation * n_cage);
      break;
    }
    case Kind::land: {
      p.b.position = Vec3(1e-4, 2e-4, -1e-4);
      p.b.rotation = rotation_about(0.003, Vec3(2, -1, 0)) * rotation_about(0.4, Vec3::UnitZ());
      const Vec3 centre = (land_clearance + approach) * radial(dir) + 1e-3 * Vec3::UnitZ();
      p.a.position = p.b.position + p.b.rotation * centre;
      p.a.rotation = p.b.rotation * rotation_about(0.9, Vec3::UnitZ());
      p.normal_on_b = p.b.rotation * radial(dir);
      const double zeta0 = land_axial_offset + 0.5 * land_width / land_stations - 0.5 * land_width;
      p.point = p.a.position + zeta0 * p.a.rotation.col(2);
      break;
    }
  }
  return p;
}

/// Motion of the pair: A spins about its own axis plus a wobble; B moves with A's rigid velocity
/// field at its centre plus `v_rel`, and spins about its own z plus a wobble. Approach rates stay
/// well below 1/damping_factor, so Hunt-Crossley never clips a force in contact.
struct Motion {
  double spin_a;
  Vec3 wobble_a, v_a;
  double spin_b;
  Vec3 wobble_b, v_rel;
};
std::vector<Motion> motions() {
  return {
      {0, Vec3::Zero(), Vec3::Zero(), 0, Vec3::Zero(), Vec3::Zero()},  // at rest
      {150, Vec3(0.4, -0.3, 0.2), Vec3(0.01, -0.02, 0.005), 400, Vec3(3, -5, 0),
       Vec3(-0.2, 0.35, 0.1)},  // running: traction saturated
      {0.3, Vec3(0.01, 0.02, 0), Vec3(0.002, -0.001, 0.001), -0.5, Vec3(0.2, -0.1, 0),
       Vec3(-0.003, 0.002, 0.001)},  // creep: linear part of the traction curve
  };
}
void set_motion(Placement& p, const Motion& m) {
  p.a.velocity = m.v_a;
  p.a.angular_velocity = m.spin_a * p.a.rotation.col(2) + m.wobble_a;
  p.b.angular_velocity = m.spin_b * p.b.rotation.col(2) + m.wobble_b;
  p.b.velocity = p.a.velocity + p.a.angular_velocity.cross(p.b.position - p.a.position) + m.v_rel;
}
/// An upper bound of the approach rate [m/s].
double speed_bound(const Placement& p) {
  const Vec3 v_rel = p.b.velocity - p.a.velocity - p.a.angular_velocity.cross(p.b.position - p.a.position);
  return v_rel.norm() + 0.1 * (p.b.angular_velocity - p.a.angular_velocity).norm();
}

constexpr double directions[] = {0.37, 2.1, -2.6};

Placement placed(const SpatialCase& c, double approach, double dir, const Motion& m, double shift = 3e-5) {
  Placement p = place(c, approach, dir, shift);
  set_motion(p, m);
  return p;
}

// ---- helpers ----------------------------------------------------------------------------------

double wrench_norm(const SpatialSegmentResult& r) {
  return r.on_a.force.norm() + r.on_a.moment.norm() + r.on_b.force.norm() + r.on_b.moment.norm();
}
std::array<double, point_diagnostics_count> diagnostics_of(const PointDiagnostics& d) {
  return {d.approach,       d.normal_force,   d.contact_angle,         d.max_pressure,
          d.film_thickness, d.slip_velocity,  d.spin_velocity,         d.traction_force,
          d.circumferential_force, d.elastic_energy, d.power_loss};
}
/// Round-off floors of the diagnostics (in diagnostics_of order): far below any physical value.
constexpr std::array<double, point_diagnostics_count> diagnostic_floor = {
    1e-18, 1e-10, 1e-12, 1e-2, 1e-20, 1e-12, 1e-10, 1e-10, 1e-10, 1e-15, 1e-10};

/// Sum over both bodies of F.v + M.w [W] and the sum of the magnitudes of its terms.
struct Power {
  double total, scale;
};
Power power_on_bodies(const SpatialSegmentResult& r, const SpatialKinematics& a, const SpatialKinematics& b) {
  const double t[4] = {r.on_a.force.dot(a.velocity), r.on_a.moment.dot(a.angular_velocity),
                       r.on_b.force.dot(b.velocity), r.on_b.moment.dot(b.angular_velocity)};
  return {t[0] + t[1] + t[2] + t[3], std::abs(t[0]) + std::abs(t[1]) + std::abs(t[2]) + std::abs(t[3])};
}

/// Makes the approach rate zero (the test's own kinematics): the contact then does no elastic or
/// damping work and the whole power of the contact forces is dissipation.
void stop_approach(const SpatialCase& c, Placement& p) {
  const Vec3 n = p.normal_on_b;  // into B's side: the approach rate is -n . (v_B - v_A) at the point
  if (c.kind == Kind::land) {
    // Every station must have zero rate: remove the relative rotation that tilts the cage towards
    // the ring about the axis (cage axis x n), then the relative velocity along n at one station.
    const Vec3 tilt_axis = p.a.rotation.col(2).cross(n).normalized();
    const Vec3 w_rel = p.a.angular_velocity - p.b.angular_velocity;
    p.a.angular_velocity -= w_rel.dot(tilt_axis) * tilt_axis;
  }
  const Vec3 va = p.a.velocity + p.a.angular_velocity.cross(p.point - p.a.position);
  const Vec3 vb = p.b.velocity + p.b.angular_velocity.cross(p.point - p.b.position);
  const double rate = -n.dot(vb - va);
  p.b.velocity += rate * n;
}

SpatialKinematics rotated(const SpatialKinematics& k, const Mat3& q) {
  SpatialKinematics out;
  out.position = q * k.position;
  out.rotation = q * k.rotation;
  out.velocity = q * k.velocity;
  out.angular_velocity = q * k.angular_velocity;
  return out;
}

// ---- conformance ------------------------------------------------------------------------------

class SpatialConformance : public ::testing::TestWithParam<SpatialCase> {
 protected:
  const SpatialCase& seg_case() const { return GetParam(); }
  AnySegment segment(const LawOptions& o = {}) const { return make_segment(GetParam(), o); }
};

// 1. No force, moment, energy or loss when apart, whatever the velocities; approach reported.
TEST_P(SpatialConformance, NoForceWhenApart) {
  const AnySegment seg = segment();
  for (const double separation : {1e-12, 1e-9, 1e-6, 5e-5}) {
    for (const double dir : directions) {
      for (const Motion& m : motions()) {
        const Placement p = placed(seg_case(), -separation, dir, m);
        const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
        EXPECT_TRUE(r.valid);
        EXPECT_EQ(wrench_norm(r), 0.0) << "separation " << separation;
        EXPECT_EQ(r.diagnostics.normal_force, 0.0);
        EXPECT_EQ(r.diagnostics.traction_force, 0.0);
        EXPECT_EQ(r.diagnostics.elastic_energy, 0.0);
        EXPECT_EQ(r.diagnostics.power_loss, 0.0);
        EXPECT_NEAR(r.diagnostics.approach, -separation, 1e-14);
      }
    }
  }
  // Rushing towards each other at 1 m/s, still apart: nothing.
  Placement p = place(seg_case(), -1e-9, 0.4);
  p.b.velocity = -p.normal_on_b;
  EXPECT_EQ(wrench_norm(evaluate_any(seg, p.a, p.b)), 0.0);
}

// 2. Continuity at onset: force and moment vanish with the approach and so does their slope (the
// law's exponent is above 1). A constant term, a damper c * rate or a rolling-resistance couple
// growing like Q^0.47 would break the bounds by orders of magnitude.
TEST_P(SpatialConformance, ContinuousAtOnset) {
  const AnySegment seg = segment();  // everything on
  const double n_exp = law_exponent(seg_case());
  for (const Motion& m : motions()) {
    for (const double dir : directions) {
      const Placement below = placed(seg_case(), -1e-13, dir, m);
      EXPECT_EQ(wrench_norm(evaluate_any(seg, below.a, below.b)), 0.0);
      for (const double approach : {1e-12, 1e-14}) {
        const Placement p = placed(seg_case(), approach, dir, m);
        const double k = expected_stiffness(seg_case(), p.contact_angle);
        const double bound = k * std::pow(approach, n_exp) * (1 + damping_factor * speed_bound(p)) *
                             (1 + friction) * (1 + 1e-3);
        const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
        EXPECT_LE(r.on_b.force.norm(), bound) << "approach " << approach;
        // Moments: levers below 0.1 m, couples (spin, rolling resistance) below 0.1 m times Q.
        EXPECT_LE(r.on_a.moment.norm() + r.on_b.moment.norm(), 0.4 * bound) << "approach " << approach;
      }
      EXPECT_LT(evaluate_any(seg, placed(seg_case(), 1e-14, dir, m).a, placed(seg_case(), 1e-14, dir, m).b)
                    .on_b.force.norm(),
                1e-6);
      // Secant slope of the whole wrench (moments over 0.05 m) near onset against one in operation:
      // it falls like approach^(n-1).
      auto slope = [&](double approach) {
        const Placement p1 = placed(seg_case(), approach, dir, m);
        const Placement p2 = placed(seg_case(), 2 * approach, dir, m);
        const SpatialSegmentResult r1 = evaluate_any(seg, p1.a, p1.b), r2 = evaluate_any(seg, p2.a, p2.b);
        return ((r2.on_b.force - r1.on_b.force).norm() + (r2.on_b.moment - r1.on_b.moment).norm() / 0.05 +
                (r2.on_a.moment - r1.on_a.moment).norm() / 0.05) / approach;
      };
      const double at_onset = slope(1e-12), in_operation = slope(1e-5);
      ASSERT_GT(in_operation, 0.0);
      EXPECT_LT(at_onset, 3.0 * std::pow(1e-12 / 1e-5, n_exp - 1) * in_operation);
    }
  }
  // The elastic law alone grows exactly like approach^n.
  const AnySegment elastic = segment({.damping = false, .traction = false});
  for (const double dir : directions) {
    const Placement p1 = placed(seg_case(), 1e-8, dir, motions()[1]);
    const Placement p2 = placed(seg_case(), 1e-6, dir, motions()[1]);
    const double f1 = evaluate_any(elastic, p1.a, p1.b).on_b.force.norm();
    const double f2 = evaluate_any(elastic, p2.a, p2.b).on_b.force.norm();
    ASSERT_GT(f1, 0.0);
    EXPECT_NEAR(std::log(f2 / f1) / std::log(100.0), n_exp, 1e-7);
  }
}

// 3. Action equals reaction; the total moment about the origin vanishes (configuration far from it).
TEST_P(SpatialConformance, ActionEqualsReaction) {
  const AnySegment seg = segment();
  const Vec3 shift(0.031, -0.047, 0.022);
  for (const Motion& m : motions()) {
    for (const double dir : directions) {
      for (const double approach : {1e-7, 3e-6, 2e-5}) {
        Placement p = placed(seg_case(), approach, dir, m);
        p.a.position += shift;
        p.b.position += shift;
        const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
        ASSERT_TRUE(r.valid);
        const double f = r.on_b.force.norm();
        ASSERT_GT(f, 0.0);
        EXPECT_LE((r.on_a.force + r.on_b.force).norm(), 1e-12 * f);
        const Vec3 ma = p.a.position.cross(r.on_a.force), mb = p.b.position.cross(r.on_b.force);
        const double scale = r.on_a.moment.norm() + r.on_b.moment.norm() + ma.norm() + mb.norm();
        EXPECT_LE((r.on_a.moment + r.on_b.moment + ma + mb).norm(), 1e-10 * scale)
            << "dir " << dir << " approach " << approach;
      }
    }
  }
}

// 4. The normal law (Hertz point contact or Palmgren stations) along the expected normal, with its
// elastic energy; the diagnostics that follow from the geometry.
TEST_P(SpatialConformance, NormalLawAlongNormal) {
  const AnySegment seg = segment({.damping = false, .traction = false});
  const double n_exp = law_exponent(seg_case());
  for (const double approach : {1e-6, 5e-6, 3e-5}) {
    for (const double dir : directions) {
      const Placement p = placed(seg_case(), approach, dir, motions()[1]);
      const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
      ASSERT_TRUE(r.valid);
      const PointDiagnostics& d = r.diagnostics;
      const double expected = expected_stiffness(seg_case(), p.contact_angle) * std::pow(approach, n_exp);
      EXPECT_NEAR(d.approach, approach, 1e-9 * approach);
      EXPECT_NEAR(d.normal_force, expected, stiffness_tolerance(seg_case()) * expected);
      EXPECT_LE((r.on_b.force - d.normal_force * p.normal_on_b).norm(), 1e-10 * expected);
      EXPECT_NEAR(d.elastic_energy, d.normal_force * approach / (n_exp + 1), 1e-9 * expected * approach);
      EXPECT_EQ(d.film_thickness, 0.0);
      EXPECT_EQ(d.traction_force, 0.0);
      EXPECT_EQ(d.power_loss, 0.0);  // no damping, no traction
      if (seg_case().kind == Kind::land) {
        EXPECT_EQ(d.circumferential_force, 0.0);  // B is the ring: no circumferential direction
        EXPECT_GT(d.max_pressure, 0.0);
      } else {
        const Vec3 e_theta = Vec3::UnitZ().cross(Vec3(p.b.position.x(), p.b.position.y(), 0).normalized());
        EXPECT_NEAR(d.circumferential_force, r.on_b.force.dot(e_theta), 1e-12 * expected);
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

// 5. Frame invariance: rotating the whole configuration (poses and rates) rotates forces and
// moments and leaves the scalar diagnostics unchanged; about an arbitrary axis the bearing's own
// circumferential direction is not rotated with it, so that one diagnostic is only checked about z.
TEST_P(SpatialConformance, FrameInvariance) {
  const AnySegment seg = segment();
  const struct {
    Mat3 q;
    bool about_z;
  } rotations[] = {{rotation_about(0.83, Vec3::UnitZ()), true},
                   {rotation_about(-2.4, Vec3::UnitZ()), true},
                   {rotation_about(1.1, Vec3(1, -2, 0.5)), false}};
  for (const Motion& m : motions()) {
    for (const double dir : directions) {
      const Placement p = placed(seg_case(), 1.5e-5, dir, m);
      const SpatialSegmentResult r0 = evaluate_any(seg, p.a, p.b);
      ASSERT_TRUE(r0.valid);
      const double f = r0.on_b.force.norm();
      const double tol_f = 1e-10 * f, tol_m = 1e-10 * (0.05 * f + r0.on_a.moment.norm() + r0.on_b.moment.norm());
      const auto d0 = diagnostics_of(r0.diagnostics);
      for (const auto& [q, about_z] : rotations) {
        const SpatialSegmentResult r = evaluate_any(seg, rotated(p.a, q), rotated(p.b, q));
        ASSERT_TRUE(r.valid);
        EXPECT_LE((r.on_a.force - q * r0.on_a.force).norm(), tol_f);
        EXPECT_LE((r.on_b.force - q * r0.on_b.force).norm(), tol_f);
        EXPECT_LE((r.on_a.moment - q * r0.on_a.moment).norm(), tol_m);
        EXPECT_LE((r.on_b.moment - q * r0.on_b.moment).norm(), tol_m);
        const auto d = diagnostics_of(r.diagnostics);
        for (int i = 0; i < point_diagnostics_count; ++i) {
          if (!about_z && i == 8) continue;  // circumferential_force
          EXPECT_NEAR(d[i], d0[i], 1e-10 * std::abs(d0[i]) + diagnostic_floor[i]) << "diagnostic " << i;
        }
      }
    }
  }
}

// 6. The forward-difference Jacobian of spatial_segment_jacobian against central differences
// computed here with the same definition of the 24 perturbations; action = reaction in the block;
// skipped columns; the ball's orientation (a sphere's) changes nothing; the normal stiffness.
using Jacobian = SpatialJacobian;
using Steps = SpatialSteps;
Steps steps_of(double position, double rotation, double velocity, double angular_velocity) {
  Steps s{};
  for (int body = 0; body < 2; ++body)
    for (int i = 0; i < 3; ++i) {
      s[12 * body + i] = position;
      s[12 * body + 3 + i] = rotation;
      s[12 * body + 6 + i] = velocity;
      s[12 * body + 9 + i] = angular_velocity;
    }
  return s;
}
void perturb(Placement& p, int j, double h) {
  SpatialKinematics& k = j < 12 ? p.a : p.b;
  const int c = j % 12, axis = c % 3;
  if (c < 3) k.position[axis] += h;
  else if (c < 6) k.rotation = rotation_about(h, Vec3::Unit(axis)) * k.rotation;
  else if (c < 9) k.velocity[axis] += h;
  else k.angular_velocity[axis] += h;
}
std::array<double, 12> rows_of(const SpatialSegmentResult& r) {
  std::array<double, 12> out{};
  for (int i = 0; i < 3; ++i) {
    out[i] = r.on_a.force[i];
    out[3 + i] = r.on_a.moment[i];
    out[6 + i] = r.on_b.force[i];
    out[9 + i] = r.on_b.moment[i];
  }
  return out;
}
constexpr double lever = 0.05;  // m: moment rows are divided by it to compare them with force rows
double row_weight(int i) { return (i % 6) >= 3 ? 1.0 / lever : 1.0; }

TEST_P(SpatialConformance, JacobianMatchesCentralDifferences) {
  const Steps forward = steps_of(1e-10, 1e-9, 1e-7, 1e-6);
  const Steps central = steps_of(1e-9, 1e-8, 1e-5, 1e-4);
  for (const LawOptions& options : {LawOptions{}, LawOptions{.damping = false, .traction = false}}) {
    const AnySegment seg = segment(options);
    for (const Motion& m : {motions()[1], motions()[2]}) {
      for (const double dir : directions) {
        const Placement p = placed(seg_case(), 2e-5, dir, m);
        const SpatialSegmentResult base = evaluate_any(seg, p.a, p.b);
        ASSERT_TRUE(base.valid);
        Jacobian jac;
        for (auto& row : jac) row.fill(7.0);  // garbage: every column must be overwritten
        ASSERT_TRUE(jacobian_any(seg, p.a, p.b, base, forward, jac));
        const double scale = base.on_b.force.norm();
        for (int j = 0; j < 24; ++j) {
          Placement plus = p, minus = p;
          perturb(plus, j, central[j]);
          perturb(minus, j, -central[j]);
          const auto fp = rows_of(evaluate_any(seg, plus.a, plus.b));
          const auto fm = rows_of(evaluate_any(seg, minus.a, minus.b));
          double diff = 0, norm = 0;
          for (int i = 0; i < 12; ++i) {
            const double ref = (fp[i] - fm[i]) / (2 * central[j]) * row_weight(i);
            const double got = jac[i][j] * row_weight(i);
            diff += (got - ref) * (got - ref);
            norm += ref * ref;
          }
          // Forward truncation ~ h / approach (5e-6) or h / slip scale; round-off ~ 1e-14 F / h.
          const double floor = 1e-12 * scale / forward[j];
          EXPECT_LE(std::sqrt(diff), 1e-3 * std::sqrt(norm) + floor) << "column " << j << " dir " << dir;
          for (int i = 0; i < 3; ++i)
            EXPECT_NEAR(jac[i][j], -jac[6 + i][j], 1e-12 * (std::abs(jac[i][j]) + floor)) << "column " << j;
        }
        if (seg_case().kind != Kind::land) {  // B is a ball: its orientation is not a coordinate
          for (int j = 15; j < 18; ++j)
            for (int i = 0; i < 12; ++i) EXPECT_EQ(jac[i][j], 0.0) << "ball rotation column " << j;
        }
        // Normal stiffness of the elastic law: n . dF_B/dx_B . n = -n Q / approach.
        if (!options.damping && !options.traction) {
          const Vec3 n = p.normal_on_b;
          Vec3 column = Vec3::Zero();
          for (int axis = 0; axis < 3; ++axis)
            column += n[axis] * Vec3(jac[6][12 + axis], jac[7][12 + axis], jac[8][12 + axis]);
          const double stiffness = law_exponent(seg_case()) * base.diagnostics.normal_force / 2e-5;
          // B moving along n (away from A's material) lowers the approach for groove and pocket
          // (n points out of the contact into B) and for the land (n = the cage's eccentricity; the
          // ring moving along it recentres the cage).
          EXPECT_NEAR(n.dot(column), -stiffness, 1e-4 * stiffness);
        }
      }
    }
  }
  // A zero step skips its column; a perturbation beyond the validity limit is reported.
  const AnySegment seg = segment();
  const Placement p = placed(seg_case(), 2e-5, 0.37, motions()[1]);
  const SpatialSegmentResult base = evaluate_any(seg, p.a, p.b);
  Steps some = forward;
  some[0] = 0.0;
  some[21] = 0.0;
  Jacobian jac;
  for (auto& row : jac) row.fill(7.0);
  ASSERT_TRUE(jacobian_any(seg, p.a, p.b, base, some, jac));
  for (int i = 0; i < 12; ++i) {
    EXPECT_EQ(jac[i][0], 0.0);
    EXPECT_EQ(jac[i][21], 0.0);
  }
  const double limit = seg_case().kind == Kind::groove   ? max_approach
                       : seg_case().kind == Kind::pocket ? pocket_max_approach
                                                         : land_max_approach;
  const Placement edge = placed(seg_case(), limit - 1e-12, 0.37, motions()[0]);
  const SpatialSegmentResult at_edge = evaluate_any(seg, edge.a, edge.b);
  ASSERT_TRUE(at_edge.valid);
  Steps big{};
  for (int axis = 0; axis < 3; ++axis) big[12 + axis] = -1e-6 * edge.normal_on_b[axis];  // B deeper
  EXPECT_FALSE(jacobian_any(seg, edge.a, edge.b, at_edge, big, jac));
}

// 7. Validity: beyond the law's limit (recoverable), and NaN in the input (no garbage out).
TEST_P(SpatialConformance, ValidityFlag) {
  const AnySegment seg = segment();
  const double limit = seg_case().kind == Kind::groove   ? max_approach
                       : seg_case().kind == Kind::pocket ? pocket_max_approach
                                                         : land_max_approach;
  for (const double dir : directions) {
    const Placement inside = placed(seg_case(), 0.99 * limit, dir, motions()[2]);
    EXPECT_TRUE(evaluate_any(seg, inside.a, inside.b).valid);
    const Placement beyond = placed(seg_case(), 1.01 * limit, dir, motions()[2]);
    EXPECT_FALSE(evaluate_any(seg, beyond.a, beyond.b).valid);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int which = 0; which < 4; ++which) {
    Placement p = placed(seg_case(), 1e-5, 0.37, motions()[1]);
    if (which == 0) p.b.position.x() = nan;
    if (which == 1) p.a.rotation(0, 2) = nan;
    if (which == 2) p.a.angular_velocity.y() = nan;
    if (which == 3) p.b.velocity.z() = nan;
    const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
    EXPECT_FALSE(r.valid) << "NaN case " << which;
    EXPECT_EQ(wrench_norm(r), 0.0) << "NaN case " << which;
  }
}

// 8. Traction (friction) opposes the sliding: B slides across A at rest, without rotation; the
// tangential force is mu(s) Q exactly (uniform sliding over the contact) and points against it.
TEST_P(SpatialConformance, TractionOpposesSliding) {
  const AnySegment seg = segment();
  for (const double dir : directions) {
    for (const double angle : {0.0, 1.0, 2.5, -2.0}) {
      Placement p = place(seg_case(), 2e-5, dir);
      const Vec3 n = p.normal_on_b;
      const Vec3 t1 = n.cross(n.unitOrthogonal()).normalized(), t2 = n.cross(t1);
      const Vec3 t = std::cos(angle) * t1 + std::sin(angle) * t2;
      const double speed = 0.15;
      p.b.velocity = speed * t;
      const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
      ASSERT_TRUE(r.valid);
      const double q = r.diagnostics.normal_force;
      ASSERT_GT(q, 0.0);
      const Vec3 f_t = r.on_b.force - r.on_b.force.dot(n) * n;
      const double expected = friction * std::tanh(speed / slip_scale) * q;
      EXPECT_NEAR(f_t.norm(), expected, 1e-9 * expected);
      EXPECT_LE((f_t + f_t.norm() * t).norm(), 1e-9 * expected) << "not against the sliding";
      EXPECT_NEAR(r.diagnostics.traction_force, expected, 1e-9 * expected);
      EXPECT_NEAR(r.diagnostics.slip_velocity, speed, 1e-12);
      EXPECT_NEAR(r.diagnostics.power_loss, expected * speed, 1e-9 * expected * speed);
    }
  }
}

// 9. Power: the loss is never negative; with no approach rate (no elastic or damping work) it is
// exactly minus the power of the contact forces and moments on the two bodies.
TEST_P(SpatialConformance, PowerLossIsDissipation) {
  const AnySegment seg = segment();
  for (const Motion& m : motions()) {
    for (const double dir : directions) {
      for (const double approach : {3e-6, 2e-5}) {
        Placement p = placed(seg_case(), approach, dir, m);
        const SpatialSegmentResult moving = evaluate_any(seg, p.a, p.b);
        EXPECT_GE(moving.diagnostics.power_loss, 0.0);
        stop_approach(seg_case(), p);
        const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
        ASSERT_TRUE(r.valid);
        const Power power = power_on_bodies(r, p.a, p.b);
        EXPECT_GE(r.diagnostics.power_loss, 0.0);
        EXPECT_NEAR(r.diagnostics.power_loss, -power.total, 1e-9 * power.scale + 1e-15)
            << "dir " << dir << " approach " << approach;
        if (&m != &motions()[0] && m.spin_a != 0) {
          EXPECT_GT(r.diagnostics.power_loss, 0.0);
        }
      }
    }
  }
}

// 10. Energy balance in any motion: the work of the contact on the two bodies goes into the elastic
// energy or is dissipated, loss = -(F.v + M.w over both bodies) - dE/dt, with dE/dt from the
// elastic_energy diagnostic of the configuration advanced rigidly in time (ball/groove: Q_elastic
// times the rate of the approach diagnostic). A wrong sign or a wrong value of the approach rate
// (damping, Hunt-Crossley) breaks it.
Placement advanced(const Placement& p, double dt) {
  Placement q = p;
  for (SpatialKinematics* k : {&q.a, &q.b}) {
    k->position += dt * k->velocity;
    const double w = k->angular_velocity.norm();
    if (w > 0) k->rotation = rotation_about(w * dt, k->angular_velocity) * k->rotation;
  }
  return q;
}

TEST_P(SpatialConformance, EnergyBalance) {
  const AnySegment seg = segment();
  const double dt = 5e-9;  // s: displacements of a few nm against approaches of microns
  for (const Motion& m : motions()) {
    for (const double dir : directions) {
      for (const double approach : {3e-6, 2e-5}) {
        const Placement p = placed(seg_case(), approach, dir, m);
        const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
        ASSERT_TRUE(r.valid);
        const Placement later = advanced(p, dt), earlier = advanced(p, -dt);
        const PointDiagnostics after = evaluate_any(seg, later.a, later.b).diagnostics;
        const PointDiagnostics before = evaluate_any(seg, earlier.a, earlier.b).diagnostics;
        double energy_rate = (after.elastic_energy - before.elastic_energy) / (2 * dt);
        if (seg_case().kind == Kind::groove) {
          // K depends on the contact angle, so (2/5) K delta^(5/2) is not a potential of the normal
          // force (it changes by dK/dt too): the elastic power is Q_elastic d(delta)/dt.
          const double elastic_force = 2.5 * r.diagnostics.elastic_energy / approach;
          energy_rate = elastic_force * (after.approach - before.approach) / (2 * dt);
        }
        const Power power = power_on_bodies(r, p.a, p.b);
        EXPECT_NEAR(r.diagnostics.power_loss, -power.total - energy_rate,
                    1e-6 * (power.scale + std::abs(energy_rate)) + 1e-12)
            << "dir " << dir << " approach " << approach;
      }
    }
  }
}

// 11. Hunt-Crossley damping: approaching at speed v multiplies the elastic force by (1 + c v) and
// dissipates c v^2 Q_elastic; separating faster than 1/c leaves no force (a contact cannot pull),
// and the elastic force's work is then the loss.
TEST_P(SpatialConformance, HuntCrossleyDamping) {
  const AnySegment seg = segment({.damping = true, .traction = false});
  const double n_exp = law_exponent(seg_case());
  for (const double dir : directions) {
    const double approach = 1e-5;
    const Placement rest = place(seg_case(), approach, dir);
    const double elastic = evaluate_any(seg, rest.a, rest.b).diagnostics.normal_force;
    const double k = expected_stiffness(seg_case(), rest.contact_angle);
    EXPECT_NEAR(elastic, k * std::pow(approach, n_exp), stiffness_tolerance(seg_case()) * elastic);
    for (const double speed : {0.3, -0.8, -3.0}) {  // > 0: approaching
      Placement p = rest;
      p.b.velocity = -speed * p.normal_on_b;  // B moving against the normal force on it
      const SpatialSegmentResult r = evaluate_any(seg, p.a, p.b);
      const double expected = std::max(0.0, elastic * (1 + damping_factor * speed));
      EXPECT_NEAR(r.diagnostics.normal_force, expected, 1e-9 * elastic) << "speed " << speed;
      EXPECT_LE((r.on_b.force - expected * p.normal_on_b).norm(), 1e-9 * elastic);
      const double loss = expected > 0 ? damping_factor * speed * speed * elastic : -elastic * speed;
      EXPECT_NEAR(r.diagnostics.power_loss, loss, 1e-9 * std::abs(loss)) << "speed " << speed;
    }
  }
}

std::string spatial_case_name(const ::testing::TestParamInfo<SpatialCase>& info) { return info.param.name; }
INSTANTIATE_TEST_SUITE_P(Spatial, SpatialConformance, ::testing::ValuesIn(all_cases()), spatial_case_name);

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
}  // namespace raceway::contact::test
