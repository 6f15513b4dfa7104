#include "contact/segments/roller_flange_segment.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "contact/laws/damping.hpp"

namespace raceway::contact {

namespace {

Vec3 radial_of(double azimuth) { return {std::cos(azimuth), std::sin(azimuth), 0.0}; }

// The face's unit normal (rib to roller) in the meridian plane of azimuth `azimuth`, ring frame.
Vec3 face_normal(const RollerFlangeGeometry& g, double azimuth) {
  return -g.side * std::cos(g.rib_angle) * Vec3::UnitZ() + std::sin(g.rib_angle) * radial_of(azimuth);
}

double azimuth_of(const Vec3& p) { return std::atan2(p.y(), p.x()); }

// Signed distance of p from the face (> 0 on the roller's side), ring frame: exact for a cone.
double face_distance(const RollerFlangeGeometry& g, const Vec3& p, double azimuth) {
  const Vec3 face_point = g.rib_radius * radial_of(azimuth) + g.rib_axial * Vec3::UnitZ();
  return face_normal(g, azimuth).dot(p - face_point);
}


// The point C of the roller's end nearest the face, in the ring frame; false if there is none.
bool nearest_end_point(const RollerFlangeGeometry& g, const Vec3& centre, const Vec3& axis, Vec3& c) {
  const Vec3 end = centre + g.side * (0.5 * g.roller_length - g.end_radius) * axis;
  c = end;
  if (g.end == RollerEndShape::spherical) return true;
  // The core circle end + core (cos(psi) u0 + sin(psi) v0); the nearest point is where
  // dD/dpsi = core n(K) . (-sin(psi) u0 + cos(psi) v0) vanishes. Start from the point the face normal
  // at the end's azimuth picks, then secant steps on that slope (the plain fixed point contracts
  // only by core / rib radius per step).
  const double core = g.roller_radius - g.end_radius;
  const Vec3 u0 = axis.unitOrthogonal(), v0 = axis.cross(u0);
  auto point = [&](double psi) { return Vec3(end + core * (std::cos(psi) * u0 + std::sin(psi) * v0)); };
  auto slope = [&](double psi) {
    return face_normal(g, azimuth_of(point(psi))).dot(-std::sin(psi) * u0 + std::cos(psi) * v0);
  };
  auto picked = [&](const Vec3& at, double& psi) {
    const Vec3 n = face_normal(g, azimuth_of(at));
    const Vec3 perp = n - n.dot(axis) * axis;
    if (!(perp.norm() > 1e-12)) return false;  // the face normal along the axis: a whole edge touches
    psi = std::atan2(-perp.dot(v0), -perp.dot(u0));
    return true;
  };
  double psi0 = 0, psi1 = 0;
  if (!picked(end, psi0) || !picked(point(psi0), psi1)) return false;
  double s0 = slope(psi0), s1 = slope(psi1);
  for (int step = 0; step < 30 && s1 != s0 && psi1 != psi0; ++step) {
    const double next = psi1 - s1 * (psi1 - psi0) / (s1 - s0);
    psi0 = psi1;
    s0 = s1;
    psi1 = next;
    s1 = slope(psi1);
    if (std::abs(psi1 - psi0) < 1e-15) break;
  }
  c = point(psi1);
  return true;
}

// A flat end on a roller whose axis leans by beta (its `side` end outwards): in the roller's own
// meridian frame (its axis a, e_r' = cos(beta) e_r - sin(beta) e_z) the face normal is
// -cos(g') a + sin(g') e_r' with g' = g + beta, the cylindrical case's form; the torus point lies
// at core + r_c |sin g'| from the roller's axis, the cone's curvature is taken at its distance from
// the ring axis.
FlangeCurvatures leaning_flat_end_curvatures(const RollerFlangeGeometry& g) {
  if (!(g.end_radius < g.roller_radius)) throw std::invalid_argument("roller flange: corner radius above roller radius");
  const double beta = g.axis_angle, gp = g.rib_angle + beta, sp = std::sin(gp);
  if (sp == 0) throw std::invalid_argument("roller flange: a flat roller end needs a rib angle to its end face");
  const double core = g.roller_radius - g.end_radius;
  FlangeCurvatures k;
  const double from_axis = core + g.end_radius * std::abs(sp);
  k.contact_radius = g.axis_radius + (-(sp > 0 ? 1.0 : -1.0) * core - g.end_radius * sp) * std::cos(beta) +
                     g.end_radius * std::cos(gp) * std::sin(beta);
  k.kx = std::abs(sp) / from_axis + std::sin(g.rib_angle) / k.contact_radius;
  k.ky = 1.0 / g.end_radius;
  return k;
}

}  // namespace

FlangeCurvatures flange_curvatures(const RollerFlangeGeometry& g) {
  if (!(g.roller_length > 0) || !(g.roller_radius > 0) || !(g.end_radius > 0) || !(g.axis_radius > 0) ||
      !(g.rib_radius > 0) || (g.side != 1 && g.side != -1) || !(std::abs(g.rib_angle) < std::numbers::pi / 4))
    throw std::invalid_argument("roller flange: lengths and radii must be positive, side +-1, |rib angle| < 45 deg");
  const double s = std::sin(g.rib_angle);
  FlangeCurvatures k;
  if (g.end == RollerEndShape::spherical) {
    // The sphere's nearest point lies at R sin(g) from the axis, inwards for g > 0.
    k.contact_radius = g.axis_radius - g.end_radius * s;
    k.kx = 1.0 / g.end_radius + s / k.contact_radius;
    k.ky = 1.0 / g.end_radius;
  } else if (g.axis_angle == 0) {
    if (!(g.end_radius < g.roller_radius)) throw std::invalid_argument("roller flange: corner radius above roller radius");
    if (s == 0) throw std::invalid_argument("roller flange: a flat roller end needs a rib angle");
    const double from_axis = g.roller_radius - g.end_radius + g.end_radius * std::abs(s);
    k.contact_radius = g.axis_radius - (s > 0 ? 1.0 : -1.0) * from_axis;
    k.kx = std::abs(s) / from_axis + s / k.contact_radius;
    k.ky = 1.0 / g.end_radius;
  } else {
    k = leaning_flat_end_curvatures(g);
  }
  if (!(k.contact_radius > 0) || !(k.kx > 0))
    throw std::invalid_argument("roller flange: the rib is concave beyond the end's curvature (no Hertz point)");
  return k;
}

std::string flange_problem(const RollerFlangeGeometry& g) {
  try {
    (void)flange_curvatures(g);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

RollerFlangeGeometry tapered_back_rib(const TaperedGeometry& t, double pitch_radius, double length,
                                      RollerEndShape end, double end_radius, double rib_angle) {
  const double beta = t.axis_angle;
  const Vec3 axis(std::sin(beta), 0.0, std::cos(beta));
  const Vec3 centre(pitch_radius, 0.0, 0.0);
  const Vec3 face = centre + 0.5 * length * axis;
  RollerFlangeGeometry g;
  g.side = +1;
  g.rib_radius = face.x();
  g.rib_axial = face.z();
  g.rib_angle = rib_angle - beta;  // from the ring's radial plane
  g.end = end;
  g.roller_length = length;
  g.roller_radius = t.roller_radius_at(0.5 * length);
  g.end_radius = end_radius;
  g.axis_radius = (centre + (0.5 * length - end_radius) * axis).x();  // the sphere's or edge torus's centre
  g.axis_angle = beta;
  return g;
}

RollerFlangeSegment make_roller_flange_segment(const RollerFlangeGeometry& g, double reduced_modulus,
                                               double damping_factor, double max_approach,
                                               const PointTraction& traction) {
  const FlangeCurvatures k = flange_curvatures(g);
  RollerFlangeSegment s;
  s.geometry = g;
  s.hertz = hertz_point_contact(k.kx, k.ky, reduced_modulus);
  s.damping_factor = damping_factor;
  s.max_approach = max_approach;
  s.traction = traction;
  return s;
}

SpatialSegmentResult evaluate(const RollerFlangeSegment& s, const SpatialKinematics& ring,
                              const SpatialKinematics& roller) {
  SpatialSegmentResult out;
  if (!ring.all_finite() || !roller.all_finite()) {
    out.valid = false;
    return out;
  }
  const RollerFlangeGeometry& g = s.geometry;
  const Mat3& to_world = ring.rotation;
  const Vec3 centre = to_world.transpose() * (roller.position - ring.position);
  const Vec3 axis = to_world.transpose() * roller.rotation.col(2);
  Vec3 c;
  if (!nearest_end_point(g, centre, axis, c)) {
    out.valid = false;
    return out;
  }
  const double azimuth = azimuth_of(c);
  const double distance = face_distance(g, c, azimuth);
  const double approach = g.end_radius - distance;
  out.diagnostics.approach = approach;
  if (!(approach > 0)) return out;
  if (approach > s.max_approach) out.valid = false;

  const Vec3 n = to_world * face_normal(g, azimuth);
  const Vec3 point = ring.position + to_world * (c - distance * face_normal(g, azimuth));
  const Vec3 v_ring = ring.velocity + ring.angular_velocity.cross(point - ring.position);
  const Vec3 v_roller = roller.velocity + roller.angular_velocity.cross(point - roller.position);
  const Vec3 sliding = v_roller - v_ring;
  const double approach_rate = -n.dot(sliding);

  const double elastic = s.hertz.stiffness * approach * std::sqrt(approach);
  const DampedForce q = hunt_crossley(elastic, s.damping_factor, approach_rate);

  // Contact frame: x circumferential at the contact, z into the ring, y = z x x.
  const Vec3 x = to_world * Vec3(-std::sin(azimuth), std::cos(azimuth), 0.0);
  const Vec3 z = -n, y = z.cross(x);
  const double cube_root = std::cbrt(q.force);
  const double a = s.hertz.a_coefficient * cube_root, b = s.hertz.b_coefficient * cube_root;
  const ContactSliding slide{sliding.dot(x), sliding.dot(y), (roller.angular_velocity - ring.angular_velocity).dot(z)};
  const TractionResult t = q.force > 0 ? integrate_traction(s.traction, PointLubricant{}, q.force,
                                                            s.hertz.a_along_x ? a : b, s.hertz.a_along_x ? b : a,
                                                            0.0, slide)
                                       : TractionResult{};
  const Vec3 force = q.force * n + t.force_x * x + t.force_y * y;
  const Vec3 couple = t.spin_moment * z;
  out.on_b.force = force;
  out.on_b.moment = (point - roller.position).cross(force) + couple;
  out.on_a.force = -force;
  out.on_a.moment = (point - ring.position).cross(-force) - couple;

  PointDiagnostics& d = out.diagnostics;
  d.normal_force = q.force;
  d.max_pressure = q.force > 0 ? 3.0 * q.force / (2.0 * std::numbers::pi * a * b) : 0.0;
  d.slip_velocity = std::hypot(slide.slide_x, slide.slide_y);
  d.spin_velocity = slide.spin;
  d.traction_force = std::hypot(t.force_x, t.force_y);
  const Vec3 e_r(roller.position.x(), roller.position.y(), 0.0);
  const double r = e_r.norm();
  d.circumferential_force = r > 0 ? force.dot(Vec3::UnitZ().cross(e_r / r)) : 0.0;
  d.elastic_energy = 0.4 * elastic * approach;
  d.power_loss = t.power_loss + q.damping_power;
  return out;
}

}  // namespace raceway::contact
