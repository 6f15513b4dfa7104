#include "contact/segments/roller_segments.hpp"

#include <cmath>

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
  return contact_at(s.law, s.traction, ring, roller, point, normal_on_roller, approach, perp(n));
}

SegmentResult evaluate(const CageBarSegment& s, const PlanarKinematics& cage,
                       const PlanarKinematics& roller) {
  const double angle = cage.theta + s.pocket_angle;
  const Vec2 radial{std::cos(angle), std::sin(angle)};
  const Vec2 tangential = perp(radial);
  const Vec2 pocket_centre = position(cage) + s.pitch_radius * radial;
  const double offset = dot(position(roller) - pocket_centre, tangential);
  const double approach = s.side * offset - s.half_clearance;
  const Vec2 outward = static_cast<double>(s.side) * tangential;  // from roller centre to the bar
  const Vec2 point = position(roller) + (s.roller_radius - 0.5 * approach) * outward;
  return contact_at(s.law, s.traction, cage, roller, point, -1.0 * outward, approach, radial);
}

SegmentResult evaluate(const CageLandSegment& s, const PlanarKinematics& cage,
                       const PlanarKinematics& ring) {
  const Vec2 e = position(cage) - position(ring);
  const double eccentricity = std::hypot(e.x, e.y);
  const double approach = eccentricity - s.clearance;
  if (!(approach > 0)) {
    SegmentResult r;
    r.diagnostics.approach = approach;
    r.valid = std::isfinite(approach);
    return r;
  }
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

}  // namespace raceway::contact
