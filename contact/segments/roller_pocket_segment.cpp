#include "contact/segments/roller_pocket_segment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "contact/laws/damping.hpp"

namespace raceway::contact {

RollerPocketBarSegment make_roller_pocket_bar_segment(double reduced_modulus, double bar_width, int slices,
                                                      double pitch_radius, double pocket_angle, double half_clearance,
                                                      double roller_radius, int side, double damping_factor,
                                                      double max_approach, const TractionCurve& traction) {
  if (slices < 1) throw std::invalid_argument("roller pocket bar: slices must be >= 1");
  if (!(bar_width > 0)) throw std::invalid_argument("roller pocket bar: the bar width must be positive");
  RollerPocketBarSegment s;
  s.pitch_radius = pitch_radius;
  s.pocket_angle = pocket_angle;
  s.half_clearance = half_clearance;
  s.roller_radius = roller_radius;
  s.side = side;
  const double width = bar_width / slices;
  for (int j = 0; j < slices; ++j) {
    // Mirror-symmetric centres bit for bit: the upper half mirrors the lower.
    const int k = j < slices - 1 - j ? j : slices - 1 - j;
    const double x = -0.5 * bar_width + (k + 0.5) * width;
    s.slice_position.push_back(k == j ? x : -x);
  }
  s.slice_stiffness = palmgren_stiffness(reduced_modulus, bar_width) / slices;
  s.damping_factor = damping_factor;
  s.max_approach = max_approach;
  s.traction = traction;
  return s;
}

SpatialSegmentResult evaluate(const RollerPocketBarSegment& s, const SpatialKinematics& cage,
                              const SpatialKinematics& roller) {
  SpatialSegmentResult out;
  if (!cage.all_finite() || !roller.all_finite()) {
    out.valid = false;
    return out;
  }
  const double ca = std::cos(s.pocket_angle), sa = std::sin(s.pocket_angle);
  const Vec3 radial = cage.rotation * Vec3(ca, sa, 0.0);
  const Vec3 tangential = cage.rotation * Vec3(-sa, ca, 0.0);
  const Vec3 pocket_centre = cage.position + s.pitch_radius * radial;
  const Vec3 axis = roller.rotation.col(2);
  const Vec3 outward = static_cast<double>(s.side) * tangential;  // from the roller's axis to the bar
  const Vec3 n = -outward;                                          // on the roller
  const double mu = s.traction.friction_coefficient, scale = s.traction.slip_velocity_scale;
  PointDiagnostics& d = out.diagnostics;
  d.approach = -std::numeric_limits<double>::infinity();
  double largest = 0;
  for (const double x : s.slice_position) {
    const Vec3 centre = roller.position + x * axis;
    const double approach = s.side * (centre - pocket_centre).dot(tangential) - s.half_clearance;
    d.approach = std::max(d.approach, approach);
    if (!(approach > 0)) continue;
    if (approach > s.max_approach) out.valid = false;
    const Vec3 point = centre + (s.roller_radius - 0.5 * approach) * outward;
    const Vec3 v_cage = cage.velocity + cage.angular_velocity.cross(point - cage.position);
    const Vec3 v_roller = roller.velocity + roller.angular_velocity.cross(point - roller.position);
    const Vec3 relative = v_roller - v_cage;
    const double elastic = s.slice_stiffness * std::pow(approach, palmgren_exponent);
    const DampedForce q = hunt_crossley(elastic, s.damping_factor, -n.dot(relative));
    const Vec3 slip = relative - n.dot(relative) * n;
    const double speed = slip.norm();
    const Vec3 traction = tanh_slip_traction(mu, scale, q.force, slip);
    const Vec3 force = q.force * n + traction;
    out.on_b.force += force;
    out.on_b.moment += (point - roller.position).cross(force);
    out.on_a.force -= force;
    out.on_a.moment += (point - cage.position).cross(-force);
    d.normal_force += q.force;
    d.traction_force += traction.norm();
    d.elastic_energy += elastic * approach / (palmgren_exponent + 1.0);
    d.power_loss += -traction.dot(slip) + q.damping_power;
    if (q.force > largest) {
      largest = q.force;
      d.slip_velocity = speed;
      d.spin_velocity = (roller.angular_velocity - cage.angular_velocity).dot(-n);
    }
  }
  if (!std::isfinite(d.approach)) out.valid = false;
  const Vec3 e_r(roller.position.x(), roller.position.y(), 0.0);
  const double r = e_r.norm();
  d.circumferential_force = r > 0 ? out.on_b.force.dot(Vec3::UnitZ().cross(e_r / r)) : 0.0;
  return out;
}

}  // namespace raceway::contact
