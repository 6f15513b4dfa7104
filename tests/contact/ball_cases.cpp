#include "ball_cases.hpp"

#include <cmath>
#include <stdexcept>

namespace raceway::contact::test::ball {

double bearing::steel_steel() { return reduced_modulus(208e9, 0.3, 208e9, 0.3); }
double bearing::steel_brass() { return reduced_modulus(208e9, 0.3, 100e9, 0.34); }

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

Groove groove_of(const SpatialCase& c) {
  const double g = c.outer ? outer_groove_radius : inner_groove_radius;
  const double m = g - ball_radius;
  const double cos_a = c.arc == 0 ? 1.0 : std::cos(arc_angle);
  const double e = c.arc == 0 ? 0.0 : c.arc * m * std::sin(arc_angle);  // scene.hpp's offset
  return {c.outer ? pitch_radius - m * cos_a : pitch_radius + m * cos_a, e, g, c.outer};
}
double design_angle(const SpatialCase& c) { return -c.arc * arc_angle; }

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

AnySegment make_segment(const SpatialCase& c, const LawOptions& o) {
  const double damping = o.damping ? damping_factor : 0.0;
  const TractionCurve curve{o.traction ? friction : 0.0, slip_scale};
  switch (c.kind) {
    case Kind::groove: {
      const Groove g = groove_of(c);
      const HertzTable hertz(
          [g](double cos_angle, double& kx, double& ky) { groove_curvatures(g, cos_angle, kx, ky); },
          0.3, 1.0, 29, steel_steel());
      return BallGrooveSegment{
          .centre_radius = g.centre_radius, .centre_axial = g.centre_axial, .groove_radius = g.groove_radius,
          .ball_radius = ball_radius, .outer = g.outer,
          .normal = {hertz, steel_steel(), damping, max_approach},
          .traction = {.model = o.traction ? TractionModel::curve : TractionModel::none,
                       .friction_coefficient = friction, .slip_velocity_scale = slip_scale},
          .lubricant = o.traction ? PointLubricant{viscosity, pressure_viscosity, limiting_shear} : PointLubricant{},
          .rolling_resistance = o.traction, .groove_side = 0, .imperfections = nullptr,
          .element_imperfections = nullptr};
    }
    case Kind::pocket:
      return BallPocketSegment{
          .pitch_radius = pitch_radius, .pocket_angle = pocket_angle, .clearance = pocket_clearance,
          .ball_radius = ball_radius, .shape = c.shape,
          .normal = {HertzTable(pocket_hertz(c.shape)), steel_brass(), damping, pocket_max_approach},
          .friction = curve,
          .film = std::nullopt};
    case Kind::land:
      return CageLandSegment3{
          .land_radius = c.outer ? outer_land_radius : inner_land_radius, .clearance = land_clearance,
          .width = land_width, .axial_offset = land_axial_offset, .stations = land_stations,
          .outer_land = c.outer,
          .law = make_line_contact_law(steel_brass(), land_width / land_stations, 1, 0.0, damping,
                                       land_max_approach),
          .friction = curve, .film = std::nullopt};
  }
  throw std::logic_error("unknown segment kind");
}

SpatialSegmentResult evaluate_any(const AnySegment& s, const SpatialKinematics& a,
                                  const SpatialKinematics& b) {
  return std::visit([&](const auto& seg) { return evaluate(seg, a, b); }, s);
}

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
double stiffness_tolerance(const SpatialCase& c) { return c.kind == Kind::groove ? 2e-4 : 1e-10; }

double approach_limit(const SpatialCase& c) {
  return c.kind == Kind::groove ? max_approach : c.kind == Kind::pocket ? pocket_max_approach : land_max_approach;
}

Mat3 rotation_about(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

double contact_angle_for(const SpatialCase& c, double dir) {
  return c.arc == 0 ? 0.25 * std::sin(2 * dir + 0.4) : design_angle(c) + 0.05 * std::sin(dir);
}

Placement place(const SpatialCase& c, double approach, double dir, double shift) {
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
double speed_bound(const Placement& p) {
  const Vec3 v_rel = p.b.velocity - p.a.velocity - p.a.angular_velocity.cross(p.b.position - p.a.position);
  return v_rel.norm() + 0.1 * (p.b.angular_velocity - p.a.angular_velocity).norm();
}

Placement placed(const SpatialCase& c, double approach, double dir, const Motion& m, double shift) {
  Placement p = place(c, approach, dir, shift);
  set_motion(p, m);
  return p;
}

double wrench_norm(const SpatialSegmentResult& r) {
  return r.on_a.force.norm() + r.on_a.moment.norm() + r.on_b.force.norm() + r.on_b.moment.norm();
}

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

Placement advanced(const Placement& p, double dt) {
  Placement q = p;
  for (SpatialKinematics* k : {&q.a, &q.b}) {
    k->position += dt * k->velocity;
    const double w = k->angular_velocity.norm();
    if (w > 0) k->rotation = rotation_about(w * dt, k->angular_velocity) * k->rotation;
  }
  return q;
}

}  // namespace raceway::contact::test::ball
