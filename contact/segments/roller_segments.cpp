#include "contact/segments/roller_segments.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace raceway::contact {
namespace {

struct Vec2 {
  double x, y;
};
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline Vec2 perp(Vec2 a) { return {-a.y, a.x}; }  // e_z x a
inline double norm_of(Vec2 a) { return std::hypot(a.x, a.y); }

inline Vec2 position(const PlanarKinematics& k) { return {k.x, k.y}; }
/// Velocity of the material point of body k at the spatial point c.
inline Vec2 point_velocity(const PlanarKinematics& k, Vec2 c) {
  return Vec2{k.vx, k.vy} + k.omega * perp(c - position(k));
}

/// The common tail of every segment: given the contact point, the unit direction of the normal
/// force on B, the approach and the sliding direction, apply the normal law and the traction curve
/// and distribute force and moment to both bodies (equal and opposite, at the same point).
SegmentResult contact_at(const LineContactLaw& law, const TractionCurve& traction,
                         const PlanarKinematics& a, const PlanarKinematics& b, Vec2 point,
                         Vec2 normal_on_b, double approach, Vec2 sliding_direction) {
  SegmentResult r;
  r.diagnostics.approach = approach;
  if (!std::isfinite(approach)) {
    r.valid = false;
    return r;
  }
  if (approach <= 0) return r;
  const Vec2 va = point_velocity(a, point);
  const Vec2 vb = point_velocity(b, point);
  const double approach_rate = -dot(vb - va, normal_on_b);
  const NormalForce n = evaluate_normal(law, approach, approach_rate);
  r.valid = n.valid;
  const double slip = dot(vb - va, sliding_direction);
  const double mu = traction.coefficient(slip);
  const double tangential = -mu * n.force;  // on B, along sliding_direction
  const Vec2 f_b = n.force * normal_on_b + tangential * sliding_direction;
  r.on_b = {f_b.x, f_b.y, cross(point - position(b), f_b)};
  r.on_a = {-f_b.x, -f_b.y, cross(point - position(a), Vec2{-f_b.x, -f_b.y})};
  r.diagnostics.normal_force = n.force;
  r.diagnostics.traction_force = tangential;
  r.diagnostics.slip_velocity = slip;
  r.diagnostics.elastic_energy = n.elastic_energy;
  r.diagnostics.power_loss = -tangential * slip + n.damping_power;
  return r;
}

/// The normal and tangential forces on B at `point`, equal and opposite on A.
void apply_at(SegmentResult& r, const PlanarKinematics& a, const PlanarKinematics& b, Vec2 point, Vec2 normal_on_b,
              double normal, double tangential, Vec2 tangent) {
  const Vec2 f_b = normal * normal_on_b + tangential * tangent;
  r.on_b = {f_b.x, f_b.y, cross(point - position(b), f_b)};
  r.on_a = {-f_b.x, -f_b.y, cross(point - position(a), Vec2{-f_b.x, -f_b.y})};
  r.diagnostics.normal_force = normal;
  r.diagnostics.traction_force = tangential;
}

/// Surface speeds along `tangent` of A and B at `point`, relative to the contact point, which
/// moves at `contact_velocity`: the entrainment speed u_m (their mean) and the slip (B - A).
struct SurfaceSpeeds {
  double entrainment, slip, approach_rate;
};
SurfaceSpeeds surface_speeds(const PlanarKinematics& a, const PlanarKinematics& b, Vec2 point, Vec2 normal_on_b,
                             Vec2 tangent, Vec2 contact_velocity) {
  const Vec2 va = point_velocity(a, point), vb = point_velocity(b, point);
  const double ua = dot(va - contact_velocity, tangent), ub = dot(vb - contact_velocity, tangent);
  return {0.5 * (ua + ub), ub - ua, -dot(vb - va, normal_on_b)};
}

/// The EHD roller-race contact (seed 003 2.2.2): film force, Couette and Poiseuille traction.
SegmentResult ehd_contact_at(const EhdRaceFilm& film, const TractionCurve& curve, const PlanarKinematics& a, const PlanarKinematics& b,
                             Vec2 point, Vec2 normal_on_b, double approach, Vec2 tangent, Vec2 contact_velocity) {
  SegmentResult r;
  r.diagnostics.approach = approach;
  const SurfaceSpeeds v = surface_speeds(a, b, point, normal_on_b, tangent, contact_velocity);
  const EhdState st = evaluate_ehd(film.law, -approach, std::abs(v.entrainment));
  r.valid = st.valid && std::isfinite(v.slip) && std::isfinite(v.approach_rate);
  // Beyond the validity limit the force is still applied (and flagged), as contact_at does.
  if (st.force == 0 || !std::isfinite(st.force) || !std::isfinite(v.slip)) return r;
  const double normal = std::max(0.0, st.force * (1.0 + film.damping_factor * v.approach_rate));
  double tangential = -curve.coefficient(v.slip) * normal, poiseuille = 0;  // without EHD traction
  if (film.traction) {
    tangential = -film.couette.coefficient(v.slip, v.entrainment) * normal;
    const double U = speed_parameter(film.law.film, std::abs(v.entrainment));
    poiseuille = film.law.film.length * poiseuille_force_per_length(film.law.film, U, st.load_parameter);
    tangential -= poiseuille * std::tanh(v.entrainment / film.couette.speed_floor);  // resists the rolling
  }
  apply_at(r, a, b, point, normal_on_b, normal, tangential, tangent);
  r.diagnostics.slip_velocity = v.slip;
  r.diagnostics.elastic_energy =
      film.law.stiffness * std::pow(st.deflection, palmgren_exponent + 1) / (palmgren_exponent + 1);
  r.diagnostics.power_loss = std::max(0.0, (normal - st.force) * v.approach_rate) +
                             std::abs((tangential + poiseuille * std::tanh(v.entrainment / film.couette.speed_floor)) *
                                      v.slip) +
                             poiseuille * std::abs(v.entrainment);
  return r;
}

/// The hydrodynamic roller-cage contact (seed 003 2.2.1): film (rolling and squeeze) and dry force,
/// the film's viscous drag and the traction curve on the dry force.
SegmentResult film_contact_at(const HydrodynamicLineLaw& law, const TractionCurve& traction, const PlanarKinematics& a,
                              const PlanarKinematics& b, Vec2 point, Vec2 normal_on_b, double approach, Vec2 tangent,
                              Vec2 contact_velocity) {
  SegmentResult r;
  r.diagnostics.approach = approach;
  const SurfaceSpeeds v = surface_speeds(a, b, point, normal_on_b, tangent, contact_velocity);
  const HydrodynamicForce h = evaluate_hydrodynamic(law, -approach, -v.approach_rate, v.entrainment);
  r.valid = h.valid && std::isfinite(v.slip);
  if (!std::isfinite(h.force) || !std::isfinite(v.slip) || (h.force == 0 && h.couette_force_per_speed == 0)) return r;
  const double dry_friction = traction.coefficient(v.slip) * h.dry.force;
  const double tangential = -(dry_friction + h.couette_force_per_speed * v.slip);
  apply_at(r, a, b, point, normal_on_b, h.force, tangential, tangent);
  r.diagnostics.slip_velocity = v.slip;
  r.diagnostics.elastic_energy = h.dry.elastic_energy;
  r.diagnostics.power_loss = -tangential * v.slip + h.dry.damping_power + h.film_force * std::max(0.0, v.approach_rate);
  return r;
}

}  // namespace

