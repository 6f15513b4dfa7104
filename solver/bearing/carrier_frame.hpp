// The rotating carrier frame of a planetary bearing (seed 003 eq. 1-6): the bearing frame rides on a
// carrier that turns at psi'(t) about the sun axis, which lies at -R_c on the bearing frame's x axis.
// Positions, velocities and angular velocities of every body are relative to the bearing frame;
// the frame's inertial forces then join the contact forces in each body's equations:
//
//   m x'' = F_x + m (psi'' y + psi'^2 (R_c + x) + 2 psi' y')        (Euler, centrifugal, Coriolis)
//   m y'' = F_y - m (psi'' (R_c + x) - psi'^2 y + 2 psi' x')
//   I w'  = G_z - I psi''                                             (w relative to the frame)
//
// Seed 003 eq. 3 writes I phi'' = G_z with phi the absolute angle; with the relative angular
// velocity the Euler term -I psi'' appears instead (they agree when the carrier's speed is constant).
#pragma once

#include <array>
#include <optional>

#include "io/scene/scene.hpp"

namespace raceway::bearing {

struct CarrierFrame {
  double radius = 0;        ///< m, R_c
  double speed = 0;         ///< rad/s, psi'
  double acceleration = 0;  ///< rad/s^2, psi''

  /// The frame's inertial force on a mass at (x, y) moving at (vx, vy) in the bearing frame [N].
  std::array<double, 2> force(double mass, double x, double y, double vx, double vy) const {
    const double w2 = speed * speed;
    return {mass * (acceleration * y + w2 * (radius + x) + 2.0 * speed * vy),
            mass * (-acceleration * (radius + x) + w2 * y - 2.0 * speed * vx)};
  }
  /// Its derivatives per unit mass: d(force / m) / d(x, y, vx, vy), rows x then y.
  std::array<std::array<double, 4>, 2> force_derivative() const {
    const double w2 = speed * speed;
    return {{{w2, acceleration, 0.0, 2.0 * speed}, {-acceleration, w2, -2.0 * speed, 0.0}}};
  }
  /// The Euler moment on a body of axial inertia I [N m].
  double moment(double inertia) const { return -inertia * acceleration; }
  /// Potential of the centrifugal field [J]: with a constant carrier speed the kinetic energy
  /// relative to the frame plus this (the Jacobi integral) is conserved; Coriolis forces do no work.
  double potential(double mass, double x, double y) const {
    const double rx = radius + x;
    return -0.5 * mass * speed * speed * (rx * rx + y * y);
  }
};

/// The carrier frame at time t, or nullopt when the bearing frame is inertial.
inline std::optional<CarrierFrame> carrier_frame(const scene::CarrierSpec& carrier, double t) {
  if (!carrier.present) return std::nullopt;
  return CarrierFrame{carrier.radius, carrier.speed(t), carrier.speed.derivative(t)};
}

}  // namespace raceway::bearing
