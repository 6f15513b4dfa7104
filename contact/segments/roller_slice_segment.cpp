#include "contact/segments/roller_slice_segment.hpp"

#include <algorithm>
#include <cmath>

#include "contact/laws/damping.hpp"
#include "contact/laws/element_imperfections.hpp"

namespace raceway::contact {

namespace {

/// A conical race: approach, the normal on the roller and the contact point, in the ring frame.
struct RaceContact {
  double approach = 0;
  Vec3 normal_local, point_local;
};
RaceContact cone_contact(const RollerSliceSegment& s, const Vec3& local, double rho) {
  const double c = std::cos(s.race_angle), sn = std::sin(s.race_angle);
  const Vec3 n_race(c * local.x() / rho, c * local.y() / rho, -sn);
  const double d = (rho - s.race_radius) * c - local.z() * sn;
  const double reach = s.roller_radius - s.drop;
  RaceContact rc;
  rc.approach = s.outer ? reach + d : reach - d;
  rc.normal_local = s.outer ? Vec3(-n_race) : n_race;
  rc.point_local = local - d * n_race;
  return rc;
}

/// The slice's force on the roller at `point` (its reaction on the ring) and the diagnostics that
/// follow from it alone: the spin about the normal, the circumferential component.
void put_force(const Vec3& force, const Vec3& point, const Vec3& n, const SpatialKinematics& ring,
               const SpatialKinematics& roller, SpatialSegmentResult& out) {
  out.on_b.force = force;
  out.on_b.moment = (point - roller.position).cross(force);
  out.on_a.force = -force;
  out.on_a.moment = (point - ring.position).cross(-force);
  PointDiagnostics& d = out.diagnostics;
  d.spin_velocity = (roller.angular_velocity - ring.angular_velocity).dot(-n);
  const Vec3 e_r(roller.position.x(), roller.position.y(), 0.0);
  const double r = e_r.norm();
  d.circumferential_force = r > 0 ? force.dot(Vec3::UnitZ().cross(e_r / r)) : 0.0;
}

/// The relative motion at the contact point: B's velocity less A's, its tangent-plane part (the
/// slip) and the approach rate.
struct SliceMotion {
  Vec3 relative, slip;
  double approach_rate = 0;
};

/// The lubricated slice (the header's "Lubricated"): the film's force and traction into `out`.
/// `rolling` is the unit rolling direction t, `ring_speed` the ring surface's speed along it
/// relative to the contact point.
void ehd_slice(const RollerSliceSegment& s, const SpatialKinematics& ring, const SpatialKinematics& roller,
               const Vec3& n, const Vec3& point, double approach, const SliceMotion& v, const Vec3& rolling,
               double ring_speed, SpatialSegmentResult& out) {
  const EhdRaceFilm& film = *s.ehd;
  EhdLineLaw law = film.law;
  law.film.reduced_radius = 1.0 / (1.0 / s.roller_radius + (s.outer ? -1.0 : 1.0) / s.race_radius);
  const double entrainment = ring_speed + 0.5 * v.slip.dot(rolling);
  const EhdState st = evaluate_ehd(law, -approach, std::abs(entrainment));
  out.valid = out.valid && st.valid && std::isfinite(entrainment);
  if (st.force == 0 || !std::isfinite(st.force) || !std::isfinite(entrainment)) return;
  const double normal = std::max(0.0, st.force * (1.0 + film.damping_factor * v.approach_rate));
  Vec3 traction = tanh_slip_traction(s.traction.friction_coefficient, s.traction.slip_velocity_scale, normal, v.slip);
  double poiseuille = 0, rolling_sense = 0;
  if (film.traction) {
    const CouetteTraction& c = film.couette;
    traction = tanh_slip_traction(c.friction_coefficient, c.saturation_ratio * std::hypot(entrainment, c.speed_floor),
                                  normal, v.slip);
    poiseuille = law.film.length *
                 poiseuille_force_per_length(law.film, speed_parameter(law.film, std::abs(entrainment)), st.load_parameter);
    rolling_sense = std::tanh(entrainment / c.speed_floor);
  }
  const Vec3 force = normal * n + traction - (poiseuille * rolling_sense) * rolling;
  put_force(force, point, n, ring, roller, out);
  PointDiagnostics& d = out.diagnostics;
  d.normal_force = normal;
  d.film_thickness = st.film_thickness;
  d.slip_velocity = v.slip.norm();
  d.traction_force = (force - normal * n).norm();
  d.elastic_energy = law.stiffness * std::pow(st.deflection, palmgren_exponent + 1) / (palmgren_exponent + 1);
  d.power_loss = std::max(0.0, (normal - st.force) * v.approach_rate) - traction.dot(v.slip) +
                 poiseuille * std::abs(entrainment);
}

}  // namespace

RollerSliceSegment make_roller_slice_segment(const SlicedLineContact& c, std::size_t j, double race_radius,
                                             double roller_radius, bool outer, const TractionCurve& traction) {
  RollerSliceSegment s;
  s.race_radius = race_radius;
  s.roller_radius = roller_radius;
  s.outer = outer;
  s.position = c.slice_centre.at(j);
  s.drop = c.law.slice_drop.at(j);
  s.stiffness = c.law.slice_stiffness.at(j);
  s.damping_factor = c.law.damping_factor;
  s.max_approach = c.law.max_approach;
  s.traction = traction;
  return s;
}

SpatialSegmentResult evaluate(const RollerSliceSegment& s, const SpatialKinematics& ring,
                              const SpatialKinematics& roller) {
  SpatialSegmentResult out;
  if (!ring.all_finite() || !roller.all_finite()) {
    out.valid = false;
    return out;
  }
  const Vec3 centre = roller.position + s.position * roller.rotation.col(2);
  const Vec3 local = ring.rotation.transpose() * (centre - ring.position);
  const double rho = std::hypot(local.x(), local.y());
  if (!(rho > 0)) {
    out.valid = false;
    return out;
  }
  double approach = 0;
  Vec3 n, point;
  if (s.race_angle == 0) {
    const Vec3 radial_local(local.x() / rho, local.y() / rho, 0.0);
    const double reach = s.roller_radius - s.drop;
    approach = s.outer ? rho - (s.race_radius - reach) : s.race_radius + reach - rho;
    const Vec3 radial = ring.rotation * radial_local;
    n = s.outer ? Vec3(-radial) : radial;  // on the roller
    point = ring.position + ring.rotation * Vec3(s.race_radius * radial_local + local.z() * Vec3::UnitZ());
  } else {
    const RaceContact rc = cone_contact(s, local, rho);
    approach = rc.approach;
    n = ring.rotation * rc.normal_local;
    point = ring.position + ring.rotation * rc.point_local;
  }
  // The rate of S's azimuth about the ring's axis in the ring's frame (the imperfections' surfaces pass
  // under S, the film's contact point follows S): azimuth_moment / rho^2.
  double azimuth_moment = 0;
  if (s.imperfections || s.roller_imperfections || s.ehd) {
    const Vec3 centre_velocity = roller.velocity + roller.angular_velocity.cross(centre - roller.position);
    const Vec3 local_rate = ring.rotation.transpose() *
                            (centre_velocity - ring.velocity - ring.angular_velocity.cross(centre - ring.position));
    azimuth_moment = local.x() * local_rate.y() - local.y() * local_rate.x();
  }
  RaceHeight surface;
  if (s.imperfections) {
    surface = race_height(*s.imperfections, std::atan2(local.y(), local.x()) - ring.spin_angle, local.z());
    approach += surface.height;
  }
  ElementHeight own;
  if (s.roller_imperfections) {  // -n: from the roller's axis to the contact; n turns with S's azimuth
    own = roller_height(*s.roller_imperfections, roller.rotation, -n, s.position,
                        ring.angular_velocity + azimuth_moment / (rho * rho) * ring.rotation.col(2), roller.angular_velocity);
    approach += own.height;
  }
  out.diagnostics.approach = approach;
  // A film carries load before the surfaces meet, up to its cutoff gap.
  if (!(approach > (s.ehd ? -s.ehd->law.film.cutoff : 0.0))) return out;
  if (approach > s.max_approach) out.valid = false;

  const Vec3 v_ring = ring.velocity + ring.angular_velocity.cross(point - ring.position);
  const Vec3 v_roller = roller.velocity + roller.angular_velocity.cross(point - roller.position);
  const Vec3 relative = v_roller - v_ring;
  double approach_rate = -n.dot(relative);
  if (s.imperfections) approach_rate += surface.per_azimuth * azimuth_moment / (rho * rho);
  if (s.roller_imperfections) approach_rate += own.rate;
  if (s.ehd) {
    const Vec3 rolling = ring.rotation * Vec3(-local.y() / rho, local.x() / rho, 0.0);
    const SliceMotion motion{relative, relative - n.dot(relative) * n, approach_rate};
    ehd_slice(s, ring, roller, n, point, approach, motion, rolling, -s.race_radius * azimuth_moment / (rho * rho), out);
    return out;
  }

  const double elastic = s.stiffness * std::pow(approach, palmgren_exponent);
  const DampedForce q = hunt_crossley(elastic, s.damping_factor, approach_rate);
  const Vec3 slip = relative - n.dot(relative) * n;
  const double speed = slip.norm();
  const double mu = s.traction.friction_coefficient;
  const double scale = s.traction.slip_velocity_scale;
  const Vec3 traction = tanh_slip_traction(mu, scale, q.force, slip);
  const Vec3 force = q.force * n + traction;
  put_force(force, point, n, ring, roller, out);

  PointDiagnostics& d = out.diagnostics;
  d.normal_force = q.force;
  d.contact_angle = s.race_angle;  // the normal is the race's own: its angle to the radial plane
  d.slip_velocity = speed;
  d.traction_force = traction.norm();
  d.elastic_energy = elastic * approach / (palmgren_exponent + 1.0);
  d.power_loss = -traction.dot(slip) + q.damping_power;
  return out;
}

}  // namespace raceway::contact
