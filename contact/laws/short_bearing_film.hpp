// The film of a short journal bearing: a cage riding on its guiding land (cage-land contact), a
// cylinder of radius R and axial width L in a bore of radial clearance c, both turning about the
// common axis, the journal's centre off the bore's by the eccentricity vector e (a plane
// perpendicular to the axis, any frame that does not turn). Rolling (the surfaces' rotation) and
// squeeze (de/dt) together, half-Sommerfeld (Guembel) cavitation, a continuous passage to the dry
// contact when the film collapses.
//
// Short-bearing Reynolds equation (Ocvirk; the axial pressure flow dominates when L << 2 pi R), with
// alpha the angle about the axis from the frame's x axis, x = R alpha, h = c - e_x cos(alpha) - e_y
// sin(alpha):
//   d/dz (h^3 dp/dz) = 6 mu (R omega_j + R omega_b) dh/dx + 12 mu dh/dt =: G(alpha),
//   p = 0 at z = +-L/2  ->  p = G (z^2 - L^2/4) / (2 h^3),  int p dz = -G L^3 / (12 h^3),
// so the film carries w(alpha) = max(0, -G) L^3 / (12 h^3) per unit length of the circumference
// (half-Sommerfeld: the negative half of the film cavitates). The pressure pushes the journal
// towards the centre, force on the journal -int w (cos alpha, sin alpha) R d(alpha), the opposite on
// the bore. Steady rotation gives Ocvirk's pi-film forces mu (omega_j + omega_b) R L^3 / c^2 times
// eps^2 / (1 - eps^2)^2 along e and pi eps / (4 (1 - eps^2)^(3/2)) across it (the tests check both).
//
// The integral over alpha is a fixed rule: `points` midpoints uniform in the Sommerfeld variable
// psi, alpha - beta = 2 atan(sqrt((1 - eps)/(1 + eps)) tan(psi / 2)) (beta the direction of e),
// dense where the film is thin, so that a nearly closed film is resolved with a few dozen points.
//
// Film collapse: the minimum film c - |e| is held above `film_floor` by a smooth maximum (as the
// roller/cage film has it), so the film's force stays bounded as the surfaces meet; the dry elastic
// contact of the overlap (the segment's own law) adds from zero at touch: the force passes
// continuously from film to dry contact at the critical film.
// Numerical integration here rather than a library: no Debian package has lubrication integrals;
// the closed forms it is checked against exist only for a centred rotation or a pure squeeze.
#pragma once

#include <array>

namespace raceway::contact {

struct ShortBearingFilm {
  double viscosity = 0;   ///< mu [Pa s]
  double radius = 0;      ///< R [m], the guiding surface's
  double width = 0;       ///< L [m], axial
  double clearance = 0;   ///< c [m], radial, centred
  double film_floor = 0;  ///< m: the smallest minimum film the film force sees (of the order of the roughness)
  int points = 64;        ///< quadrature points around the circumference
  /// L^3 of the pressure term [m^3]; 0: width^3. A strip [z1, z2] of a land of width L (the cage's
  /// stations) carries 6 int (L^2/4 - z^2) dz = 6 (L^2 (z2 - z1) / 4 - (z2^3 - z1^3) / 3) of it
  /// (strip_pressure_width_cubed): the strips of a land sum to L^3, its pressure profile being
  /// parabolic across the width; the Couette shear takes `width`, the strip's own.
  double pressure_width_cubed = 0;
};
/// The pressure's L^3 of the strip [z1, z2] (z from the land's centre) of a land of width L.
double strip_pressure_width_cubed(double land_width, double z1, double z2);

struct ShortBearingForce {
  std::array<double, 2> on_journal{};  ///< N, in the frame of e
  double minimum_film = 0;             ///< m, the floored minimum film
  double power_loss = 0;               ///< W, the squeeze's dissipation (>= 0) plus the Couette shear's
  double couette_torque = 0;           ///< N m on the journal about the axis (resists omega_j - omega_b)
  bool valid = true;
};

/// At eccentricity (e_x, e_y) and its rate, journal and bore angular speeds about the axis.
ShortBearingForce evaluate_short_bearing(const ShortBearingFilm& film, std::array<double, 2> eccentricity,
                                         std::array<double, 2> eccentricity_rate, double journal_speed,
                                         double bore_speed);

}  // namespace raceway::contact