SegmentResult evaluate(const RollerRaceSegment& s, const PlanarKinematics& ring,
                       const PlanarKinematics& roller) {
  const Vec2 rel = position(roller) - position(ring);
  const double d = std::hypot(rel.x, rel.y);
  const Vec2 n = (1.0 / d) * rel;  // from ring centre towards the roller
  // Inner race: the roller rides outside the race; outer race: inside the bore.
  const double approach = s.internal ? d + s.roller_radius - s.race_radius
                                     : s.race_radius + s.roller_radius - d;
  const double roller_surface = s.internal ? d + s.roller_radius : d - s.roller_radius;
  const Vec2 point = position(ring) + (0.5 * (roller_surface + s.race_radius)) * n;
  const Vec2 normal_on_roller = s.internal ? -1.0 * n : n;
  if (s.ehd) {
    // The contact point turns with the roller about the ring centre.
    const Vec2 rel_velocity = Vec2{roller.vx - ring.vx, roller.vy - ring.vy};
    const double turn_rate = cross(n, rel_velocity) / d;
    const Vec2 contact_velocity = Vec2{ring.vx, ring.vy} + (turn_rate * norm_of(point - position(ring))) * perp(n);
    return ehd_contact_at(*s.ehd, s.traction, ring, roller, point, normal_on_roller, approach, perp(n), contact_velocity);
  }
  return contact_at(s.law, s.traction, ring, roller, point, normal_on_roller, approach, perp(n));
}

namespace {
/// The unit vector at `angle`. A pocket's two bars are evaluated one after the other at the same
/// angle: the second takes the first's cosine and sine (the same argument's bits, so the same
/// values), which halves the bars' trigonometry.
Vec2 unit_at(double angle) {
  struct Last {
    std::uint64_t key = 0;
    Vec2 unit{1, 0};
    bool filled = false;
  };
  thread_local Last last;
  const auto key = std::bit_cast<std::uint64_t>(angle);
  if (!last.filled || last.key != key) last = {key, Vec2{std::cos(angle), std::sin(angle)}, true};
  return last.unit;
}

/// The approach of a roller centred at `centre` to bar s of a cage at `cage` whose pocket points
/// along `radial`: what evaluate(CageBarSegment) and bar_approach share.
inline double bar_gap(const CageBarSegment& s, const PlanarKinematics& cage, Vec2 radial, Vec2 centre) {
  const Vec2 pocket_centre = position(cage) + s.pitch_radius * radial;
  const double offset = dot(centre - pocket_centre, perp(radial));
  return s.side * offset - s.half_clearance;
}
}  // namespace

