// The eight segment kinds of the typed contact conformance suite (test_segment_conformance.cpp,
// test_segment_jacobian.cpp): roller-race, cage-bar and cage-land (planar, PlanarKinematics) and
// ball-groove, ball-pocket and cage-land, roller-end/flange and roller-race slice (spatial,
// SpatialKinematics).
//
// A kind is a small traits struct: the segment type, its configurations (roller_cases.hpp,
// ball_cases.hpp), how to build one with a chosen law and how to place its two bodies at a chosen
// approach along a contact path, the constants of its law, and its family. The family (PlanarFamily,
// SpatialFamily) says what is the same for every kind of a kinematics type: the wrenches as
// 3-vectors (planar: forces in the plane, moments about z), rotating, translating and advancing a
// placement, the test's own perturbation of a kinematic component, the finite-difference steps, and
// which NaN inputs must make a result invalid. The checks are then written once, for every kind.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <numbers>
#include <string>
#include <type_traits>
#include <vector>

#include "ball_cases.hpp"
#include "flange_cases.hpp"
#include "slice_cases.hpp"
#include "contact/segments/diagnostic_fields.hpp"
#include "contact/segments/segment_jacobian.hpp"
#include "roller_cases.hpp"

namespace raceway::contact::test {

/// Which parts of a segment's law a check switches on. `detailed`: the roller segments' law sliced
/// (5 slices) with a 2 um crown; the ball segments' laws have no such option and ignore it.
struct Law {
  bool damping = true;
  bool traction = true;
  bool detailed = false;
};

/// Force and moment on both bodies as 3-vectors (planar: forces in the plane, moments about z).
struct Wrenches {
  Vec3 force_a, moment_a, force_b, moment_b;
  double norm() const { return force_a.norm() + moment_a.norm() + force_b.norm() + moment_b.norm(); }
};

/// A rotation of the whole configuration about an axis through the origin.
struct FrameRotation {
  double angle;
  Vec3 axis;
  bool about_bearing_axis() const { return axis.normalized() == Vec3::UnitZ(); }
  Mat3 matrix() const { return ball::rotation_about(angle, axis); }
};

/// A NaN put into one input of a segment, and what it must do: `geometry`, always an invalid
/// result; `rate`, an invalid result in contact (velocities enter damping and traction there);
/// `free`, nothing asked (the input need not enter) beyond: a result flagged valid is unaffected.
template <class Placement>
struct NanInput {
  enum Effect { geometry, rate, free };
  std::string name;
  Effect effect;
  std::function<void(Placement&)> apply;
};

/// The configurations of one segment kind among all of a family's.
template <class Case, class KindTag>
std::vector<Case> configurations_of(const std::vector<Case>& all, KindTag kind) {
  std::vector<Case> out;
  std::copy_if(all.begin(), all.end(), std::back_inserter(out), [&](const Case& c) { return c.kind == kind; });
  return out;
}

/// Power of the contact on both bodies, sum of F.v + M.w, and the sum of the terms' magnitudes.
struct Power {
  double total, scale;
};

/// The types of a family, from its kinematics type (the Jacobian's layout, contact/segments/
/// segment_jacobian.hpp) and the test's description of a motion of the two bodies.
template <class KinematicsType, class MotionType>
struct FamilyTypes {
  using Kinematics = KinematicsType;
  using Result = typename JacobianShape<Kinematics>::Result;
  using Steps = typename JacobianShape<Kinematics>::Steps;
  using Jacobian = typename JacobianShape<Kinematics>::Matrix;
  static constexpr int components = JacobianShape<Kinematics>::components;
  using Placement = Placed<Kinematics>;
  using Motion = MotionType;
};

// ---- planar family ------------------------------------------------------------------------------

struct PlanarFamily : FamilyTypes<PlanarKinematics, roller::Motion> {
  static constexpr const auto& diagnostic_fields = line_diagnostic_fields;
  static constexpr double lever = 0.03;            ///< m, the largest lever (a ring radius)
  static constexpr double jacobian_lever = 0.02;   ///< m, moment rows over it compare with force rows
  static constexpr double geometry_tolerance = 1e-10;  ///< relative, of what follows from the placement
  static constexpr double approach_tolerance = 1e-15;  ///< m, of a reported approach when apart
  static constexpr double energy_dt = 1e-9;        ///< s, of the energy balance's central difference
  /// Forward steps as a caller of segment_jacobian would choose them: small against the approach
  /// (5 um) and the slip scale (0.05 m/s), large against round-off of coordinates of some 3 cm.
  static constexpr Steps forward_steps = {1e-10, 1e-10, 1e-9, 1e-8, 1e-8, 1e-7,
                                          1e-10, 1e-10, 1e-9, 1e-8, 1e-8, 1e-7};
  /// Central-difference reference: truncation error (h / scale)^2, well below 1e-6.
  static constexpr Steps central_steps = {1e-9, 1e-9, 1e-8, 1e-6, 1e-6, 1e-5,
                                          1e-9, 1e-9, 1e-8, 1e-6, 1e-6, 1e-5};
  static constexpr double jacobian_relative = 1e-4;  ///< of a column against the central reference
  static constexpr double jacobian_roundoff = 1e-13; ///< floor: this times |F| / step
  static constexpr std::array<int, 1> orientation_components = {Component::theta};
  static constexpr std::array<int, 2> skipped_columns = {Component::theta, components + Component::theta};
  /// A segment whose invalid results never carry force (not asked of the roller segments).
  static constexpr bool invalid_has_no_force = false;

