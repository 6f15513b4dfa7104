// Test support for the roller-end/flange segment (contact/segments/roller_flange_segment.hpp): four
// configurations of an NJ 207-like cylindrical roller bearing (spherical and flat roller ends,
// inner- and outer-ring ribs on either side) and a placement that puts the roller, tilted by 1 mrad,
// where the approach has a chosen value. The geometry each check expects (nearest point of the end,
// normal, contact point, Hertz constants) is stated here: the torus's nearest point by a search over
// its core circle and bisection on the stationarity condition, not by the segment's fixed-point iteration.
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "ball_cases.hpp"
#include "contact/segments/roller_flange_segment.hpp"

namespace raceway::contact::test::flange {

using ball::Placement;
inline constexpr double pitch_radius = 32.5e-3, roller_radius = 5e-3, roller_length = 10e-3;
inline constexpr double max_approach = 1e-4;
inline constexpr double degree = std::numbers::pi / 180.0;

struct FlangeCase {
  std::string name;
  RollerFlangeGeometry geometry;
};

inline std::vector<FlangeCase> all_cases() {
  auto g = [](int side, double axial, double radius, double angle, RollerEndShape end, double end_radius) {
    return RollerFlangeGeometry{side, axial, radius, angle, end, roller_length, roller_radius, end_radius, pitch_radius};
  };
  return {{"inner_rib_spherical_end", g(+1, 5.02e-3, 28e-3, 4 * degree, RollerEndShape::spherical, 40e-3)},
          {"outer_rib_spherical_end", g(-1, -5.02e-3, 37e-3, -4 * degree, RollerEndShape::spherical, 40e-3)},
          {"inner_rib_flat_end", g(-1, -5.01e-3, 28.5e-3, 0.5 * degree, RollerEndShape::flat, 0.5e-3)},
          {"outer_rib_flat_end", g(+1, 5.01e-3, 36.5e-3, -0.5 * degree, RollerEndShape::flat, 0.5e-3)}};
}

/// The test's Hertz constants: curvatures at the nominal contact of an aligned roller.
inline HertzPointContact expected_hertz(const FlangeCase& c) {
  const RollerFlangeGeometry& g = c.geometry;
  const double s = std::sin(g.rib_angle);
  double kx, ky = 1.0 / g.end_radius;
  if (g.end == RollerEndShape::spherical) {
    kx = 1.0 / g.end_radius + s / (g.axis_radius - g.end_radius * s);
  } else {  // the torus where its normal leans by the rib angle: at rho + r_c |s| from the axis
    const double from_axis = g.roller_radius - g.end_radius + g.end_radius * std::abs(s);
    kx = std::abs(s) / from_axis + s / (g.axis_radius - std::copysign(from_axis, s));
  }
  return hertz_point_contact(kx, ky, ball::steel_steel());
}

inline RollerFlangeSegment make(const FlangeCase& c, bool damping, bool traction) {
  PointTraction t;
  t.model = traction ? TractionModel::curve : TractionModel::none;
  t.friction_coefficient = traction ? ball::friction : 0.0;
  t.slip_velocity_scale = ball::slip_scale;
  return make_roller_flange_segment(c.geometry, ball::steel_steel(), damping ? ball::damping_factor : 0.0,
                                    max_approach, t);
}

inline Vec3 face_normal(const RollerFlangeGeometry& g, double azimuth) {
  return -g.side * std::cos(g.rib_angle) * Vec3::UnitZ() + std::sin(g.rib_angle) * ball::radial(azimuth);
}
/// Distance of p from the rib's cone in p's meridian plane (ring frame).
inline double face_distance(const RollerFlangeGeometry& g, const Vec3& p) {
  const double azimuth = std::atan2(p.y(), p.x());
  return face_normal(g, azimuth).dot(p - g.rib_radius * ball::radial(azimuth) - g.rib_axial * Vec3::UnitZ());
}

/// The roller (ring frame, centre at axial 0) tilted by 1 mrad; `dir` its azimuth.
inline Mat3 roller_attitude(double dir) {
  return ball::rotation_about(1e-3, Vec3(std::cos(dir + 0.5), std::sin(dir + 0.5), 0.0)) *
         ball::rotation_about(0.7 + dir, Vec3::UnitZ());
}

/// The end point nearest the face for a roller centred at `centre` with axis `axis`: the sphere's
/// centre, or the torus core-circle point found by sampling and ternary refinement.
inline Vec3 nearest_point(const RollerFlangeGeometry& g, const Vec3& centre, const Vec3& axis) {
  const Vec3 end = centre + g.side * (0.5 * g.roller_length - g.end_radius) * axis;
  if (g.end == RollerEndShape::spherical) return end;
  const Vec3 u = axis.unitOrthogonal(), v = axis.cross(u);
  const double core = g.roller_radius - g.end_radius;
  auto point = [&](double psi) { return Vec3(end + core * (std::cos(psi) * u + std::sin(psi) * v)); };
  constexpr int samples = 3600;
  int best = 0;
  for (int i = 1; i < samples; ++i)
    if (face_distance(g, point(2 * std::numbers::pi * i / samples)) <
        face_distance(g, point(2 * std::numbers::pi * best / samples)))
      best = i;
  // Refine by bisection on the stationarity condition n(K) . dK/dpsi = 0 (a root is resolved to
  // round-off in psi, where the distance's flat minimum is not).
  auto slope = [&](double psi) {
    const Vec3 k = point(psi);
    return face_normal(g, std::atan2(k.y(), k.x())).dot(core * (-std::sin(psi) * u + std::cos(psi) * v));
  };
  double lo = 2 * std::numbers::pi * (best - 1) / samples, hi = 2 * std::numbers::pi * (best + 1) / samples;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (slope(mid) < 0) lo = mid;
    else hi = mid;
  }
  return point(0.5 * (lo + hi));
}

