#include "contact/segments/ball_segments.hpp"

#include "contact/segments/land_film.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>

#include "contact/laws/damping.hpp"
#include "contact/laws/element_imperfections.hpp"

namespace raceway::contact {
namespace {

const Vec3 unit_z = Vec3::UnitZ();
constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

/// Length of (x, y). Contact coordinates are far from overflow, so no std::hypot (several times
/// slower) in the hot path.
inline double length(double x, double y) { return std::sqrt(x * x + y * y); }

/// Velocity of the material point of body k at the spatial point c.
inline Vec3 point_velocity(const SpatialKinematics& k, const Vec3& c) {
  return k.velocity + k.angular_velocity.cross(c - k.position);
}

/// Puts the force `f_b` on B at the contact point `point` and the couple `couple_b` on B, and their
/// opposites on A at the same point: action = reaction and zero total moment about any point.
inline void apply_at_point(const SpatialKinematics& a, const SpatialKinematics& b, const Vec3& point,
                           const Vec3& f_b, const Vec3& couple_b, SpatialSegmentResult& r) {
  r.on_b.force += f_b;
  r.on_b.moment += (point - b.position).cross(f_b) + couple_b;
  r.on_a.force -= f_b;
  r.on_a.moment -= (point - a.position).cross(f_b) + couple_b;
}

/// Component of the force on B along the bearing's circumferential direction at B's centre
/// (e_theta = e_z x e_r); 0 when B's centre lies on the bearing axis.
inline double circumferential(const Vec3& b_position, const Vec3& f_b) {
  const double r = length(b_position.x(), b_position.y());
  if (!(r > 0)) return 0.0;
  return (-b_position.y() * f_b.x() + b_position.x() * f_b.y()) / r;
}

/// Hertz point contact with Hunt-Crossley damping: Q = K delta^1.5 (1 + c d(delta)/dt), clipped at
/// zero (damping.hpp); elastic energy (2/5) K delta^2.5.
struct HertzNormal {
  double force = 0, elastic_energy = 0, damping_power = 0;
};
inline HertzNormal hertz_hunt_crossley(double stiffness, double damping_factor, double approach,
                                       double approach_rate) {
  const double elastic = stiffness * approach * std::sqrt(approach);
  const DampedForce damped = hunt_crossley(elastic, damping_factor, approach_rate);
  HertzNormal h;
  h.force = damped.force;
  h.elastic_energy = 0.4 * elastic * approach;
  h.damping_power = damped.damping_power;
  return h;
}

/// Slope of a regularised Coulomb curve through zero: mu(s) / s, finite at s = 0 (no 0/0).
inline double friction_per_speed(const TractionCurve& curve, double speed) {
  if (curve.friction_coefficient == 0) return 0.0;
  if (speed > 0) return curve.coefficient(speed) / speed;
  return curve.friction_coefficient / curve.slip_velocity_scale;
}

/// A result that failed: no force, flagged recoverable.
inline SpatialSegmentResult invalid_result(double approach) {
  SpatialSegmentResult r;
  r.diagnostics.approach = approach;
  r.valid = false;
  return r;
}

/// Never hand garbage on: a non-finite wrench or diagnostic (NaN or infinity in the input) turns
/// the result into an invalid one without force.
inline void check_finite(SpatialSegmentResult& r) {
  const PointDiagnostics& d = r.diagnostics;
  const double sum = r.on_a.force.sum() + r.on_a.moment.sum() + r.on_b.force.sum() +
                     r.on_b.moment.sum() + d.approach + d.normal_force + d.contact_angle +
                     d.max_pressure + d.film_thickness + d.slip_velocity + d.spin_velocity +
                     d.traction_force + d.circumferential_force + d.elastic_energy + d.power_loss;
  if (!std::isfinite(sum)) r = invalid_result(d.approach);
}

/// What a ball's point contact (groove, pocket) hands on once its laws are evaluated: the force
/// and couple on the ball at the contact point, and the diagnostics that differ between the two.
struct BallContact {
  Vec3 point, force_on_ball, couple_on_ball;
  double normal_force, max_pressure, film_thickness, slip_velocity, spin_velocity, traction_force,
      elastic_energy, power_loss;
};

/// The common tail of the ball's point contacts: puts the wrench on both bodies and fills the
/// diagnostics (the caller has set approach, contact angle and validity).
inline void finish_ball_contact(const SpatialKinematics& a, const SpatialKinematics& ball,
                                const BallContact& c, SpatialSegmentResult& r) {
  apply_at_point(a, ball, c.point, c.force_on_ball, c.couple_on_ball, r);
  PointDiagnostics& d = r.diagnostics;
  d.normal_force = c.normal_force;
  d.max_pressure = c.max_pressure;
  d.film_thickness = c.film_thickness;
  d.slip_velocity = c.slip_velocity;
  d.spin_velocity = c.spin_velocity;
  d.traction_force = c.traction_force;
  d.circumferential_force = circumferential(ball.position, c.force_on_ball);
  d.elastic_energy = c.elastic_energy;
  d.power_loss = c.power_loss;
  check_finite(r);
}

}  // namespace

namespace {

/// A ball-groove contact up to its traction: geometry, normal force, film and sliding. `done`: the
/// result is complete (apart, outside the groove, or invalid input) and has no traction.
struct GrooveContact {
  SpatialSegmentResult r;
  bool done = true;
  Vec3 n, ex, ey, point, w_rel;
  HertzNormal normal;
  double q = 0, rx = 0, ry = 0, entrainment = 0, a = 0, b = 0, ax = 0, ay = 0;
  FilmThickness film;
  ContactSliding sliding;
};

GrooveContact groove_contact(const BallGrooveSegment& s, const SpatialKinematics& ring, const SpatialKinematics& ball) {
  GrooveContact g;
  SpatialSegmentResult& r = g.r;
  const Mat3& rot = ring.rotation;
  const Vec3 rel = ball.position - ring.position;
  const Vec3 p = rot.transpose() * rel;  // ball centre, ring frame
  const double rho_ball = length(p.x(), p.y());
  if (!(rho_ball > 0) || !std::isfinite(rho_ball) || !std::isfinite(p.z())) {
    r = invalid_result(not_a_number);
    return g;
  }
  const Vec3 e_r(p.x() / rho_ball, p.y() / rho_ball, 0.0);  // ring frame, at the ball's azimuth
  const Vec3 e_t(-e_r.y(), e_r.x(), 0.0);
  // d = ball centre - arc centre, in the (e_r, e_z) plane of the ball's azimuth.
  const double d_rad = rho_ball - s.centre_radius;
  const double d_ax = p.z() - s.centre_axial;
  const double len = length(d_rad, d_ax);
  // The race's imperfections (a spall, waviness) move its surface along the normal by a height at
  // the contact's azimuth (contact/laws/race_imperfections.hpp); a perfect race adds nothing.
  RaceHeight surface;
  if (s.imperfections) {
    const double contact_axial = len > 0 ? s.centre_axial + s.groove_radius * d_ax / len : 0.0;
    surface = race_height(*s.imperfections, std::atan2(p.y(), p.x()) - ring.spin_angle, contact_axial);
  }
  double approach = s.imperfections ? len - (s.groove_radius - s.ball_radius) + surface.height
                                    : len - (s.groove_radius - s.ball_radius);
  // The ball's own imperfections (element_imperfections.hpp) at the contact's place on the ball.
  ElementHeight ball_surface;
  if (s.element_imperfections && len > 0) {
    const GrooveContactFrame frame = groove_contact_frame(s, ring, ball);
    ball_surface = element_height(*s.element_imperfections, ball.rotation, frame.n, frame.rate, ball.angular_velocity);
    approach += ball_surface.height;
  }
  r.diagnostics.approach = approach;
  if (!std::isfinite(approach)) {
    r = invalid_result(approach);
    return g;
  }
  if (len > 0) r.diagnostics.contact_angle = std::atan2(d_ax, std::abs(d_rad));
  if (approach <= 0 || s.groove_side * d_ax < 0) return g;
  g.done = false;

  // Geometry of the contact: normal n from the ball centre into the ring (body 1), the contact point
  // on the groove, and the contact frame (x rolling = e_theta, y = n x x, z = n).
  const double n_rad = d_rad / len, n_ax = d_ax / len;
  const Vec3 n_ring = n_rad * e_r + n_ax * unit_z;
  const Vec3 point_ring = s.centre_radius * e_r + s.centre_axial * unit_z + s.groove_radius * n_ring;
  g.n = rot * n_ring;
  g.ex = rot * e_t;
  g.ey = g.n.cross(g.ex);
  g.point = ring.position + rot * point_ring;
  const Vec3 v_rel = point_velocity(ball, g.point) - point_velocity(ring, g.point);
  double approach_rate = g.n.dot(v_rel);  // exact d(approach)/dt
  if (s.imperfections) {  // and the surface's height passing under the contact
    const Vec3 rel_dot = rot.transpose() * (ball.velocity - ring.velocity - ring.angular_velocity.cross(rel));
    approach_rate += surface.per_azimuth * rel_dot.dot(e_t) / rho_ball;
  }
  if (s.element_imperfections) approach_rate += ball_surface.rate;

  // Hertz at s = cos(contact angle); relative curvatures for the film.
  const double cos_angle = std::abs(n_rad);
  const HertzPointContact hertz = s.normal.hertz.at(cos_angle);
  g.normal = hertz_hunt_crossley(hertz.stiffness, s.normal.damping_factor, approach, approach_rate);
  r.valid = approach <= s.normal.max_approach;
  g.q = g.normal.force;
  const double rho_contact = s.centre_radius + s.groove_radius * n_rad;  // from the ring axis
  const double kx = 1.0 / s.ball_radius + (s.outer ? -cos_angle : cos_angle) / rho_contact;
  const double ky = 1.0 / s.ball_radius - 1.0 / s.groove_radius;
  g.rx = 1.0 / kx, g.ry = 1.0 / ky;

  // Entrainment: surface speeds along x relative to the contact point, which moves with the ring
  // plus a rotation about the ring axis at the ball centre's azimuth rate in the ring frame.
  const Vec3 p_dot = rot.transpose() * (ball.velocity - ring.velocity - ring.angular_velocity.cross(rel));
  const double azimuth_rate = p_dot.dot(e_t) / rho_ball;
  const double u_ring = -azimuth_rate * rho_contact;
  const double slide_x = v_rel.dot(g.ex), slide_y = v_rel.dot(g.ey);
  const double u_ball = u_ring + slide_x;
  g.entrainment = 0.5 * std::abs(u_ring + u_ball);

  // The contact reads the central film alone (its minimum film is no diagnostic of it).
  if (s.lubricant.inlet_meniscus > 0)
    g.film = hamrock_dowson_film(g.entrainment, g.q, g.rx, g.ry, s.normal.reduced_modulus, s.lubricant);
  else
    g.film.central = hamrock_dowson_central_film(g.entrainment, g.q, g.rx, g.ry, s.normal.reduced_modulus, s.lubricant);
  const double cbrt_q = std::cbrt(g.q);
  g.a = hertz.a_coefficient * cbrt_q, g.b = hertz.b_coefficient * cbrt_q;
  g.ax = hertz.a_along_x ? g.a : g.b, g.ay = hertz.a_along_x ? g.b : g.a;
  if (s.lubricant.inlet_meniscus > 0) g.film = starved_film(g.film, g.rx, g.ax, s.lubricant.inlet_meniscus);
  g.w_rel = ball.angular_velocity - ring.angular_velocity;
  g.sliding = ContactSliding{slide_x, slide_y, g.w_rel.dot(g.n)};
  return g;
}

/// The contact up to its traction: the geometry and laws of groove_contact and the EHL rolling
/// resistance, which does not depend on the traction.
PreparedGrooveContact prepare(const BallGrooveSegment& s, const GrooveContact& g, const SpatialKinematics& ring,
                              const SpatialKinematics& ball) {
  PreparedGrooveContact p;
  p.in_contact = !g.done;
  p.valid = g.r.valid;
  p.approach = g.r.diagnostics.approach;
  p.contact_angle = g.r.diagnostics.contact_angle;
  if (g.done) return p;
  const double q = g.q;
  p.n = g.n, p.ex = g.ex, p.ey = g.ey, p.point = g.point;
  p.ring_position = ring.position, p.ball_position = ball.position;
  p.normal_force = q;
  p.max_pressure = q > 0 ? 1.5 * q / (std::numbers::pi * g.a * g.b) : 0.0;
  p.film_thickness = g.film.central;
  p.slip_velocity = length(g.sliding.slide_x, g.sliding.slide_y);
  p.spin_velocity = g.sliding.spin;
  p.elastic_energy = g.normal.elastic_energy;
  p.damping_power = g.normal.damping_power;
  // EHL rolling resistance as a pair of couples about y opposing the relative rolling rotation
  // (equivalent to shifting the pressure centre towards the inlet by F_R Rx / Q): it conserves force
  // and angular momentum and dissipates F_R Rx |Omega| (= F_R u_e in pure rolling). F_R is bounded
  // by Q (1/F = 1/F_R + 1/Q, a change of order F_R/Q ~ 1e-4 under load): Houpert's F_R ~ Q^0.47
  // alone would have an unbounded slope at contact onset.
  if (s.rolling_resistance && g.film.central > 0) {
    const double houpert =
        ehl_rolling_resistance(g.entrainment, q, g.rx, g.ry, s.normal.reduced_modulus, s.lubricant);
    // Handed over with the traction as the film vanishes (Houpert's F_R ~ u^0.66 has an unbounded
    // slope at zero entrainment; film_weight ~ h^2 ~ u^1.34 there makes the couple C1).
    const double f_r = houpert > 0 ? film_weight(g.film.central, s.lubricant) * houpert * q / (houpert + q) : 0.0;
    const double rolling_rate = g.w_rel.dot(g.ey);
    const double scale = s.traction.slip_velocity_scale > 0 ? s.traction.slip_velocity_scale : 1.0;
    p.rolling = true;
    p.rolling_moment = -f_r * g.rx * std::tanh(rolling_rate * g.rx / scale);
    p.rolling_loss = -p.rolling_moment * rolling_rate;
  }
  return p;
}

/// The fields of a prepared contact in their fixed order, for write() and read().
template <class Prepared, class Visit>
void visit_prepared(Prepared& p, Visit&& visit) {
  for (auto* v : {&p.n, &p.ex, &p.ey, &p.point, &p.ring_position, &p.ball_position})
    for (int i = 0; i < 3; ++i) visit((*v)[i]);
  for (auto* x : {&p.approach, &p.contact_angle, &p.normal_force, &p.max_pressure, &p.film_thickness, &p.slip_velocity,
                  &p.spin_velocity, &p.elastic_energy, &p.damping_power, &p.rolling_moment, &p.rolling_loss})
    visit(*x);
}

}  // namespace

void PreparedGrooveContact::write(double* out) const {
  int i = 0;
  visit_prepared(*this, [&](double x) { out[i++] = x; });
  out[i++] = in_contact ? 1.0 : 0.0;
  out[i++] = valid ? 1.0 : 0.0;
  out[i++] = rolling ? 1.0 : 0.0;
}

PreparedGrooveContact PreparedGrooveContact::read(const double* in) {
  PreparedGrooveContact p;
  int i = 0;
  visit_prepared(p, [&](double& x) { x = in[i++]; });
  p.in_contact = in[i++] != 0.0;
  p.valid = in[i++] != 0.0;
  p.rolling = in[i++] != 0.0;
  return p;
}

SpatialSegmentResult finish_groove_contact(const PreparedGrooveContact& p, const TractionResult& traction_sum) {
  SpatialSegmentResult r;
  r.diagnostics.approach = p.approach;
  r.diagnostics.contact_angle = p.contact_angle;
  r.valid = p.valid;
  if (!p.in_contact) return r;
  const TractionResult traction = p.normal_force > 0 ? traction_sum : TractionResult{};
  Vec3 couple = traction.spin_moment * p.n;
  if (p.rolling) couple += p.rolling_moment * p.ey;
  const Vec3 tangential = traction.force_x * p.ex + traction.force_y * p.ey;
  const Vec3 f_ball = -p.normal_force * p.n + tangential;
  // finish_ball_contact reads the bodies' positions only.
  SpatialKinematics ring, ball;
  ring.position = p.ring_position;
  ball.position = p.ball_position;
  finish_ball_contact(ring, ball,
                      {.point = p.point, .force_on_ball = f_ball, .couple_on_ball = couple,
                       .normal_force = p.normal_force, .max_pressure = p.max_pressure,
                       .film_thickness = p.film_thickness, .slip_velocity = p.slip_velocity,
                       .spin_velocity = p.spin_velocity,
                       .traction_force = length(traction.force_x, traction.force_y),
                       .elastic_energy = p.elastic_energy,
                       .power_loss = traction.power_loss + p.damping_power + p.rolling_loss},
                      r);
  return r;
}

SpatialSegmentResult evaluate(const BallGrooveSegment& s, const SpatialKinematics& ring,
                              const SpatialKinematics& ball) {
  const GrooveContact g = groove_contact(s, ring, ball);
  if (g.done) return g.r;
  const TractionResult traction =
      g.q > 0 ? integrate_traction(s.traction, s.lubricant, g.q, g.ax, g.ay, g.film.central, g.sliding)
              : TractionResult{};
  return finish_groove_contact(prepare(s, g, ring, ball), traction);
}

int traction_block_count(const BallGrooveSegment& s) { return traction_block_count(s.traction); }

TractionResult evaluate_traction_block(const BallGrooveSegment& s, const SpatialKinematics& ring,
                                       const SpatialKinematics& ball, int block, PreparedGrooveContact* prepared) {
  const GrooveContact g = groove_contact(s, ring, ball);
  if (prepared) *prepared = prepare(s, g, ring, ball);
  if (g.done || !(g.q > 0)) return {};
  return integrate_traction_block(s.traction, s.lubricant, g.q, g.ax, g.ay, g.film.central, g.sliding, block);
}

namespace {
/// The pocket's film (pocket_film.hpp) on the ball (B) and the cage (A), both at the ball's centre.
/// `axis`: the pocket's axis, `d`: the ball centre off the axis, both in the cage frame.
void add_pocket_film(const BallPocketSegment& s, const SpatialKinematics& cage, const SpatialKinematics& ball,
                     const Vec3& axis, const Vec3& d, SpatialSegmentResult& r) {
  const Mat3& rot = cage.rotation;
  // The pocket frame (e1, e2, a): e1 the cage's axis, e2 = a x e1, in the cage frame.
  const Vec3 e1 = unit_z, e2 = axis.cross(unit_z);
  const Vec3 v = rot.transpose() * (ball.velocity - point_velocity(cage, ball.position));
  const Vec3 w = rot.transpose() * (ball.angular_velocity - cage.angular_velocity);
  PocketMotion motion;
  motion.offset = {d.dot(e1), d.dot(e2)};
  motion.velocity = {v.dot(e1), v.dot(e2), v.dot(axis)};
  motion.angular_velocity = {w.dot(e1), w.dot(e2), w.dot(axis)};
  const PocketFilmForce f = evaluate_pocket_film(*s.film, motion);
  if (!f.valid) r.valid = false;
  const Vec3 force = rot * (f.force_on_ball[0] * e1 + f.force_on_ball[1] * e2 + f.force_on_ball[2] * axis);
  const Vec3 moment = rot * (f.moment_on_ball[0] * e1 + f.moment_on_ball[1] * e2 + f.moment_on_ball[2] * axis);
  apply_at_point(cage, ball, ball.position, force, moment, r);
  r.diagnostics.normal_force = f.pressure_force;
  r.diagnostics.power_loss = f.power_loss;
  r.diagnostics.film_thickness = f.minimum_film;
  r.diagnostics.traction_force = f.shear_force;
  r.diagnostics.circumferential_force = circumferential(ball.position, r.on_b.force);
}
}  // namespace

namespace {
/// The ball centre off the pocket centre (cylindrical: off its axis) in the cage frame.
struct PocketOffset {
  Vec3 axis;          ///< the radial pocket axis, cage frame
  Vec3 d;             ///< the offset
  double len;         ///< |d|
  double approach;    ///< len - clearance / 2
};
/// (cos a, sin a, 0), the radial axis of the pocket at cage-frame angle a. A pocket's angle is a
/// constant of its law, so this thread keeps the axes of the angles last asked for, by their bits
/// (direct-mapped): a hit returns the bits the evaluation would.
Vec3 pocket_axis(double angle) {
  struct Entry {
    std::uint64_t key = 0;
    double c = 0, s = 0;
    bool filled = false;
  };
  thread_local std::array<Entry, 64> memo{};
  const auto key = std::bit_cast<std::uint64_t>(angle);
  Entry& e = memo[(key * 0x9E3779B97F4A7C15ull) >> 58];
  if (!e.filled || e.key != key) e = {key, std::cos(angle), std::sin(angle), true};
  return {e.c, e.s, 0.0};
}

PocketOffset pocket_offset(const BallPocketSegment& s, const SpatialKinematics& cage, const Vec3& ball_position) {
  PocketOffset o;
  const Vec3 p = cage.rotation.transpose() * (ball_position - cage.position);  // cage frame
  o.axis = pocket_axis(s.pocket_angle);
  o.d = p - s.pitch_radius * o.axis;
  if (s.shape == PocketShape::cylindrical) o.d -= o.d.dot(o.axis) * o.axis;
  o.len = o.d.norm();
  o.approach = o.len - 0.5 * s.clearance;
  return o;
}
}  // namespace

double pocket_approach(const BallPocketSegment& s, const SpatialKinematics& cage, const Vec3& ball_position) {
  return pocket_offset(s, cage, ball_position).approach;
}

SpatialSegmentResult evaluate(const BallPocketSegment& s, const SpatialKinematics& cage,
                              const SpatialKinematics& ball) {
  SpatialSegmentResult r;
  const Mat3& rot = cage.rotation;
  const PocketOffset o = pocket_offset(s, cage, ball.position);
  const Vec3& axis = o.axis;
  const Vec3& d = o.d;
  const double len = o.len;
  const double approach = o.approach;
  r.diagnostics.approach = approach;
  if (!std::isfinite(approach)) return invalid_result(approach);
  if (s.film) add_pocket_film(s, cage, ball, axis, d, r);
  if (approach <= 0) {
    check_finite(r);
    return r;
  }

  const Vec3 n = rot * (d / len);  // from the ball centre into the cage (body 1)
  const Vec3 point = ball.position + s.ball_radius * n;
  const Vec3 v_rel = point_velocity(ball, point) - point_velocity(cage, point);
  const double approach_rate = n.dot(v_rel);
  const HertzPointContact hertz = s.normal.hertz.at(1.0);
  const HertzNormal normal =
      hertz_hunt_crossley(hertz.stiffness, s.normal.damping_factor, approach, approach_rate);
  r.valid = approach <= s.normal.max_approach;
  const double q = normal.force;

  const Vec3 slide = v_rel - approach_rate * n;  // tangential sliding of the ball on the cage
  const double speed = slide.norm();
  const double per_speed = friction_per_speed(s.friction, speed);
  const Vec3 friction = -(per_speed * q) * slide;
  const Vec3 f_ball = -q * n + friction;
  const double cbrt_q = std::cbrt(q);
  const double ab = hertz.a_coefficient * hertz.b_coefficient * cbrt_q * cbrt_q;
  const PointDiagnostics film = r.diagnostics;  // the film's share, added below
  const BallContact contact{
      .point = point, .force_on_ball = f_ball, .couple_on_ball = Vec3::Zero(), .normal_force = q,
      .max_pressure = q > 0 ? 1.5 * q / (std::numbers::pi * ab) : 0.0, .film_thickness = 0.0,
      .slip_velocity = speed, .spin_velocity = (ball.angular_velocity - cage.angular_velocity).dot(n),
      .traction_force = per_speed * q * speed, .elastic_energy = normal.elastic_energy,
      .power_loss = per_speed * q * speed * speed + normal.damping_power};
  finish_ball_contact(cage, ball, contact, r);
  if (s.film) {
    r.diagnostics.normal_force += film.normal_force;
    r.diagnostics.power_loss += film.power_loss;
    r.diagnostics.film_thickness = film.film_thickness;
    r.diagnostics.traction_force += film.traction_force;
    r.diagnostics.circumferential_force = circumferential(ball.position, r.on_b.force);
  }
  return r;
}

namespace {
/// Station j's strip of the land's film (land_film.hpp) on the cage (A) and the ring (B).
void add_land_film(const CageLandSegment3& s, int j, const SpatialKinematics& cage, const SpatialKinematics& ring,
                   const Vec3& station, const Vec3& q, SpatialSegmentResult& r) {
  const Vec3 arm = station - ring.position;
  const Vec3 q_rate = ring.rotation.transpose() *
                      (point_velocity(cage, station) - ring.velocity - ring.angular_velocity.cross(arm));
  const double spin = (cage.angular_velocity - ring.angular_velocity).dot(ring.rotation.col(2));
  const LandFilmStation f = land_film_station(*s.film, s.width, s.stations, j, s.outer_land, ring.rotation,
                                              ring.position, q, q_rate, spin);
  if (!f.valid) r.valid = false;
  apply_at_point(cage, ring, f.point, f.force_on_ring, f.couple_on_ring, r);
  r.diagnostics.normal_force += f.force_on_ring.norm();
  r.diagnostics.power_loss += f.power_loss;
  const double film = r.diagnostics.film_thickness;
  r.diagnostics.film_thickness = film > 0 ? std::min(film, f.minimum_film) : f.minimum_film;
}
}  // namespace

SpatialSegmentResult evaluate(const CageLandSegment3& s, const SpatialKinematics& cage,
                              const SpatialKinematics& ring) {
  SpatialSegmentResult r;
  const Mat3& rot = ring.rotation;
  const Vec3 cage_axis = cage.rotation.col(2);
  const Vec3 ring_axis = rot.col(2);
  const double side = s.outer_land ? 1.0 : -1.0;
  // Inner land: the cage bore (land + clearance) meets the land opposite to the eccentricity;
  // outer land: the cage's outside (land - clearance) meets the land bore on its side.
  const double cage_radius = s.outer_land ? s.land_radius - s.clearance : s.land_radius + s.clearance;
  if (s.stations < 1) return invalid_result(not_a_number);
  const double station_length = s.width / s.stations;

  double max_approach = -std::numeric_limits<double>::infinity(), max_force = 0;
  Vec3 friction_sum = Vec3::Zero();
  PointDiagnostics& dg = r.diagnostics;
  for (int j = 0; j < s.stations; ++j) {
    const double zeta = s.axial_offset + (j + 0.5) * station_length - 0.5 * s.width;
    const Vec3 station = cage.position + zeta * cage_axis;
    const Vec3 q = rot.transpose() * (station - ring.position);  // ring frame
    const double eccentricity = length(q.x(), q.y());
    const double approach = eccentricity - s.clearance;
    if (!std::isfinite(approach) || !std::isfinite(q.z())) return invalid_result(approach);
    max_approach = std::max(max_approach, approach);
    if (s.film) add_land_film(s, j, cage, ring, station, q, r);
    if (approach <= 0) continue;

    // Normal force on the ring (B) along u, the station's eccentricity direction (bearing frame);
    // contact point midway between the two surfaces on the radial line through u.
    const Vec3 u = rot * Vec3(q.x() / eccentricity, q.y() / eccentricity, 0.0);
    const double radial = 0.5 * (side * s.land_radius + eccentricity + side * cage_radius);
    const Vec3 point = ring.position + radial * u + q.z() * ring_axis;
    const Vec3 v_rel = point_velocity(ring, point) - point_velocity(cage, point);  // B on A
    const double approach_rate = -u.dot(v_rel);
    const NormalForce nf = evaluate_normal(s.law, approach, approach_rate);
    if (!nf.valid) r.valid = false;
    const Vec3 slide = v_rel + approach_rate * u;  // tangential part (axial and circumferential)
    const double speed = slide.norm();
    const double per_speed = friction_per_speed(s.friction, speed);
    const Vec3 friction = -(per_speed * nf.force) * slide;
    apply_at_point(cage, ring, point, nf.force * u + friction, Vec3::Zero(), r);

    friction_sum += friction;
    dg.normal_force += nf.force;
    dg.elastic_energy += nf.elastic_energy;
    dg.power_loss += per_speed * nf.force * speed * speed + nf.damping_power;
    if (nf.force > max_force) {  // the most loaded station gives slip, spin and pressure
      max_force = nf.force;
      dg.slip_velocity = speed;
      dg.spin_velocity = (ring.angular_velocity - cage.angular_velocity).dot(u);
    }
  }
  dg.approach = max_approach;
  if (max_force > 0) {
    // Line-contact Hertz estimate: p = sqrt(q E* / (pi R)), q the load per length, 1/R the relative
    // curvature of the conforming cylinders, E* from Palmgren's K of a station (palmgren_stiffness).
    const double e_reduced =
        s.law.stiffness / (palmgren_coefficient * std::pow(station_length, 8.0 / 9.0));
    const double curvature = std::abs(1.0 / s.land_radius - 1.0 / cage_radius);
    dg.max_pressure = std::sqrt(max_force / station_length * e_reduced * curvature / std::numbers::pi);
  }
  dg.traction_force = friction_sum.norm();
  check_finite(r);
  return r;
}

GrooveContactFrame groove_contact_frame(const BallGrooveSegment& s, const SpatialKinematics& ring,
                                        const SpatialKinematics& ball) {
  GrooveContactFrame f;
  const Mat3& rot = ring.rotation;
  const Vec3 rel = ball.position - ring.position;
  const Vec3 p = rot.transpose() * rel;
  const double rho = length(p.x(), p.y());
  if (!(rho > 0)) return f;
  const Vec3 e_r(p.x() / rho, p.y() / rho, 0.0);
  const double d_rad = rho - s.centre_radius, d_ax = p.z() - s.centre_axial, len = length(d_rad, d_ax);
  if (!(len > 0)) return f;
  f.n = rot * ((d_rad / len) * e_r + (d_ax / len) * unit_z);
  const Vec3 p_dot = rot.transpose() * (ball.velocity - ring.velocity - ring.angular_velocity.cross(rel));
  const double azimuth_rate = (p.x() * p_dot.y() - p.y() * p_dot.x()) / (rho * rho);
  f.rate = ring.angular_velocity + azimuth_rate * rot.col(2);
  f.valid = true;
  return f;
}

}  // namespace raceway::contact