  static Vec3 position(const Kinematics& k) { return {k.x, k.y, 0.0}; }
  static Vec3 velocity(const Kinematics& k) { return {k.vx, k.vy, 0.0}; }
  static Vec3 angular_velocity(const Kinematics& k) { return {0.0, 0.0, k.omega}; }
  static void set_velocity(Kinematics& k, const Vec3& v) {
    k.vx = v.x();
    k.vy = v.y();
  }
  static Wrenches wrenches(const Result& r) {
    return {{r.on_a.fx, r.on_a.fy, 0.0}, {0.0, 0.0, r.on_a.mz}, {r.on_b.fx, r.on_b.fy, 0.0}, {0.0, 0.0, r.on_b.mz}};
  }
  /// Column j of a Jacobian block as the change of the wrenches.
  static Wrenches column(const Jacobian& jac, int j) {
    return {{jac[0][j], jac[1][j], 0.0}, {0.0, 0.0, jac[2][j]}, {jac[3][j], jac[4][j], 0.0}, {0.0, 0.0, jac[5][j]}};
  }
  /// Bearing-frame axis moved by a position component, -1 for the others.
  static int position_axis(int component) {
    return component == Component::px ? 0 : component == Component::py ? 1 : -1;
  }
  /// The test's own perturbation of column j (A's components, then B's).
  static void perturb(Placement& p, int j, double h) {
    Kinematics& k = j < components ? p.a : p.b;
    double* field[components] = {&k.x, &k.y, &k.theta, &k.vx, &k.vy, &k.omega};
    *field[j % components] += h;
  }
  static Placement translated(const Placement& p, const Vec3& d) { return roller::translated(p, d.x(), d.y()); }
  static Placement rotated(const Placement& p, const FrameRotation& q) { return roller::rotated(p, q.angle); }
  static Placement advanced(const Placement& p, double dt) { return roller::advanced(p, dt); }
  static std::vector<FrameRotation> frame_rotations() {
    std::vector<FrameRotation> out;
    for (const double angle : {0.7, -2.3, std::numbers::pi / 2, 3.0}) out.push_back({angle, Vec3::UnitZ()});
    return out;
  }
  /// Unit directions in the contact's tangent plane (here: its tangent line, both senses).
  static std::vector<Vec3> tangents(const Vec3& n) { return {Vec3(-n.y(), n.x(), 0.0), Vec3(n.y(), -n.x(), 0.0)}; }
  /// An upper bound of the approach rate: the relative speed of any point within 3 cm of the centres.
  static double speed_bound(const Placement& p) {
    return std::hypot(p.a.vx, p.a.vy) + std::hypot(p.b.vx, p.b.vy) +
           0.03 * (std::abs(p.a.omega) + std::abs(p.b.omega));
  }
  /// Tolerance of diagnostic i (line_diagnostic_fields order) under a rotation of the frame:
  /// forces against the normal force, speeds and powers against the motion's speeds.
  static double diagnostic_tolerance(int i, double value, double normal_force, double speed_scale) {
    const std::array<double, diagnostics_count> scale = {
        std::abs(value), normal_force, normal_force, speed_scale, std::abs(value), normal_force * speed_scale};
    return 1e-10 * scale[static_cast<std::size_t>(i)];
  }
  static std::vector<NanInput<Placement>> nan_inputs() {
    std::vector<NanInput<Placement>> out;
    const char* names[components] = {"x", "y", "theta", "vx", "vy", "omega"};
    for (int j = 0; j < 2 * components; ++j) {
      const int c = j % components;
      const auto effect = position_axis(c) >= 0   ? NanInput<Placement>::geometry
                          : c == Component::theta ? NanInput<Placement>::free
                                                  : NanInput<Placement>::rate;
      out.push_back({std::string(j < components ? "A." : "B.") + names[c], effect,
                     [j](Placement& p) { perturb(p, j, std::numeric_limits<double>::quiet_NaN()); }});
    }
    return out;
  }
  /// Makes the approach rate zero at the test's line of action (B's velocity along the normal).
  static void stop_approach(Placement& p) {
    const Vec3 n = p.normal_on_b;
    const Vec3 va = velocity(p.a) + angular_velocity(p.a).cross(p.point - position(p.a));
    const Vec3 vb = velocity(p.b) + angular_velocity(p.b).cross(p.point - position(p.b));
    set_velocity(p.b, velocity(p.b) - n.dot(vb - va) * n);
  }
};

/// A kind of a family: its segment type, and its configurations among all of the family's.
template <class Family, class SegmentType, class CaseType, std::vector<CaseType> (*all_configurations)(), auto kind>
struct KindOf : Family {
  using Segment = SegmentType;
  using Case = CaseType;
  static std::vector<Case> cases() { return configurations_of(all_configurations(), kind); }
};

/// The planar kinds: the roller configurations of one segment type.
template <class SegmentType, roller::Kind kind>
struct RollerKind : KindOf<PlanarFamily, SegmentType, roller::SegmentCase, &roller::all_segment_cases, kind> {
  using typename RollerKind::KindOf::Case, typename RollerKind::KindOf::Segment;
  using typename PlanarFamily::Placement, typename PlanarFamily::Motion;
  static Segment make(const Case& c, const Law& law) {
    roller::LawOptions o{.damping = law.damping, .traction = law.traction};
    if (law.detailed) {
      o.slices = 5;
      o.crown_drop = 2e-6;
    }
    return std::get<Segment>(roller::make_segment(c, o));
  }
  static std::vector<Motion> motions() { return roller::motions(); }
  /// A off the origin; `shift`: cage bar only, the roller's radial offset from the pocket centre.
  static Placement placed(const Case& c, const Segment& s, double approach, double dir, const Motion& m,
                          double shift = 2e-5) {
    PlanarKinematics a = m.first;
    a.x = 0.3e-3;
    a.y = 0.1e-3;
    return roller::place(c, s, a, m.second, approach, dir, shift);
  }
  static double stiffness(const Case& c, const Placement&) { return roller::expected_stiffness(c); }
  static double exponent(const Case&) { return palmgren_exponent; }
  static double stiffness_tolerance(const Case&) { return 1e-10; }
  static double approach_limit(const Case&) { return roller::seed002::max_approach; }
  static constexpr double damping_factor = roller::seed002::damping_factor;
  static constexpr double friction = roller::seed002::friction_coefficient;
  static constexpr double slip_scale = roller::seed002::slip_velocity_scale;
  static constexpr bool b_orientation_free = true;  ///< B (roller, ring) is round in the plane
  static constexpr bool energy_is_potential = true;
  static void stop_approach(const Case&, Placement& p) { PlanarFamily::stop_approach(p); }
};

// ---- spatial family -----------------------------------------------------------------------------

struct SpatialFamily : FamilyTypes<SpatialKinematics, ball::Motion> {
  static constexpr const auto& diagnostic_fields = point_diagnostic_fields;
  static constexpr double lever = 0.05;
  static constexpr double jacobian_lever = 0.05;
  static constexpr double geometry_tolerance = 1e-9;
  static constexpr double approach_tolerance = 1e-14;
  static constexpr double energy_dt = 5e-9;  // s: displacements of a few nm against approaches of microns
  static Steps steps(double position, double rotation, double velocity, double angular_velocity) {
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
  static inline const Steps forward_steps = steps(1e-10, 1e-9, 1e-7, 1e-6);
  static inline const Steps central_steps = steps(1e-9, 1e-8, 1e-5, 1e-4);
  /// Forward truncation ~ h / approach or h / slip scale; round-off ~ 1e-14 F / h.
  static constexpr double jacobian_relative = 1e-3;
  static constexpr double jacobian_roundoff = 1e-12;
  static constexpr std::array<int, 3> orientation_components = {rotation_x, rotation_y, rotation_z};
  static constexpr std::array<int, 2> skipped_columns = {position_x, components + angular_velocity_z};
  static constexpr bool invalid_has_no_force = true;  ///< never garbage: NaN in, no force out

  static Vec3 position(const Kinematics& k) { return k.position; }
  static Vec3 velocity(const Kinematics& k) { return k.velocity; }
  static Vec3 angular_velocity(const Kinematics& k) { return k.angular_velocity; }
  static void set_velocity(Kinematics& k, const Vec3& v) { k.velocity = v; }
  static Wrenches wrenches(const Result& r) { return {r.on_a.force, r.on_a.moment, r.on_b.force, r.on_b.moment}; }
  static Wrenches column(const Jacobian& jac, int j) {
    auto part = [&](int block) { return Vec3(jac[3 * block][j], jac[3 * block + 1][j], jac[3 * block + 2][j]); };
    return {part(0), part(1), part(2), part(3)};
  }
  static int position_axis(int component) { return component < 3 ? component : -1; }
  static void perturb(Placement& p, int j, double h) {
    Kinematics& k = j < components ? p.a : p.b;
    const int c = j % components, axis = c % 3;
    if (c < 3) k.position[axis] += h;
    else if (c < 6) k.rotation = ball::rotation_about(h, Vec3::Unit(axis)) * k.rotation;
    else if (c < 9) k.velocity[axis] += h;
    else k.angular_velocity[axis] += h;
  }
  static Placement translated(const Placement& p, const Vec3& d) {
    Placement q = p;
    q.a.position += d;
    q.b.position += d;
    q.point += d;
    return q;
  }
  static Placement rotated(const Placement& p, const FrameRotation& q) {
    const Mat3 m = q.matrix();
    Placement out = p;
    out.a = ball::rotated(p.a, m);
    out.b = ball::rotated(p.b, m);
    out.normal_on_b = m * p.normal_on_b;
    out.point = m * p.point;
    return out;
  }
  static Placement advanced(const Placement& p, double dt) { return ball::advanced(p, dt); }
  /// About the bearing axis, and about an arbitrary axis (which does not rotate the bearing's own
  /// circumferential direction with it: that diagnostic is then not compared).
  static std::vector<FrameRotation> frame_rotations() {
    return {{0.83, Vec3::UnitZ()}, {-2.4, Vec3::UnitZ()}, {1.1, Vec3(1, -2, 0.5)}};
  }
  static std::vector<Vec3> tangents(const Vec3& n) {
    const Vec3 t1 = n.cross(n.unitOrthogonal()).normalized(), t2 = n.cross(t1);
    std::vector<Vec3> out;
    for (const double angle : {0.0, 1.0, 2.5, -2.0}) out.push_back(std::cos(angle) * t1 + std::sin(angle) * t2);
    return out;
  }
  static double speed_bound(const Placement& p) { return ball::speed_bound(p); }
  /// Relative 1e-10 plus a round-off floor far below any physical value (point_diagnostic_fields order).
  static double diagnostic_tolerance(int i, double value, double, double) {
    constexpr std::array<double, point_diagnostics_count> floor = {
        1e-18, 1e-10, 1e-12, 1e-2, 1e-20, 1e-12, 1e-10, 1e-10, 1e-10, 1e-15, 1e-10};
    return 1e-10 * std::abs(value) + floor[static_cast<std::size_t>(i)];
  }
  static std::vector<NanInput<Placement>> nan_inputs() {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    using In = NanInput<Placement>;
    return {{"B.position.x", In::geometry, [](Placement& p) { p.b.position.x() = nan; }},
            {"A.rotation(0,2)", In::geometry, [](Placement& p) { p.a.rotation(0, 2) = nan; }},
            {"A.angular_velocity.y", In::rate, [](Placement& p) { p.a.angular_velocity.y() = nan; }},
            {"B.velocity.z", In::rate, [](Placement& p) { p.b.velocity.z() = nan; }}};
  }
};

/// The spatial kinds: the ball configurations of one segment type.
template <class SegmentType, ball::Kind kind>
struct BallKind : KindOf<SpatialFamily, SegmentType, ball::SpatialCase, &ball::all_cases, kind> {
  using typename BallKind::KindOf::Case, typename BallKind::KindOf::Segment;
  using typename SpatialFamily::Placement, typename SpatialFamily::Motion;
  static Segment make(const Case& c, const Law& law) {
    return std::get<Segment>(ball::make_segment(c, {.damping = law.damping, .traction = law.traction}));
  }
  static std::vector<Motion> motions() { return ball::motions(); }
  /// `shift`: cylindrical pocket only, offset along the pocket axis.
  static Placement placed(const Case& c, const Segment&, double approach, double dir, const Motion& m,
                          double shift = 3e-5) {
    return ball::placed(c, approach, dir, m, shift);
  }
  static double stiffness(const Case& c, const Placement& p) { return ball::expected_stiffness(c, p.contact_angle); }
  static double exponent(const Case& c) { return ball::law_exponent(c); }
  static double stiffness_tolerance(const Case& c) { return ball::stiffness_tolerance(c); }
  static double approach_limit(const Case& c) { return ball::approach_limit(c); }
  static constexpr double damping_factor = ball::damping_factor;
  static constexpr double friction = ball::friction;
  static constexpr double slip_scale = ball::slip_scale;
  static constexpr bool b_orientation_free = kind != ball::Kind::land;  ///< B is a ball (a sphere)
  /// Ball-groove: K depends on the contact angle, so (2/5) K delta^(5/2) is not a potential of the
  /// normal force (it changes by dK/dt too): the elastic power is Q_elastic d(delta)/dt.
  static constexpr bool energy_is_potential = kind != ball::Kind::groove;
  static void stop_approach(const Case& c, Placement& p) { ball::stop_approach(c, p); }
};

/// The roller-end/flange segment: a spatial point contact whose B, the roller, is not round about
/// every axis (its orientation places the end).
struct RollerFlange : SpatialFamily {
  using Segment = RollerFlangeSegment;
  using Case = flange::FlangeCase;
  static std::vector<Case> cases() { return flange::all_cases(); }
  static Segment make(const Case& c, const Law& law) { return flange::make(c, law.damping, law.traction); }
  static std::vector<Motion> motions() { return ball::motions(); }
  static Placement placed(const Case& c, const Segment&, double approach, double dir, const Motion& m,
                          double = 0) {
    return flange::placed(c, approach, dir, m);
  }
  static double stiffness(const Case& c, const Placement&) { return flange::expected_hertz(c).stiffness; }
  static double exponent(const Case&) { return 1.5; }
  static double stiffness_tolerance(const Case&) { return 1e-9; }
  static double approach_limit(const Case&) { return flange::max_approach; }
  static constexpr double damping_factor = ball::damping_factor;
  static constexpr double friction = ball::friction;
  static constexpr double slip_scale = ball::slip_scale;
  static constexpr bool b_orientation_free = false;
  static constexpr bool energy_is_potential = true;
  /// The approach is a difference of coordinates of the rib's size (3 cm) through a sphere centre
  /// 35 mm behind the roller's end: its round-off, some 1e-17 m, is 3e-12 of the force at 5 um.
  static constexpr double jacobian_roundoff = 3e-12;
  static void stop_approach(const Case&, Placement& p) { flange::stop_approach(p); }
};

/// One slice of a roller on a raceway, spatial: B, the roller, is not round about every axis.
struct RollerSlice : SpatialFamily {
  using Segment = RollerSliceSegment;
  using Case = slice::SliceCase;
  static std::vector<Case> cases() { return slice::all_cases(); }
  static Segment make(const Case& c, const Law& law) { return slice::make(c, law.damping, law.traction); }
  static std::vector<Motion> motions() { return ball::motions(); }
  static Placement placed(const Case& c, const Segment&, double approach, double dir, const Motion& m,
                          double = 0) {
    return slice::placed(c, approach, dir, m);
  }
  static double stiffness(const Case&, const Placement&) { return slice::expected_stiffness(); }
  static double exponent(const Case&) { return palmgren_exponent; }
  static double stiffness_tolerance(const Case&) { return 1e-10; }
  static double approach_limit(const Case&) { return slice::max_approach; }
  static constexpr double damping_factor = ball::damping_factor;
  static constexpr double friction = ball::friction;
  static constexpr double slip_scale = ball::slip_scale;
  static constexpr bool b_orientation_free = false;
  static constexpr bool energy_is_potential = true;
  /// The approach is a difference of coordinates of 3-4 cm: its round-off, about 1e-17 m, is 2e-12
  /// of a 5 um approach; a forward difference of the force sees twice that.
  static constexpr double jacobian_roundoff = 5e-12;
  static void stop_approach(const Case&, Placement& p) { flange::stop_approach(p); }
};

// ---- the eight kinds ------------------------------------------------------------------------------

struct RollerRace : RollerKind<RollerRaceSegment, roller::Kind::race> {};
struct CageBar : RollerKind<CageBarSegment, roller::Kind::bar> {};
struct CageLand : RollerKind<CageLandSegment, roller::Kind::land> {};
struct BallGroove : BallKind<BallGrooveSegment, ball::Kind::groove> {};
struct BallPocket : BallKind<BallPocketSegment, ball::Kind::pocket> {};
struct CageLand3 : BallKind<CageLandSegment3, ball::Kind::land> {};

using AllSegmentKinds =
    ::testing::Types<RollerRace, CageBar, CageLand, BallGroove, BallPocket, CageLand3, RollerFlange,
                     RollerSlice>;

/// Names of the typed instances: the kind's name.
struct KindName {
  template <class T>
  static std::string GetName(int) {
    if constexpr (std::is_same_v<T, RollerRace>) return "RollerRace";
    else if constexpr (std::is_same_v<T, CageBar>) return "CageBar";
    else if constexpr (std::is_same_v<T, CageLand>) return "CageLand";
    else if constexpr (std::is_same_v<T, BallGroove>) return "BallGroove";
    else if constexpr (std::is_same_v<T, BallPocket>) return "BallPocket";
    else if constexpr (std::is_same_v<T, CageLand3>) return "CageLand3";
    else if constexpr (std::is_same_v<T, RollerFlange>) return "RollerFlange";
    else return "RollerSlice";
  }
};

// ---- what the checks share ------------------------------------------------------------------------

/// Runs `check(configuration, segment)` for every configuration of a kind, the segment built with
/// `law`; failures name the configuration.
template <class Kind, class Check>
void for_each_configuration(const Law& law, Check check) {
  const auto configurations = Kind::cases();
  ASSERT_FALSE(configurations.empty()) << "a kind without configurations checks nothing";
  for (const auto& c : configurations) {
    SCOPED_TRACE(c.name);
    check(c, Kind::make(c, law));
  }
}

template <class Kind>
typename Kind::Result evaluate_at(const typename Kind::Segment& s, const typename Kind::Placement& p) {
  return evaluate(s, p.a, p.b);
}

template <class Kind>
Power power_on_bodies(const typename Kind::Result& r, const typename Kind::Placement& p) {
  const Wrenches w = Kind::wrenches(r);
  const double t[4] = {w.force_a.dot(Kind::velocity(p.a)), w.moment_a.dot(Kind::angular_velocity(p.a)),
                       w.force_b.dot(Kind::velocity(p.b)), w.moment_b.dot(Kind::angular_velocity(p.b))};
  return {t[0] + t[1] + t[2] + t[3], std::abs(t[0]) + std::abs(t[1]) + std::abs(t[2]) + std::abs(t[3])};
}

/// Moment of both wrenches about the origin: zero when action equals reaction at one point.
template <class Kind>
Vec3 moment_about_origin(const Wrenches& w, const typename Kind::Placement& p) {
  return w.moment_a + w.moment_b + Kind::position(p.a).cross(w.force_a) + Kind::position(p.b).cross(w.force_b);
}

}  // namespace raceway::contact::test