double bar_approach(const CageBarSegment& s, const PlanarKinematics& cage, double roller_x, double roller_y) {
  return bar_gap(s, cage, unit_at(cage.theta + s.pocket_angle), Vec2{roller_x, roller_y});
}

SegmentResult evaluate(const CageBarSegment& s, const PlanarKinematics& cage,
                       const PlanarKinematics& roller) {
  const Vec2 radial = unit_at(cage.theta + s.pocket_angle);
  const Vec2 tangential = perp(radial);
  const double approach = bar_gap(s, cage, radial, position(roller));
  const Vec2 outward = static_cast<double>(s.side) * tangential;  // from roller centre to the bar
  const Vec2 point = position(roller) + (s.roller_radius - 0.5 * approach) * outward;
  if (s.film)  // the contact point moves with the roller along the bar
    return film_contact_at(*s.film, s.traction, cage, roller, point, -1.0 * outward, approach, radial,
                           Vec2{roller.vx, roller.vy});
  return contact_at(s.law, s.traction, cage, roller, point, -1.0 * outward, approach, radial);
}

namespace {
/// The land's short-bearing film on the cage (A) and the ring (B), added to r.
void add_land_film(const CageLandSegment& s, const PlanarKinematics& cage, const PlanarKinematics& ring, SegmentResult& r) {
  const double ex = cage.x - ring.x, ey = cage.y - ring.y;
  const double sign = s.outer_land ? 1.0 : -1.0;  // the journal's centre from the bore's: the cage's on an outer land
  const ShortBearingForce f =
      evaluate_short_bearing(*s.film, {sign * ex, sign * ey}, {sign * (cage.vx - ring.vx), sign * (cage.vy - ring.vy)},
                             s.outer_land ? cage.omega : ring.omega, s.outer_land ? ring.omega : cage.omega);
  if (!f.valid) r.valid = false;
  // On the ring: the journal's force and torque on an inner land (the ring is the journal), their
  // opposites on an outer one.
  const double to_ring = s.outer_land ? -1.0 : 1.0;
  const double fx = to_ring * f.on_journal[0], fy = to_ring * f.on_journal[1], torque = to_ring * f.couette_torque;
  // The force acts midway between the centres: its moment about either centre is (e/2) x F_ring.
  const double moment = 0.5 * (ex * fy - ey * fx);
  r.on_b.fx += fx, r.on_b.fy += fy, r.on_b.mz += moment + torque;
  r.on_a.fx -= fx, r.on_a.fy -= fy, r.on_a.mz += moment - torque;
  r.diagnostics.normal_force += std::hypot(fx, fy);
  r.diagnostics.power_loss += f.power_loss;
}

SegmentResult dry_land(const CageLandSegment& s, const PlanarKinematics& cage, const PlanarKinematics& ring,
                       const Vec2& e, double eccentricity, double approach) {
  const Vec2 n = (1.0 / eccentricity) * e;  // the cage is displaced along n
  // Inner land: the cage bore (radius land + clearance) meets the land on the side opposite to n.
  // Outer land: the cage outside (radius land - clearance) meets the land bore on the side of n.
  const double side = s.outer_land ? 1.0 : -1.0;
  const Vec2 land_point = position(ring) + (side * s.land_radius) * n;
  const double cage_radius = s.outer_land ? s.land_radius - s.clearance : s.land_radius + s.clearance;
  const Vec2 cage_point = position(cage) + (side * cage_radius) * n;
  const Vec2 point = 0.5 * (land_point + cage_point);
  // The land pushes the cage back towards the ring centre: force on the ring (B) is along +n.
  return contact_at(s.law, s.traction, cage, ring, point, n, approach, perp(n));
}
}  // namespace

SegmentResult evaluate(const CageLandSegment& s, const PlanarKinematics& cage,
                       const PlanarKinematics& ring) {
  const Vec2 e = position(cage) - position(ring);
  const double eccentricity = std::hypot(e.x, e.y);
  const double approach = eccentricity - s.clearance;
  SegmentResult r;
  if (approach > 0) {
    r = dry_land(s, cage, ring, e, eccentricity, approach);
  } else {
    r.diagnostics.approach = approach;
    r.valid = std::isfinite(approach);
  }
  if (s.film && std::isfinite(approach)) add_land_film(s, cage, ring, r);
  return r;
}

}  // namespace raceway::contact