inline Placement place(const FlangeCase& c, double approach, double dir) {
  const RollerFlangeGeometry& g = c.geometry;
  Placement p;
  p.a.position = Vec3(2e-4, -1e-4, 5e-5);
  p.a.rotation = ball::rotation_about(0.004, Vec3(1, 2, 0)) * ball::rotation_about(1.3, Vec3::UnitZ());
  const Mat3 attitude = roller_attitude(dir);
  const Vec3 axis = attitude.col(2);
  Vec3 centre = g.axis_radius * ball::radial(dir);
  // Moving the roller axially moves C along z, where the face normal's component is -side cos(g):
  // the distance changes by -side cos(g) dz. Solve for the wanted distance end_radius - approach.
  const Vec3 c0 = nearest_point(g, centre, axis);
  const double dz = (face_distance(g, c0) - (g.end_radius - approach)) / (g.side * std::cos(g.rib_angle));
  centre.z() += dz;
  const Vec3 c1 = c0 + dz * Vec3::UnitZ();
  const Vec3 n = face_normal(g, std::atan2(c1.y(), c1.x()));
  p.b.position = p.a.position + p.a.rotation * centre;
  p.b.rotation = p.a.rotation * attitude;
  p.normal_on_b = p.a.rotation * n;
  p.point = p.a.position + p.a.rotation * (c1 - (g.end_radius - approach) * n);
  return p;
}

inline Placement placed(const FlangeCase& c, double approach, double dir, const ball::Motion& m) {
  Placement p = place(c, approach, dir);
  ball::set_motion(p, m);
  return p;
}

inline void stop_approach(Placement& p) {
  const Vec3 n = p.normal_on_b;
  const Vec3 va = p.a.velocity + p.a.angular_velocity.cross(p.point - p.a.position);
  const Vec3 vb = p.b.velocity + p.b.angular_velocity.cross(p.point - p.b.position);
  p.b.velocity += -n.dot(vb - va) * n;
}

}  // namespace raceway::contact::test::flange
