// A rolling element's in-plane velocity in its orbital frame ([solver] element_velocity_frame =
// "orbital"; balls and planar rollers): the states svx, svy of a rolling element hold (v_r, v_theta),
// its velocity along e_r = (cos phi, sin phi, 0) and e_theta = (-sin phi, cos phi, 0) at its own
// angular position phi = atan2(y, x) about the bearing axis; svz stays vz and the positions stay
// Cartesian. The frame turns with the element, r phi' = v_theta, so the velocity states' rates carry
// the frame's turning terms:
//   v_r' = a_r + v_theta^2 / r,   v_theta' = a_theta - v_r v_theta / r   (r = sqrt(x^2 + y^2)).
// Why: CVODE's error weights are per state; in this frame the radial contact vibration and the
// orbital velocity (which the cage speed needs) have tolerances of their own
// (docs/integration_methods.md).
#pragma once

#include <cmath>

#include "contact/segments/ball_segments.hpp"

namespace raceway::bearing {

/// The orbital frame at the in-plane position (x, y): cos phi, sin phi and r.
struct OrbitalFrame {
  double c = 1, s = 0, r = 0;
  OrbitalFrame(double x, double y) : r(std::sqrt(x * x + y * y)) {  // (hypot: a few times dearer, and r is mm)
    const double inverse = 1.0 / r;
    c = x * inverse, s = y * inverse;
  }
  /// (v_r, v_theta, v_z) -> the bearing frame's (vx, vy, vz).
  contact::Vec3 to_bearing(const contact::Vec3& v) const { return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()}; }
  /// The bearing frame's (vx, vy, vz) -> (v_r, v_theta, v_z).
  contact::Vec3 to_orbital(const contact::Vec3& v) const { return {c * v.x() + s * v.y(), -s * v.x() + c * v.y(), v.z()}; }
  /// The states' rates (v_r', v_theta', v_z') from the acceleration (a_r, a_theta, a_z) at the
  /// orbital velocity v = (v_r, v_theta, v_z): the frame's turning terms added.
  contact::Vec3 velocity_rates(const contact::Vec3& a, const contact::Vec3& v) const {
    return {a.x() + v.y() * v.y() / r, a.y() - v.x() * v.y() / r, a.z()};
  }
  /// The inverse: the acceleration in the bearing frame from the states' rates.
  contact::Vec3 acceleration(const contact::Vec3& rates, const contact::Vec3& v) const {
    return to_bearing({rates.x() - v.y() * v.y() / r, rates.y() + v.x() * v.y() / r, rates.z()});
  }
};

}  // namespace raceway::bearing
