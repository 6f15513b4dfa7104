// The film of a ball in a cylindrical cage pocket (a pocket drilled radially: machined cages): a
// sphere of radius r_b in a cylinder of radius r_p = r_b + c (c the radial clearance), its centre off
// the cylinder's axis by the vector e (in the plane across the axis), rolling, sliding and squeezing
// at once, Reynolds' (Swift-Stieber) cavitation, and a continuous passage to the dry contact.
//
// Geometry. Pocket frame (e1, e2, a), a the cylinder's axis; alpha the angle about a from e1,
// n(alpha) = (cos, sin, 0), t(alpha) = (-sin, cos, 0), z along a from the ball's centre. The gap is
//   h(alpha, z) = h0(alpha) + z^2 / (2 r_b),   h0(alpha) = c - e . n(alpha),
// to first order in e / r_p and z / r_b. Around the pocket the gap changes over r_p alpha ~ r_p; along
// the axis over sqrt(2 r_b h0) against sqrt(2 R h0) around it (1/R = 1/r_b - 1/r_p): the pressure
// flows along the axis, its circumferential flow is of relative order r_b / R = c / r_p (the
// narrow-strip approximation, the converse of the short journal bearing's). Each strip alpha is then the rigid
// line film of a cylinder of radius r_b on a plane (reynolds_line_film.hpp), with
//   entrainment  u_z(alpha) = ((omega x r_b n) . a - v . a) / 2   (the ball's surface and the wall,
//                relative to the strip's thinnest film, which moves with the ball along the axis),
//   film rate    dh0/dt|eff = -v . n + (v_t / 2) d h0 / (r_p d alpha),
//                v_t = v . t + r_b omega . a (the ball's surface speed around the pocket: the
//                circumferential wedge acts on the strip as a squeeze),
// with v the ball centre's velocity and omega its angular velocity, both relative to the cage. Its
// load per unit length w(alpha) pushes the ball back along -n(alpha); the pressure's resultant,
// -int w n r_p d(alpha), passes through the ball's centre.
//
// Shear: the Couette stress eta v_slide / h of the ball's surface sliding on the wall, over a flooded
// pocket: each strip's int dz / h = pi sqrt(2 r_b / h0). Its force and moment about the ball's centre
// (the pressure-gradient shear, which gives a film's rolling resistance, is left out).
//
// The integral around the pocket is a fixed rule: `points` midpoints uniform in the Sommerfeld variable
// (dense where the film is thin), as the short journal bearing's, with the grid's eccentricity held
// below grid_eccentricity: near touch a separating or sliding ball's film carries its load on the
// thick side, which the film's own grid would leave with a few strips. Film collapse: the minimum film c - |e|
// is held above `film_floor` by a smooth maximum, so the film force stays bounded as the surfaces meet;
// the dry elastic contact of the segment adds from zero at touch (continuous at the critical film).
// Numerical integration here rather than a library: no Debian package has lubrication integrals.
#pragma once

#include <array>

namespace raceway::contact {

struct PocketFilm {
  double viscosity = 0;     ///< eta [Pa s]
  double ball_radius = 0;   ///< r_b [m]
  double clearance = 0;     ///< c [m], radial: pocket radius - ball radius
  double film_floor = 0;    ///< m: the smallest minimum film the film sees (of the order of the roughness)
  int points = 48;          ///< strips around the pocket
  /// The strips' Sommerfeld grid follows the film's eccentricity up to about this one (a smooth
  /// minimum): 48 strips are then within 0.3 % of 8192 on the film's own grid up to an eccentricity
  /// of 0.999 (the test's), where the grid of the film's own eccentricity leaves the thick side bare.
  double grid_eccentricity = 0.98;
  bool shear = true;        ///< add the Couette shear of the flooded pocket
};

/// The ball's motion relative to the cage, in the pocket frame (e1, e2, a).
struct PocketMotion {
  std::array<double, 2> offset{};       ///< e [m], the ball centre off the axis
  std::array<double, 3> velocity{};     ///< v [m/s], the ball centre's, relative to the cage
  std::array<double, 3> angular_velocity{};  ///< omega [rad/s], the ball's, relative to the cage
};

struct PocketFilmForce {
  std::array<double, 3> force_on_ball{};   ///< N, pocket frame, at the ball's centre (pressure and shear)
  std::array<double, 3> moment_on_ball{};  ///< N m about the ball's centre (shear)
  double pressure_force = 0;               ///< N, |the pressure's resultant|
  double shear_force = 0;                  ///< N, |the shear's resultant|
  double minimum_film = 0;                 ///< m, the floored minimum film
  double power_loss = 0;                   ///< W, the work rate the film takes from the bodies
  bool valid = true;
};

PocketFilmForce evaluate_pocket_film(const PocketFilm& film, const PocketMotion& motion);

}  // namespace raceway::contact
