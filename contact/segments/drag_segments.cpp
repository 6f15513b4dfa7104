#include "contact/segments/drag_segments.hpp"

#include <cmath>

namespace raceway::contact {

SpatialSegmentResult evaluate(const BallDragSegment& s, const SpatialKinematics& a, const SpatialKinematics& b) {
  SpatialSegmentResult r;
  if (!a.all_finite() || !b.all_finite()) {
    r.valid = false;
    return r;
  }
  const Vec3 arm = b.position - a.position;
  const Vec3 relative = b.velocity - (a.velocity + a.angular_velocity.cross(arm));
  const SphereDrag drag = sphere_drag(s.mixture, s.ball_diameter, relative);
  r.on_b.force = drag.force;
  r.on_a.force = -drag.force;
  r.on_a.moment = arm.cross(-drag.force);
  const Vec3 e_theta = Vec3::UnitZ().cross(Vec3(b.position.x(), b.position.y(), 0.0)).normalized();
  r.diagnostics.slip_velocity = relative.norm();
  r.diagnostics.traction_force = drag.force.norm();
  r.diagnostics.circumferential_force = b.position.head<2>().squaredNorm() > 0 ? drag.force.dot(e_theta) : 0.0;
  r.diagnostics.power_loss = drag.power_loss;
  return r;
}

SpatialSegmentResult evaluate(const CageChurningSegment& s, const SpatialKinematics& a, const SpatialKinematics& b) {
  SpatialSegmentResult r;
  if (!a.all_finite() || !b.all_finite()) {
    r.valid = false;
    return r;
  }
  const Vec3 axis = b.rotation.col(2);
  const double relative_spin = (b.angular_velocity - a.angular_velocity).dot(axis);
  const double moment = ring_churning_moment(s.mixture, s.bore_radius, s.outside_radius, relative_spin);
  r.on_b.moment = moment * axis;
  r.on_a.moment = -moment * axis;
  r.diagnostics.spin_velocity = relative_spin;
  r.diagnostics.traction_force = std::abs(moment) / s.outside_radius;
  r.diagnostics.power_loss = -moment * relative_spin;
  return r;
}

}  // namespace raceway::contact
